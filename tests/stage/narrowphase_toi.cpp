// SPDX-License-Identifier: MIT
// Time of impact (conservative advancement) against the analytic contact time.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "narrowphase/collide.hpp"
#include "narrowphase/gjk.hpp"

namespace elan::detail {
namespace narrowphase_toi_test {

Shape make(ShapeType type, Real r, Vec3 he = Vec3::Zero()) {
  ShapeDef d;
  d.type = type;
  d.radius = r;
  d.half_extents = he;
  return make_shape(d);
}

Transform at(Real x, Real y, Real z, Quat q = Quat::Identity()) {
  Transform t;
  t.position = Vec3(x, y, z);
  t.rotation = q;
  return t;
}

// The stopping rule: distance within [target, target + max(target / 4, 1e-4 * size)].
Real allowance(Real target, Real size) {
  return std::max(target / 4, Real(1e-4) * size);
}

TEST(TimeOfImpact, SphereAtThinBoxMatchesAnalyticTime) {
  const Shape ball = make(ShapeType::Sphere, Real(0.1));
  const Shape plate = make(ShapeType::Box, 0, Vec3(1, Real(0.005), 1));
  const Real target = Real(0.01);
  // The ball crosses the 1 cm plate from y = 2 to y = -2 in one step: it would tunnel.
  const Real t = time_of_impact(ball, at(0.1, 2, 0.2), at(0.1, -2, 0.2), plate, at(0, 0, 0),
                                at(0, 0, 0), target);
  // Centre height at contact: half thickness + radius + target.
  const Real exact = (2 - (Real(0.005) + Real(0.1) + target)) / 4;
  EXPECT_LE(t, exact + Real(1e-6));
  EXPECT_GE(t, exact - allowance(target, plate.bounding_radius) / 4 - Real(1e-6));
  // Both moving: the same relative motion gives the same time.
  const Real t2 = time_of_impact(ball, at(0.1, 2, 0.2), at(0.1, 0, 0.2), plate, at(0, 0, 0),
                                 at(0, 2, 0), target);
  EXPECT_NEAR(t2, t, 1e-4);
}

TEST(TimeOfImpact, MissAndSeparatingReturnOne) {
  const Shape ball = make(ShapeType::Sphere, Real(0.1));
  const Shape plate = make(ShapeType::Box, 0, Vec3(1, Real(0.005), 1));
  EXPECT_EQ(
      time_of_impact(ball, at(3, 2, 0), at(3, -2, 0), plate, at(0, 0, 0), at(0, 0, 0), Real(0.01)),
      1);
  EXPECT_EQ(
      time_of_impact(ball, at(0, 1, 0), at(0, 3, 0), plate, at(0, 0, 0), at(0, 0, 0), Real(0.01)),
      1);
}

// A spinning bar sweeps into a resting ball: the distance at the returned time is at the target
// (no overshoot from the rotation bound), and the bar does reach the ball within the step.
TEST(TimeOfImpact, RotationIsBoundedWithoutOvershoot) {
  const Shape ball = make(ShapeType::Sphere, Real(0.1));
  const Shape bar = make(ShapeType::Box, 0, Vec3(1, Real(0.05), Real(0.05)));
  const Transform xb0 = at(0, 0, 0);
  const Transform xb1 = at(0, 0, 0, Quat(Eigen::AngleAxis<Real>(Real(1.2), Vec3::UnitZ())));
  const Transform xs = at(Real(0.4), Real(0.6), 0);
  const Real target = Real(0.01);
  const Real t = time_of_impact(ball, xs, xs, bar, xb0, xb1, target);
  ASSERT_LT(t, 1);
  Transform xb;
  xb.rotation = xb0.rotation.slerp(t, xb1.rotation);
  const GjkResult g = gjk_distance(ball, xs, bar, xb);
  EXPECT_GE(g.distance, target - Real(1e-5));
  EXPECT_LE(g.distance, target + allowance(target, bar.bounding_radius) + Real(1e-5));
  // Analytic: the bar's top face (y = 0.05 in its frame) meets the ball's bottom when the
  // ball centre is 0.05 + 0.1 + target above the rotating face line: atan2 geometry.
  const Real rho = std::hypot(Real(0.4), Real(0.6));
  const Real angle = std::atan2(Real(0.6), Real(0.4)) - std::asin((Real(0.16)) / rho);
  EXPECT_NEAR(t * Real(1.2), angle, 0.01);
}

}  // namespace narrowphase_toi_test
}  // namespace elan::detail
