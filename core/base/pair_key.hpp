// SPDX-License-Identifier: MIT
// Pair keys: (a, b) with a < b packed in one 64-bit integer, so sorting keys sorts pairs.
#pragma once

#include <cstdint>
#include <utility>

namespace elan::detail {

inline constexpr uint64_t make_pair_key(uint32_t a, uint32_t b) {
  return a < b ? (uint64_t{a} << 32) | b : (uint64_t{b} << 32) | a;
}
inline constexpr uint32_t pair_first(uint64_t key) {
  return uint32_t(key >> 32);
}
inline constexpr uint32_t pair_second(uint64_t key) {
  return uint32_t(key & 0xFFFFFFFFu);
}

}  // namespace elan::detail
