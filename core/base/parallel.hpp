// SPDX-License-Identifier: MIT
// Deterministic parallel helpers over fixed blocks: the layout of work depends on the item count
// and a compile-time grain only, never on the thread count.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/grow.hpp"
#include "core/base/heap_bytes.hpp"
#include "core/base/step_scratch.hpp"
#include "core/base/tbb_hand_off.hpp"

namespace elan::detail {

inline constexpr std::size_t block_count(std::size_t count, std::size_t grain) {
  return (count + grain - 1) / grain;
}

// Calls f(begin, end, block) for every block [block*grain, min(count, (block+1)*grain)).
// determinism: block boundaries are a function of (count, grain) alone (rule 2), so a loop that
// writes only to slots it owns gives the same bits for any thread count.
template <class F>
void for_blocks(std::size_t count, std::size_t grain, F&& f) {
  const std::size_t blocks = block_count(count, grain);
  if (blocks == 0) return;
  if (blocks == 1) {
    f(std::size_t{0}, count, std::size_t{0});
    return;
  }
  TbbHandOff hand_off;
  hand_off.spawn(f);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, blocks, 1),
      [&](const tbb::blocked_range<std::size_t>& r) {
        TbbHandOff::TaskScope task(hand_off);
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
          f(b * grain, std::min(count, (b + 1) * grain), b);
        }
      },
      tbb::simple_partitioner());
  hand_off.joined();
}

// Per-thread scratch: the slots the current arena needs, and the calling thread's slot (a serial
// call from a thread TBB has not seen, whose index is negative, gets slot 0). Which thread takes
// which block changes from run to run, so nothing but capacity may depend on the slot.
inline std::size_t thread_slots() {
  return std::size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
}
inline std::size_t thread_slot() {
  const int thread = tbb::this_task_arena::current_thread_index();
  return thread < 0 ? 0 : std::size_t(thread);
}

// The largest capacity among per-thread buffers.
template <class T>
std::size_t largest_capacity(const std::vector<std::vector<T>>& buffers) {
  std::size_t largest = 0;
  for (const std::vector<T>& b : buffers) largest = std::max(largest, b.capacity());
  return largest;
}

// Per-thread buffers for the current arena (thread_slots()), emptied, each with room for exactly
// `room` entries (more is cut back). Which thread takes which block changes from run to run, so
// every buffer is given what the largest needs: none reallocates because the schedule changed.
template <class T>
void reset_thread_buffers(std::vector<std::vector<T>>& buffers, std::size_t room) {
  if (buffers.size() < thread_slots()) buffers.resize(thread_slots());
  for (std::vector<T>& b : buffers) {
    b.clear();
    if (b.capacity() > room) {
      cut_capacity(b, room);
    } else {
      b.reserve(room);
    }
  }
}

// Joins per-block outputs in block order into `out` (cleared first).
// determinism: rule 1, variable-length output is concatenated in block order.
template <class T, class A1, class A2>
void concat_blocks(const std::vector<std::vector<T, A1>>& blocks, std::vector<T, A2>& out) {
  std::size_t total = 0;
  for (const auto& b : blocks) total += b.size();
  out.clear();
  out.reserve(total);
  for (const auto& b : blocks) out.insert(out.end(), b.begin(), b.end());
}

// Per-(block, bin) counts, block-major (counts[block * bins + bin]), become exclusive offsets in
// bin-major, block-minor order: block b's items of a bin follow block b-1's, so a scatter that
// walks each block in order keeps block order within every bin (the determinism of a parallel
// counting sort). bin_start gets each bin's first offset and, at [bins], the total; `pad` free
// slots are left after every bin. Returns the total.
inline uint32_t bin_major_offsets(uint32_t* counts, std::size_t blocks, std::size_t bins,
                                  uint32_t* bin_start, uint32_t pad = 0) {
  uint32_t running = 0;
  for (std::size_t d = 0; d < bins; ++d) {
    bin_start[d] = running;
    for (std::size_t b = 0; b < blocks; ++b) {
      const uint32_t t = counts[b * bins + d];
      counts[b * bins + d] = running;
      running += t;
    }
    running += pad;
  }
  bin_start[bins] = running;
  return running;
}

// Reused buffers of sort_key_blocks / sort_keys, so a warm call allocates nothing. Given a step
// scratch, the sorts take the two large ones from it and give them back before returning.
struct KeySortScratch {
  ScratchVector<uint64_t> keys;                 // sort_keys: all the keys
  std::vector<ScratchVector<uint64_t>> bucket;  // sort_key_blocks: per thread, one bucket
  std::vector<uint32_t> counts;
};

inline std::size_t heap_bytes(const KeySortScratch& s) {
  return heap_bytes(s.keys) + heap_bytes(s.bucket) + heap_bytes(s.counts);
}

// Parallel sort of 64-bit keys, every key <= max_key: an MSD pass on the top 8 bits below
// max_key's width scatters block by block into 256 buckets, then each bucket is sorted alone.
// Integer keys that compare equal are equal, so the output is a function of the input multiset
// alone, whatever the thread count.
// sort_key_blocks writes the keys of all `blocks`, sorted, to `out`, scattering them there
// directly (a thread's scratch holds one bucket at a time); sort_keys sorts in place, through a
// scratch copy of all the keys.
// `out` is a std::vector or a ScratchVector of keys (the world's pair list lives in the step's
// scratch); a smaller one grows to exactly the keys' count.
template <class Keys>
void sort_key_blocks(const std::vector<ScratchVector<uint64_t>>& blocks, uint64_t max_key,
                     Keys& out, KeySortScratch& scratch, StepScratch* step_scratch = nullptr);
void sort_keys(std::span<uint64_t> keys, uint64_t max_key, KeySortScratch& scratch,
               StepScratch* step_scratch = nullptr);

}  // namespace elan::detail
