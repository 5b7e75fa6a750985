// SPDX-License-Identifier: MIT
// The deep pair's contact of constant cost (narrowphase/deep_contact.hpp): depth and normal on
// cases with a closed-form answer, an upper bound of the true depth that separates the pair when
// B is moved by it, and the direction given to coincident centres; and the deep test it shares
// with the deep-pair budget (core/base/deep_overlap.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/base/deep_overlap.hpp"
#include "narrowphase/deep_contact.hpp"
#include "narrowphase/gjk.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_deep_contact_test {

using test::at;
using test::axis_angle;
using test::box;
using test::cylinder;
using test::sphere;

// Supports and dot products of a few unit vectors: rounding only.
constexpr double kTol = sizeof(Real) == 4 ? 2e-5 : 1e-12;

Manifold deep(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
              uint32_t ia = 1, uint32_t ib = 2) {
  Manifold m;
  EXPECT_TRUE(deep_contact(a, xa, ia, b, xb, ib, m));
  EXPECT_EQ(m.point_count, 1u);
  EXPECT_EQ(m.points[0].feature_id, kDeepFeatureId);
  return m;
}

// Two unit boxes face on, centres 0.2 m apart along x: each reaches 0.5 m towards the other, so
// they overlap by 0.5 + 0.5 - 0.2 = 0.8 m along the line of centres; the point lies between the
// centres, in the middle of the overlap slab [-0.3, 0.5] (x = 0.1 from A's centre).
TEST(DeepContact, UnitBoxesFaceOnOverlapAlongTheLineOfCentres) {
  const Shape b = box(Real(0.5), Real(0.5), Real(0.5));
  const Manifold m = deep(b, at(0, 0, 0), b, at(Real(0.2), 0, 0));
  EXPECT_NEAR(m.normal.x(), 1, kTol);
  EXPECT_NEAR(m.normal.y(), 0, kTol);
  EXPECT_NEAR(m.normal.z(), 0, kTol);
  EXPECT_NEAR(m.points[0].separation, -0.8, kTol);
  EXPECT_NEAR(m.points[0].anchor_a.x(), 0.1, kTol);
  EXPECT_NEAR(m.points[0].anchor_a.y(), 0, kTol);
  EXPECT_NEAR(m.points[0].anchor_a.z(), 0, kTol);
  // The same pair turned as a whole and moved far off: the same depth, the normal turned.
  const Quat q = axis_angle(Real(0.7), Vec3(1, 2, 3));
  const Vec3 c(100, -20, 50);
  const Manifold t = deep(b, {c, q}, b, {c + q * Vec3(Real(0.2), 0, 0), q});
  EXPECT_NEAR(t.points[0].separation, -0.8, 1e4 * kTol);
  EXPECT_NEAR(t.normal.dot(q * Vec3::UnitX()), 1, 1e4 * kTol);
}

// A face normal wins over the line of centres when its overlap is less: unit boxes with centres
// at (0.3, 0.1, 0) overlap by 1 - 0.3 = 0.7 along x and 1 - 0.1 = 0.9 along y, and along their
// line of centres u = (3, 1, 0) / sqrt(10) by 2 h(u) - |d| = (|u_x| + |u_y|) - 0.316 = 0.949.
TEST(DeepContact, TheLeastOverlapOfTheCandidateAxesIsTheDepth) {
  const Shape b = box(Real(0.5), Real(0.5), Real(0.5));
  const Manifold m = deep(b, at(0, 0, 0), b, at(Real(0.3), Real(0.1), 0));
  EXPECT_NEAR(m.normal.x(), 1, kTol);
  EXPECT_NEAR(m.points[0].separation, -0.7, kTol);
}

// Two spheres of radius 0.5 at one point: every direction is a normal of depth 2 r = 1; the one
// taken is the virtual direction of the two indices, reversed with them.
TEST(DeepContact, CoincidentSpheresOverlapByTheirDiameter) {
  const Shape s = sphere(Real(0.5));
  const Manifold m = deep(s, at(1, 2, 3), s, at(1, 2, 3), 4, 9);
  EXPECT_NEAR(m.points[0].separation, -1, kTol);
  EXPECT_NEAR(m.normal.norm(), 1, kTol);
  EXPECT_NEAR(m.normal.dot(spawn_direction(4, 9)), 1, kTol);
  const Manifold r = deep(s, at(1, 2, 3), s, at(1, 2, 3), 9, 4);
  EXPECT_NEAR(r.normal.dot(-m.normal), 1, kTol);
  EXPECT_NEAR(r.points[0].separation, -1, kTol);
  // Off centre by 0.3: the depth is r_a + r_b - d = 0.7, along the line of centres.
  const Manifold o = deep(s, at(0, 0, 0), s, at(0, 0, Real(0.3)));
  EXPECT_NEAR(o.points[0].separation, -0.7, kTol);
  EXPECT_NEAR(o.normal.z(), 1, kTol);
}

// Cylinders of radius 0.3 and half height 0.3 (those of cylinders500_one_point): coaxial 0.1 m
// apart along the axis, the caps overlap by 0.3 + 0.3 - 0.1 = 0.5 along y; side by side 0.2 m
// apart, the rims overlap by 0.3 + 0.3 - 0.2 = 0.4 along x; at one point with one turned a
// quarter about x, the least overlap of the candidates is 0.6 (a cap against the other's side,
// or two sides: every axis reaches 0.3 on each).
TEST(DeepContact, CylindersOverlapByTheirSupportsAlongTheNormal) {
  const Shape c = cylinder(Real(0.3), Real(0.3));
  const Manifold up = deep(c, at(0, 0, 0), c, at(0, Real(0.1), 0));
  EXPECT_NEAR(up.normal.y(), 1, kTol);
  EXPECT_NEAR(up.points[0].separation, -0.5, kTol);
  const Manifold side = deep(c, at(0, 0, 0), c, at(Real(0.2), 0, 0));
  EXPECT_NEAR(side.normal.x(), 1, kTol);
  EXPECT_NEAR(side.points[0].separation, -0.4, kTol);
  const Quat quarter = axis_angle(Real(M_PI / 2), Vec3::UnitX());
  const Manifold turned = deep(c, at(0, 0, 0), c, at(0, 0, 0, quarter));
  EXPECT_NEAR(turned.points[0].separation, -0.6, kTol);
  EXPECT_NEAR(turned.normal.norm(), 1, kTol);
}

// A plank and a ball on it, 0.3 m along the plank from its centre: the line of centres would
// push the ball 2.2 + 0.5 - 0.3 = 2.4 m along the plank; the plank's thin axes give 0.1 + 0.5 =
// 0.6 m, the true depth.
TEST(DeepContact, ABallInAPlankLeavesByThePlanksThinSide) {
  const Shape plank = box(Real(2.2), Real(0.1), Real(0.1));
  const Shape ball = sphere(Real(0.5));
  ASSERT_TRUE(inner_balls_deep(Vec3::Zero(), inner_ball_radius(plank), Vec3(Real(0.3), 0, 0),
                               inner_ball_radius(ball)));
  const Manifold m = deep(plank, at(0, 0, 0), ball, at(Real(0.3), 0, 0));
  EXPECT_NEAR(m.points[0].separation, -0.6, kTol);
  EXPECT_NEAR(std::abs(m.normal.x()), 0, kTol);
}

// Random deep pairs of every convex primitive: the depth is at least the true one (the least
// overlap over all directions, found by EPA) and B moved out by the depth along the normal (and
// 1 mm more) no longer overlaps A (GJK).
TEST(DeepContact, DepthBoundsTheTrueDepthAndSeparatesThePair) {
  const Shape shapes[] = {
      box(Real(0.4), Real(0.3), Real(0.5)), sphere(Real(0.4)),
      test::capsule(Real(0.25), Real(0.4)), cylinder(Real(0.35), Real(0.3)),
      test::round_hull(16, Real(0.45)),     test::box_hull(Real(0.3), Real(0.5), Real(0.4))};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  int checked = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const Shape& a = shapes[trial % 6];
    const Shape& b = shapes[(trial / 6) % 6];
    const Vec3 pa{u(rng), u(rng), u(rng)};
    const Transform xa =
        test::pose(pa, Quat{u(rng), u(rng), u(rng), u(rng) + Real(1.5)}.normalized());
    const Real ra = inner_ball_radius(a), rb = inner_ball_radius(b);
    const Vec3 off = Vec3{u(rng), u(rng), u(rng)} * (kDeepFraction * (ra + rb) / Real(1.8));
    const Transform xb = {xa.position + off,
                          Quat{u(rng), u(rng), u(rng), u(rng) + Real(1.5)}.normalized()};
    ASSERT_TRUE(inner_balls_deep(xa.position, ra, xb.position, rb));
    const Manifold m = deep(a, xa, b, xb);
    const Real depth = -m.points[0].separation;
    ASSERT_GT(depth, 0);
    const EpaResult e = epa_penetration(a, xa, b, xb);
    if (e.ok) {
      EXPECT_GE(depth, e.depth - Real(1e-3)) << "trial " << trial;
      ++checked;
    }
    const Transform out{xb.position + (depth + Real(1e-3)) * m.normal, xb.rotation};
    const GjkResult g = gjk_distance(a, xa, b, out);
    EXPECT_FALSE(g.overlap) << "trial " << trial;
    EXPECT_GT(g.distance, 0) << "trial " << trial;
  }
  EXPECT_GT(checked, 500);
}

// The virtual direction of coincident centres: unit, reversed with the indices, and spread: body
// 0's directions to bodies 1..200 point into every octant, at least 10 into each (25 on
// average; a sequence stuck on one axis or plane would leave octants empty).
TEST(DeepContact, SpawnDirectionIsUnitAntisymmetricAndSpread) {
  int octants[8] = {};
  for (uint32_t k = 1; k <= 200; ++k) {
    const Vec3 v = spawn_direction(0, k);
    ASSERT_NEAR(v.norm(), 1, kTol);
    EXPECT_EQ(spawn_direction(k, 0), Vec3(-v));
    ++octants[(v.x() > 0) + 2 * (v.y() > 0) + 4 * (v.z() > 0)];
  }
  for (int o = 0; o < 8; ++o) EXPECT_GE(octants[o], 10) << "octant " << o;
  for (uint32_t k = 0; k < 50; ++k) {
    const Vec3 v = spawn_direction(k, k + 1000);
    EXPECT_TRUE(v.allFinite());
    EXPECT_NEAR(v.norm(), 1, kTol);
  }
}

// The deep test: two unit boxes are deep with their centres within 0.9 m (inner balls of radius
// 0.5), not at 0.95; a box with a mesh-like shape (radius 0) never.
TEST(DeepOverlap, UnitBoxesAreDeepWithinNinetyPercentOfTheirInnerRadii) {
  const Shape b = box(Real(0.5), Real(0.5), Real(0.5));
  const Real r = inner_ball_radius(b);
  EXPECT_NEAR(r, 0.5, kTol);
  EXPECT_TRUE(inner_balls_deep(Vec3::Zero(), r, Vec3(Real(0.89), 0, 0), r));
  EXPECT_FALSE(inner_balls_deep(Vec3::Zero(), r, Vec3(Real(0.91), 0, 0), r));
  EXPECT_NEAR(inner_ball_radius(test::box_hull(Real(0.3), Real(0.5), Real(0.4))), 0.15, kTol);
}

}  // namespace narrowphase_deep_contact_test
}  // namespace elan::detail
