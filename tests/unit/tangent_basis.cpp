// SPDX-License-Identifier: MIT
// The friction rows' tangent basis (Duff et al. 2017): orthonormal and right-handed for every unit
// normal, the axes and the branch's edge (n.z = 0, either sign of zero) included, and the carrying
// of a friction impulse from one normal's basis to another's.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/base/contact.hpp"

namespace elan::detail {
namespace tangent_basis_test {

// Float rounding of a handful of products and one division: a few ulp of 1.
constexpr Real kTolerance = Real(1e-6);

void expect_orthonormal(const Vec3& n) {
  Vec3 t1, t2;
  tangent_basis(n, t1, t2);
  EXPECT_NEAR(t1.norm(), 1, kTolerance) << n.transpose();
  EXPECT_NEAR(t2.norm(), 1, kTolerance) << n.transpose();
  EXPECT_NEAR(t1.dot(n), 0, kTolerance) << n.transpose();
  EXPECT_NEAR(t2.dot(n), 0, kTolerance) << n.transpose();
  EXPECT_NEAR(t1.dot(t2), 0, kTolerance) << n.transpose();
  // Right-handed: t2 = n x t1, as the solver's rows assume.
  EXPECT_LE((n.cross(t1) - t2).norm(), 2 * kTolerance) << n.transpose();
}

TEST(TangentBasis, OrthonormalAndRightHandedForEveryNormal) {
  std::vector<Vec3> normals = {Vec3(1, 0, 0),          Vec3(-1, 0, 0),        Vec3(0, 1, 0),
                               Vec3(0, -1, 0),         Vec3(0, 0, 1),         Vec3(0, 0, -1),
                               Vec3(0, 1, Real(-0.0)), Vec3(1, 0, Real(-0.0))};
  std::mt19937 rng(4);
  std::normal_distribution<float> g(0, 1);
  for (int i = 0; i < 20000; ++i) {
    Vec3 n{g(rng), g(rng), g(rng)};
    if (i % 4 == 1) n.z() = Real(1e-7) * g(rng);  // beside the sign switch
    if (i % 4 == 2) n = Vec3{Real(1e-4) * g(rng), Real(1e-4) * g(rng), -1};  // near -z
    normals.push_back(n.normalized());
  }
  for (const Vec3& n : normals) {
    expect_orthonormal(n);
    if (HasFailure()) return;
  }
}

TEST(TangentBasis, SameNormalSameBits) {
  const Vec3 n = Vec3(Real(0.3), Real(-0.8), Real(0.2)).normalized();
  Vec3 a1, a2, b1, b2;
  tangent_basis(n, a1, a2);
  tangent_basis(n, b1, b2);
  EXPECT_EQ(a1, b1);
  EXPECT_EQ(a2, b2);
}

TEST(TangentBasis, CarriedImpulseIsTheWorldImpulseProjected) {
  // Across the basis's switch (n.z from just below zero to just above) the two numbers change but
  // the world impulse does not; onto a turned normal it is projected into the new plane.
  const Vec3 below = Vec3(1, Real(0.1), Real(-1e-6)).normalized();
  const Vec3 above = Vec3(1, Real(0.1), Real(1e-6)).normalized();
  const Real old_t[2] = {Real(2.5), Real(-1.5)};
  Vec3 a1, a2, b1, b2;
  tangent_basis(below, a1, a2);
  tangent_basis(above, b1, b2);
  EXPECT_GT((a1 - b1).norm(), 1) << "the bases should differ across the switch";
  Real new_t[2];
  carry_tangent_impulse(below, old_t, above, new_t);
  const Vec3 before = old_t[0] * a1 + old_t[1] * a2;
  const Vec3 after = new_t[0] * b1 + new_t[1] * b2;
  EXPECT_LE((before - after).norm(), Real(1e-5));

  const Vec3 turned = Vec3(1, Real(0.5), 0).normalized();
  carry_tangent_impulse(below, old_t, turned, new_t);
  tangent_basis(turned, b1, b2);
  const Vec3 projected = before - before.dot(turned) * turned;
  EXPECT_LE((new_t[0] * b1 + new_t[1] * b2 - projected).norm(), Real(1e-5));
}

}  // namespace tangent_basis_test
}  // namespace elan::detail
