// SPDX-License-Identifier: MIT
// The finaliser of SplitMix64 (Steele, Lea and Flood 2014; Stafford's Mix13): a bijection of 64-bit
// words whose every output bit depends on every input bit, so that neighbouring inputs (pair keys,
// packed feature words, a hash's running state) get unrelated outputs.
#pragma once

#include <cstdint>

namespace elan::detail {

inline uint64_t splitmix64_finalize(uint64_t h) {
  h ^= h >> 30;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 27;
  h *= 0x94D049BB133111EBull;
  h ^= h >> 31;
  return h;
}

}  // namespace elan::detail
