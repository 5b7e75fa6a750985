// SPDX-License-Identifier: MIT
// State hash: a word-at-a-time multiply-xorshift mix (the finaliser of SplitMix64 / Stafford's
// Mix13), fast enough to run every step for recordings.
#include "core/base/state_hash.hpp"
#include "core/base/splitmix.hpp"

#include <cstring>

namespace elan::detail {

namespace {
inline uint64_t mix(uint64_t h, uint64_t w) {
  h ^= w + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  return splitmix64_finalize(h);
}
inline uint64_t bits(Real x) {
  if constexpr (sizeof(Real) == 8) {
    uint64_t u;
    std::memcpy(&u, &x, 8);
    return u;
  } else {
    uint32_t u;
    std::memcpy(&u, &x, 4);
    return u;
  }
}
}  // namespace

uint64_t hash_bodies(const BodyStore& b) {
  uint64_t h = 0x656C616E00000000ull ^ b.size();
  for (std::size_t i = 0; i < b.size(); ++i) {
    const Real v[13] = {b.px[i], b.py[i], b.pz[i], b.qw[i], b.qx[i], b.qy[i], b.qz[i],
                        b.vx[i], b.vy[i], b.vz[i], b.wx[i], b.wy[i], b.wz[i]};
    for (Real x : v) h = mix(h, bits(x));
  }
  return h;
}

}  // namespace elan::detail
