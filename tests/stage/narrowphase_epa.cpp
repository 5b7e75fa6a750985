// SPDX-License-Identifier: MIT
// EPA penetration depth, normal and witness points against closed forms and an exact SAT oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "narrowphase/gjk.hpp"
#include "narrowphase_oracle.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_epa_test {

using test::at;
using test::axis_angle;
using test::box;
using test::capsule;
using test::cylinder;
using test::sphere;

// EPA stops at a relative gap of 1e-5 (float); boxes and cores are polytopes, so the answer is
// exact up to rounding.
constexpr double kTol = sizeof(Real) == 4 ? 1e-4 : 1e-8;

void expect_finite_unit(const EpaResult& e) {
  EXPECT_TRUE(std::isfinite(e.depth));
  EXPECT_TRUE(e.point_a.allFinite());
  EXPECT_TRUE(e.point_b.allFinite());
  EXPECT_NEAR(e.normal.norm(), 1, 1e-5);
}

TEST(Epa, OverlappingSpheresMatchClosedForm) {
  const Shape a = sphere(0.5), b = sphere(0.7);
  const Vec3 d = Vec3(0.3, 0.6, -0.2);
  const EpaResult e = epa_penetration(a, at(1, 1, 1), b, at(1 + d.x(), 1 + d.y(), 1 + d.z()));
  ASSERT_TRUE(e.ok);
  EXPECT_NEAR(e.depth, 1.2 - d.norm(), kTol);
  EXPECT_TRUE(e.normal.isApprox(d.normalized(), Real(1e-5)));
  EXPECT_TRUE(e.point_a.isApprox(Vec3(1, 1, 1) + Real(0.5) * d.normalized(), Real(1e-5)));
  EXPECT_NEAR((e.point_a - e.point_b).dot(e.normal), e.depth, kTol);
}

TEST(Epa, BoxFaceContactMatchesClosedForm) {
  const Shape a = box(1, 1, 1), b = box(0.5, 2, 1.5);
  // Overlap 0.2 along x is the least; along y and z it is several units.
  const EpaResult e = epa_penetration(a, at(0, 0, 0), b, at(1.3, 0.4, -0.3));
  ASSERT_TRUE(e.ok);
  EXPECT_NEAR(e.depth, 0.2, kTol);
  EXPECT_TRUE(e.normal.isApprox(Vec3::UnitX(), Real(1e-5)));
  EXPECT_NEAR(e.point_a.x(), 1, kTol);
  EXPECT_NEAR(e.point_b.x(), 0.8, kTol);
  // Rotated frame: the same contact seen after turning both bodies.
  const Quat q(Eigen::AngleAxis<Real>(Real(0.7), Vec3(1, 2, -1).normalized()));
  const EpaResult r = epa_penetration(a, at(0, 0, 0, q), b, at(0, 0, 0, q));
  ASSERT_TRUE(r.ok);
  const EpaResult s = epa_penetration(a, at(2, 3, 4, q), b, at(2, 3, 4, q));
  EXPECT_NEAR(r.depth, s.depth, kTol);
  Transform xb = at(0, 0, 0, q);
  xb.position = q * Vec3(1.3, 0.4, -0.3);
  const EpaResult t = epa_penetration(a, at(0, 0, 0, q), b, xb);
  EXPECT_NEAR(t.depth, 0.2, 5 * kTol);
  EXPECT_TRUE(t.normal.isApprox(q * Vec3::UnitX(), Real(1e-4)));
}

TEST(Epa, CapsulesMatchClosedForms) {
  const Shape a = capsule(0.3, 1), b = capsule(0.2, 0.5);
  // Crossing at right angles, axes 0.4 apart along x: depth 0.5 - 0.4.
  const Quat qz(Eigen::AngleAxis<Real>(Real(std::numbers::pi / 2), Vec3::UnitX()));
  EpaResult e = epa_penetration(a, at(0, 0, 0), b, at(0.4, 0.2, 0.1, qz));
  ASSERT_TRUE(e.ok);
  EXPECT_NEAR(e.depth, 0.1, kTol);
  EXPECT_TRUE(e.normal.isApprox(Vec3::UnitX(), Real(1e-5)));
  // Cores crossing (distance 0): depth is the sum of radii, normal along the common perpendicular.
  e = epa_penetration(a, at(0, 0, 0), b, at(0, 0.2, 0, qz));
  ASSERT_TRUE(e.ok);
  EXPECT_NEAR(e.depth, 0.5, kTol);
  EXPECT_NEAR(std::abs(e.normal.x()), 1, 1e-5);
  // A capsule standing in a box near its top: the core must rise 1 - 0.4, plus the radius.
  e = epa_penetration(capsule(0.2, 0.5), at(0, 0.9, 0), box(2, 1, 2), at(0, 0, 0));
  ASSERT_TRUE(e.ok);
  EXPECT_NEAR(e.depth, 0.8, kTol);
  EXPECT_TRUE(e.normal.isApprox(-Vec3::UnitY(), Real(1e-5)));
}

// Random overlapping hulls: EPA's depth equals the exact SAT depth (minimum overlap over face
// normals and edge-pair axes), and its normal is an axis that achieves it.
TEST(Epa, MatchesSatDepthOnRandomHulls) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0;
  for (int i = 0; i < 300 && tested < 150; ++i) {
    const Shape a = oracle::random_hull(rng, 8 + i % 16, 1.0);
    const Shape b = oracle::random_hull(rng, 8 + (i * 5) % 24, 0.8);
    const Transform xa = at(0, 0, 0, oracle::random_rotation(rng));
    const Vec3 offset = Vec3(Real(u(rng)), Real(u(rng)), Real(u(rng))) * Real(0.6);
    const Transform xb = at(offset.x(), offset.y(), offset.z(), oracle::random_rotation(rng));
    const oracle::Poly pa = oracle::place_hull(a, xa), pb = oracle::place_hull(b, xb);
    const double depth = oracle::sat_depth(pa, pb);
    if (depth < 1e-3) continue;
    ++tested;
    const EpaResult e = epa_penetration(a, xa, b, xb);
    ASSERT_TRUE(e.ok) << i;
    expect_finite_unit(e);
    EXPECT_NEAR(e.depth, depth, 2e-4 * (1 + depth)) << i;
    // Along e.normal the overlap of the projections is the reported depth.
    const Eigen::Vector3d n = e.normal.cast<double>();
    const auto [alo, ahi] = oracle::project(pa, n);
    const auto [blo, bhi] = oracle::project(pb, n);
    EXPECT_NEAR(ahi - blo, depth, 2e-4 * (1 + depth)) << i;
    (void)alo, (void)bhi;
  }
  EXPECT_GE(tested, 100);
}

TEST(Epa, DegenerateInputsStayFinite) {
  const Shape unit = box(1, 1, 1);
  // Identical boxes at one pose: depth 2 along some face normal.
  EpaResult e = epa_penetration(unit, at(0, 0, 0), unit, at(0, 0, 0));
  ASSERT_TRUE(e.ok);
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 2, kTol * 2);
  // Coincident sphere centres: depth = sum of radii, any unit normal.
  e = epa_penetration(sphere(1), at(1, 2, 3), sphere(0.5), at(1, 2, 3));
  ASSERT_TRUE(e.ok);
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 1.5, kTol);
  // Coincident parallel capsules (flat core difference).
  e = epa_penetration(capsule(0.2, 1), at(0, 0, 0), capsule(0.2, 1), at(0, 0, 0));
  ASSERT_TRUE(e.ok);
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 0.4, kTol);
  EXPECT_NEAR(e.normal.y(), 0, 1e-5);
  // Touching exactly: depth 0 within rounding.
  e = epa_penetration(unit, at(0, 0, 0), unit, at(2, 0.5, 0.5));
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 0, 1e-5);
  // Thin plates (1e-3) overlapping by 5e-4.
  const Shape thin = box(1, Real(1e-3), 1);
  e = epa_penetration(thin, at(0, 0, 0), thin, at(0.2, Real(1.5e-3), 0.1));
  ASSERT_TRUE(e.ok);
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 5e-4, 1e-6);
  EXPECT_NEAR(e.normal.y(), 1, 1e-4);
  // Huge box and tiny sphere sunk 0.005 into its top face.
  e = epa_penetration(sphere(0.01), at(3, Real(1000.005), -7), box(1000, 1000, 1000), at(0, 0, 0));
  ASSERT_TRUE(e.ok);
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 0.005, 1e-4);
  EXPECT_NEAR(e.normal.y(), -1, 1e-4);
}

}  // namespace narrowphase_epa_test
}  // namespace elan::detail
