// SPDX-License-Identifier: MIT
// Sizing of the buffers a step rebuilds: they keep their capacity from step to step, so once a
// scene has run a while a step allocates nothing.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace elan::detail {

// The room a buffer that must hold n grows to: a quarter past n, and at least kGrowFloor past it.
// A count that creeps up step by step (a settling pile's pairs) would otherwise reallocate at
// every new high, and doubling would leave up to half of it unused for good. The floor is for
// small counts, whose quarter is a few entries that a scene's ordinary wander passes.
inline constexpr std::size_t kGrowFloor = 64;
inline std::size_t grown_room(std::size_t n) {
  return n + std::max(n / 4, kGrowFloor);
}

// Resizes `v` to n, growing it to grown_room(n) when it must grow.
template <class V>
void grow_to(V& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(grown_room(n));
  v.resize(n);
}

// As grow_to, every element set to `value`.
template <class V, class T>
void grow_fill(V& v, std::size_t n, const T& value) {
  if (n > v.capacity()) v.reserve(grown_room(n));
  v.assign(n, value);
}

// Hands back what a passing spike left in a buffer that otherwise keeps its capacity: the first
// steps of a pile, when every pair is new and boxes span more strips, leave the collide stage's
// new-key buffers many times larger than a settled pile uses and the sweep's entries about twice
// as large. Counted over windows of kWindow steps, so a buffer whose use swings from step to step
// is never cut and regrown in turn: one whose capacity exceeds twice the last window's high (plus
// kFloorBytes) is cut to a quarter past that high, at most once a window. Memory only: no result
// depends on a capacity.
class SpikeTrim {
 public:
  static constexpr uint32_t kWindow = 64;
  static constexpr std::size_t kFloorBytes = 64 * 1024;

  // Records one step's use of a buffer that now holds `capacity` elements of `element_bytes`
  // each. Returns the capacity to cut it to, or 0 to leave it.
  std::size_t note(std::size_t used, std::size_t capacity, std::size_t element_bytes) {
    high_ = std::max(high_, used);
    if (++steps_ < kWindow) return 0;
    const std::size_t keep = std::max<std::size_t>(high_ + high_ / 4, 1);  // 0 would mean leave it
    high_ = 0;
    steps_ = 0;
    return capacity > 2 * keep + kFloorBytes / element_bytes ? keep : 0;
  }

 private:
  std::size_t high_ = 0;
  uint32_t steps_ = 0;
};

// Reallocates `v` at `capacity` (at least its size), contents kept.
template <class V>
void cut_capacity(V& v, std::size_t capacity) {
  V kept(v.get_allocator());
  kept.reserve(std::max(capacity, v.size()));
  kept.assign(v.begin(), v.end());
  v.swap(kept);
}

// Notes this step's use of `v` with `trim`, and cuts its capacity when the rule says so.
template <class V>
void trim_spike(V& v, SpikeTrim& trim) {
  const std::size_t cut = trim.note(v.size(), v.capacity(), sizeof(typename V::value_type));
  if (cut != 0) cut_capacity(v, cut);
}

}  // namespace elan::detail
