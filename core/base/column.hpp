// SPDX-License-Identifier: MIT
// Column<T>: one aligned, growable array of a structure-of-arrays store.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

namespace elan::detail {

// perf: 64-byte alignment puts every column on a cache line and lets SIMD loads be aligned.
inline constexpr std::size_t kColumnAlign = 64;

template <class T>
struct AlignedAllocator {
  using value_type = T;
  AlignedAllocator() = default;
  template <class U>
  AlignedAllocator(const AlignedAllocator<U>&) {}
  T* allocate(std::size_t n) {
    void* p = ::operator new(n * sizeof(T), std::align_val_t(kColumnAlign));
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t(kColumnAlign)); }
  template <class U>
  bool operator==(const AlignedAllocator<U>&) const {
    return true;
  }
};

template <class T>
using Column = std::vector<T, AlignedAllocator<T>>;

}  // namespace elan::detail
