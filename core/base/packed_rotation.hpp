// A unit quaternion in seven bytes, for caches that keep a rotation as the reference of a
// tolerance (the separation cache, the body pair cache) and never rotate anything by it exactly.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "elan/math.hpp"

namespace elan::detail {

// The largest component of the unit quaternion is left out and made non-negative (q and -q are
// one rotation); it is at least 1/2, so it comes back from the unit norm as sqrt(1 - the others'
// squares), well conditioned (the "smallest three" of network codecs; leaving out w instead would
// lose half the digits near a half turn). The other three lie in [-1/sqrt 2, 1/sqrt 2] and are
// kept in 16 bits, to steps of 1/46340: each within 1.08e-5, 1.87e-5 together; the rebuilt one
// moves by at most |kept| / largest <= sqrt 3 times that, 3.24e-5; the quaternion by 3.74e-5 in
// all. Rotating by it instead of the exact one moves a point at radius r by at most twice that
// times r: kError bounds the factor.
//
// Bytes, not int16_t fields, so that it has alignment 1 and packs into the holder's last bytes.
struct PackedRotation {
  static constexpr Real kError = Real(1e-4);  // rad

  // The other three of (x, y, z, w), in that order, as little-endian int16; then which of
  // (x, y, z, w) is left out. The default is the identity.
  uint8_t bytes[7] = {0, 0, 0, 0, 0, 0, 3};

  // A kept component's step: 1/sqrt 2 maps to 32767.
  static constexpr Real kScale = Real(32767 * 1.41421356237309505);

  static PackedRotation pack(const Quat& q);
  // Inline: the collide stage unpacks one for every cached pair it checks.
  Quat unpack() const {
    Real kept[3];
    Real rest = 0;
    for (int k = 0; k < 3; ++k) {
      kept[k] = Real(kept_step(k));
      rest += kept[k] * kept[k];
    }
    rest /= kScale * kScale;
    Quat q;
    auto& c = q.coeffs();  // x, y, z, w
    for (int i = 0, k = 0; i < 4; ++i) {
      c[i] = i == bytes[6] ? std::sqrt(std::max(Real(0), 1 - rest)) : kept[k++] / kScale;
    }
    return q;
  }
  // Whether the bytes could have come from pack(): the left-out index is 0..3 and no kept
  // component is -32768, which pack() never writes.
  bool valid() const;

  bool operator==(const PackedRotation&) const = default;

 private:
  // Kept component k (0..2) in steps of 1/kScale.
  int16_t kept_step(int k) const {
    return int16_t(uint16_t(bytes[2 * k]) | uint16_t(bytes[2 * k + 1]) << 8);
  }
};
static_assert(sizeof(PackedRotation) == 7 && alignof(PackedRotation) == 1);

}  // namespace elan::detail
