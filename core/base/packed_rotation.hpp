// SPDX-License-Identifier: MIT
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
  // perf: built in registers, one case per left-out component. Written into the coefficients
  // one by one, it was stored to the stack and read back as a vector, a failed store-to-load
  // forward that waits for every older store to commit; at 2 threads those include stores to
  // manifolds the other core last wrote, so this one load stalled the collide stage.
  Quat unpack() const { return unpack(bytes, bytes[6]); }
  // The same from the six bytes of the kept components and the left-out index kept apart (the
  // separation cache keeps the index in spare bits).
  static Quat unpack(const uint8_t kept[6], int left_out) {
    const Real a = Real(kept_step(kept, 0)), b = Real(kept_step(kept, 1));
    const Real c = Real(kept_step(kept, 2));
    Real rest = a * a;
    rest += b * b;
    rest += c * c;
    rest /= kScale * kScale;
    const Real big = std::sqrt(std::max(Real(0), 1 - rest));
    const Real x = a / kScale, y = b / kScale, z = c / kScale;
    switch (left_out) {  // Quat(w, x, y, z)
      case 0:
        return Quat(z, big, x, y);
      case 1:
        return Quat(z, x, big, y);
      case 2:
        return Quat(z, x, y, big);
      default:
        return Quat(big, x, y, z);
    }
  }
  // Whether the bytes could have come from pack(): the left-out index is 0..3 and no kept
  // component is -32768, which pack() never writes.
  bool valid() const;

  bool operator==(const PackedRotation&) const = default;

 private:
  // Kept component k (0..2) in steps of 1/kScale.
  static int16_t kept_step(const uint8_t kept[6], int k) {
    return int16_t(uint16_t(kept[2 * k]) | uint16_t(kept[2 * k + 1]) << 8);
  }
};
static_assert(sizeof(PackedRotation) == 7 && alignof(PackedRotation) == 1);

}  // namespace elan::detail
