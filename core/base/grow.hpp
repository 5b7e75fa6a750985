// Sizing of the buffers a step rebuilds: they keep their capacity from step to step, so once a
// scene has run a while a step allocates nothing.
#pragma once

#include <cstddef>

namespace elan::detail {

// Resizes `v` to n, growing it by a quarter past n when it must grow: a count that creeps up
// step by step (a settling pile's pairs) would otherwise reallocate at every new high, and
// doubling would leave up to half of it unused for good.
template <class V>
void grow_to(V& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(n + n / 4);
  v.resize(n);
}

// As grow_to, every element set to `value`.
template <class V, class T>
void grow_fill(V& v, std::size_t n, const T& value) {
  if (n > v.capacity()) v.reserve(n + n / 4);
  v.assign(n, value);
}

}  // namespace elan::detail
