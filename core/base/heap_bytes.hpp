// SPDX-License-Identifier: MIT
// heap_bytes(): the bytes a container holds on the heap (its capacity, not its size: what the
// allocator keeps after a step, which is what the memory report counts). Allocator overhead is
// not included.
#pragma once

#include <cstddef>
#include <vector>

namespace elan::detail {

template <class T, class A>
std::size_t heap_bytes(const std::vector<T, A>& v) {
  return v.capacity() * sizeof(T);
}

// A vector of vectors: the outer array and every inner one.
template <class T, class A, class B>
std::size_t heap_bytes(const std::vector<std::vector<T, A>, B>& v) {
  std::size_t bytes = v.capacity() * sizeof(std::vector<T, A>);
  for (const auto& inner : v) bytes += heap_bytes(inner);
  return bytes;
}

}  // namespace elan::detail
