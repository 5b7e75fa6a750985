// SPDX-License-Identifier: MIT
// The smallest-three rotation codec (see packed_rotation.hpp).
#include "core/base/packed_rotation.hpp"

#include <algorithm>
#include <cmath>

namespace elan::detail {

PackedRotation PackedRotation::pack(const Quat& q) {
  const auto& c = q.coeffs();  // x, y, z, w
  int largest = 3;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(c[i]) > std::abs(c[largest])) largest = i;
  }
  // The three kept, in (x, y, z, w) order, for each left-out index.
  static constexpr int kKept[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  const Real scale = c[largest] < 0 ? -kScale : kScale;
  PackedRotation p;
  p.bytes[6] = uint8_t(largest);
  for (int k = 0; k < 3; ++k) {
    // lrint, to nearest (ties to even): one instruction, where lround is a library call, and the
    // collide stage packs a rotation for every touching exact test of a pair it may reuse.
    const long step = std::clamp(std::lrint(c[kKept[largest][k]] * scale), -32767L, 32767L);
    const auto bits = uint16_t(int16_t(step));
    p.bytes[2 * k] = uint8_t(bits & 0xFF);
    p.bytes[2 * k + 1] = uint8_t(bits >> 8);
  }
  return p;
}

bool PackedRotation::valid() const {
  if (bytes[6] > 3) return false;
  for (int k = 0; k < 3; ++k) {
    if (kept_step(bytes, k) == INT16_MIN) return false;
  }
  return true;
}

}  // namespace elan::detail
