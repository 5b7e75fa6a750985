// Radix sort for the pair and contact keys.
#include "core/base/parallel.hpp"

#include <array>

namespace elan::detail {

void radix_sort(std::vector<uint64_t>& keys, std::vector<uint64_t>& scratch) {
  const std::size_t n = keys.size();
  if (n < 64) {
    std::sort(keys.begin(), keys.end());
    return;
  }
  scratch.resize(n);
  uint64_t all_or = 0, all_and = ~uint64_t{0};
  for (uint64_t k : keys) {
    all_or |= k;
    all_and &= k;
  }
  const uint64_t varying = all_or ^ all_and;
  uint64_t* src = keys.data();
  uint64_t* dst = scratch.data();
  for (int shift = 0; shift < 64; shift += 16) {
    if (((varying >> shift) & 0xFFFF) == 0) continue;
    std::array<uint32_t, 65536> count{};
    for (std::size_t i = 0; i < n; ++i) ++count[(src[i] >> shift) & 0xFFFF];
    uint32_t sum = 0;
    for (auto& c : count) {
      const uint32_t t = c;
      c = sum;
      sum += t;
    }
    for (std::size_t i = 0; i < n; ++i) dst[count[(src[i] >> shift) & 0xFFFF]++] = src[i];
    std::swap(src, dst);
  }
  if (src != keys.data()) std::copy(src, src + n, keys.data());
}

}  // namespace elan::detail
