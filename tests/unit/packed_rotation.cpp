// SPDX-License-Identifier: MIT
// The smallest-three rotation codec of the separation and body pair caches: its error bound, and
// which bytes a snapshot reader must refuse.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/base/packed_rotation.hpp"

namespace elan::detail {
namespace packed_rotation_test {

TEST(PackedRotation, ComesBackWithinItsErrorBound) {
  // Three components kept in 16 bits, the largest rebuilt from the unit norm: it is at least 1/2,
  // so its square root is well conditioned, near a half turn too (w near 0), where rebuilding w
  // would lose half the digits. The quaternion comes back within 3.74e-5 (packed_rotation.hpp), so
  // any point turned by it within twice that times its radius, up to the sign of the whole.
  std::mt19937 rng(9);
  std::normal_distribution<float> n(0, 1);
  Real worst = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Quat q{n(rng), n(rng), n(rng), n(rng)};
    if (trial % 4 == 1) q.w() = Real(1e-4) * n(rng);  // near a half turn
    if (trial % 4 == 2) q.coeffs()[trial % 3] = 0;    // an exact zero among the kept
    q.normalize();
    const PackedRotation packed = PackedRotation::pack(q);
    ASSERT_TRUE(packed.valid());
    const Quat r = packed.unpack();
    const Real sign = q.dot(r) < 0 ? Real(-1) : Real(1);
    const Real error = (q.coeffs() - sign * r.coeffs()).norm();
    worst = std::max(worst, error);
    const Vec3 point{n(rng), n(rng), n(rng)};
    EXPECT_LE((q * point - r * point).norm(), PackedRotation::kError * point.norm())
        << "trial " << trial;
    if (HasFailure()) return;
  }
  EXPECT_LE(worst, Real(3.74e-5));
  // The steps are what they say: not far below the bound either (a bound that cannot be
  // approached would hide a coarser encoding than the comment claims).
  EXPECT_GT(worst, Real(1e-5));
}

TEST(PackedRotation, IdentityByDefaultAndBytesPackNeverWritesAreInvalid) {
  EXPECT_EQ(PackedRotation().unpack().coeffs(), Quat::Identity().coeffs());
  EXPECT_EQ(PackedRotation::pack(Quat::Identity()), PackedRotation());
  PackedRotation p = PackedRotation::pack(Quat(Real(0.5), Real(-0.5), Real(0.5), Real(-0.5)));
  EXPECT_TRUE(p.valid());
  p.bytes[6] = 4;  // no fifth component
  EXPECT_FALSE(p.valid());
  p.bytes[6] = 0;
  p.bytes[2] = 0x00;  // kept component -32768: pack() clamps to +-32767
  p.bytes[3] = 0x80;
  EXPECT_FALSE(p.valid());
}

}  // namespace packed_rotation_test
}  // namespace elan::detail
