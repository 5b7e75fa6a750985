// SPDX-License-Identifier: MIT
// GJK distance and closest points against closed forms and an exact polytope oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "narrowphase/gjk.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase_oracle.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_gjk_test {

using test::at;
using test::axis_angle;
using test::box;
using test::capsule;
using test::cylinder;
using test::sphere;

// Float GJK stops at a relative gap of 1e-5; the tolerances leave room for float rounding.
constexpr double kTol = sizeof(Real) == 4 ? 2e-4 : 1e-8;

void expect_finite(const GjkResult& g) {
  EXPECT_TRUE(std::isfinite(g.distance));
  EXPECT_TRUE(g.point_a.allFinite());
  EXPECT_TRUE(g.point_b.allFinite());
}

TEST(Gjk, SphereSphereMatchesClosedForm) {
  const Shape a = sphere(0.5), b = sphere(0.25);
  const Transform xa = at(1, 2, 3), xb = at(2, 4, 5);
  const Real centre = std::sqrt(Real(1 + 4 + 4));
  const GjkResult core = gjk_distance(a, xa, b, xb, false);
  EXPECT_NEAR(core.distance, centre, kTol * centre);
  EXPECT_TRUE(core.point_a.isApprox(xa.position, Real(1e-5)));
  const GjkResult full = gjk_distance(a, xa, b, xb, true);
  EXPECT_FALSE(full.overlap);
  EXPECT_NEAR(full.distance, centre - Real(0.75), kTol * centre);
  const Vec3 n = (xb.position - xa.position) / centre;
  EXPECT_LT((full.point_a - (xa.position + Real(0.5) * n)).norm(), 1e-3);
  EXPECT_LT((full.point_b - (xb.position - Real(0.25) * n)).norm(), 1e-3);
}

TEST(Gjk, SphereBoxMatchesClosedForm) {
  const Shape a = sphere(0.5), b = box(1, 2, 3);
  // Face region: closest point (1, 0.5, 0.2) on the +x face.
  GjkResult g = gjk_distance(a, at(3, 0.5, 0.2), b, at(0, 0, 0));
  EXPECT_NEAR(g.distance, 1.5, kTol);
  // The rounded support converges in distance much faster than in direction (the error in the
  // closest point is the square root of the distance's); the core query is exact.
  EXPECT_LT((g.point_b - Vec3(1, 0.5, 0.2)).norm(), 1e-2);
  g = gjk_distance(a, at(3, 0.5, 0.2), b, at(0, 0, 0), false);
  EXPECT_NEAR(g.distance, 2, kTol);
  EXPECT_TRUE(g.point_b.isApprox(Vec3(1, 0.5, 0.2), Real(1e-5)));
  // Corner region: centre at (2, 3, 4), corner (1, 2, 3): sqrt(3) - 0.5.
  g = gjk_distance(a, at(2, 3, 4), b, at(0, 0, 0));
  EXPECT_NEAR(g.distance, std::sqrt(3.0) - 0.5, kTol);
  EXPECT_TRUE(g.point_b.isApprox(Vec3(1, 2, 3), Real(1e-4)));
}

TEST(Gjk, BoxBoxFaceEdgeVertexMatchClosedForms) {
  const Shape a = box(1, 1, 1), b = box(1, 1, 1);
  const Real s2 = std::sqrt(Real(2)), s3 = std::sqrt(Real(3));
  // Face-face: gap 1 along x, offsets across keep the faces overlapping.
  EXPECT_NEAR(gjk_distance(a, at(0, 0, 0), b, at(3, 0.2, 0.1)).distance, 1.0, kTol);
  // Edge-edge: A turned 45 deg about z (edge along z at x = sqrt 2), B about y (edge along y at
  // x = 4 - sqrt 2): crossing edges, gap 4 - 2 sqrt 2.
  const GjkResult e = gjk_distance(a, at(0, 0, 0, axis_angle(std::numbers::pi / 4, Vec3::UnitZ())),
                                   b, at(4, 0, 0, axis_angle(std::numbers::pi / 4, Vec3::UnitY())));
  EXPECT_NEAR(e.distance, 4 - 2 * s2, kTol);
  EXPECT_TRUE(e.point_a.isApprox(Vec3(s2, 0, 0), Real(1e-3)));
  // Vertex-face: A's (1,1,1) corner turned onto +x, B's face at x = 4 - 1.
  const Quat q = Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3::UnitX());
  const GjkResult v = gjk_distance(a, at(0, 0, 0, q), b, at(4, 0.1, -0.2));
  EXPECT_NEAR(v.distance, 3 - s3, kTol * 3);
  EXPECT_TRUE(v.point_a.isApprox(Vec3(s3, 0, 0), Real(1e-3)));
}

TEST(Gjk, CapsuleCapsuleParallelAndSkewMatchClosedForms) {
  const Shape a = capsule(0.3, 1), b = capsule(0.2, 0.5);
  // Parallel along y, 2 apart: core distance 2.
  GjkResult g = gjk_distance(a, at(0, 0, 0), b, at(2, 0.4, 0), false);
  EXPECT_NEAR(g.distance, 2, kTol * 2);
  EXPECT_NEAR((g.point_b - g.point_a).normalized().x(), 1, 1e-4);
  g = gjk_distance(a, at(0, 0, 0), b, at(2, 0.4, 0), true);
  EXPECT_NEAR(g.distance, 1.5, kTol * 2);
  // Skew: B along z through (2, 0.3, *): closest core points (0, 0.3, 0) and (2, 0.3, 0).
  const Transform xb = at(2, 0.3, 0.1, axis_angle(std::numbers::pi / 2, Vec3::UnitX()));
  g = gjk_distance(a, at(0, 0, 0), b, xb, false);
  EXPECT_NEAR(g.distance, 2, kTol * 2);
  EXPECT_TRUE(g.point_a.isApprox(Vec3(0, 0.3, 0), Real(1e-4)));
  EXPECT_LT((g.point_b - Vec3(2, 0.3, 0)).norm(), 1e-4);
}

// Hundreds of random hull pairs: disjoint ones (by exact SAT) must match the exact polytope
// distance to 1e-4 relative, overlapping ones must report overlap.
TEST(Gjk, MatchesExactDistanceOnRandomHulls) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> u(-1, 1);
  int disjoint = 0, overlapping = 0;
  for (int i = 0; i < 400; ++i) {
    const Shape a = oracle::random_hull(rng, 6 + i % 20, 1.0);
    const Shape b = oracle::random_hull(rng, 6 + (i * 7) % 30, 0.7);
    const Vec3 centre_a = test::draw3(rng, u);
    const Transform xa = test::pose(centre_a, oracle::random_rotation(rng));
    const Vec3 direction = test::draw3(rng, u).normalized();
    const Vec3 offset = direction * Real(0.3 + 1.5 * (u(rng) + 1) / 2);
    const Transform xb = at(0, 0, 0, oracle::random_rotation(rng));
    Transform xb2 = xb;
    xb2.position = xa.position + offset;
    const oracle::Poly pa = oracle::place_hull(a, xa), pb = oracle::place_hull(b, xb2);
    const double depth = oracle::sat_depth(pa, pb);
    const GjkResult g = gjk_distance(a, xa, b, xb2);
    expect_finite(g);
    if (depth < -1e-3) {
      ++disjoint;
      const double ref = oracle::polytope_distance(pa, pb);
      ASSERT_FALSE(g.overlap) << i;
      EXPECT_NEAR(g.distance, ref, 1e-4 * ref + 1e-6) << i;
      EXPECT_NEAR((g.point_b - g.point_a).norm(), g.distance, 1e-4 * ref + 1e-6) << i;
      // The lower bound may not pass the exact distance (the separation cache relies on it),
      // and is nearly as tight as the distance. In float, GJK also stops where one more vertex no
      // longer shortens v (or repeats one): correcting v's direction by an angle shortens it only
      // to second order, which rounds away, while the last search falls short of |v| to first
      // order, by up to about 1.5e-4 of the distance in these 314 pairs. And v.w / |v| rounds by a
      // few 1e-6 m when |v| is millimetres and w metres.
      EXPECT_LE(g.lower_bound, ref + 1e-6) << i;
      EXPECT_GE(g.lower_bound, ref * (1 - 2e-4) - 5e-6) << i;
    } else if (depth > 1e-3) {
      ++overlapping;
      EXPECT_TRUE(g.overlap) << i;
    }
  }
  EXPECT_GT(disjoint, 100);
  EXPECT_GT(overlapping, 50);
}

// The sphere and capsule pairs with boxes and hulls run GJK on the cores in B's frame
// (gjk_core_in_frame_of_b). Moved back to the world, its answer must be the world-frame GJK's,
// which the tests above hold to closed forms and the exact polytope distance.
TEST(Gjk, CoreInFrameOfBMatchesTheWorldFrame) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-1, 1);
  int apart = 0, overlapping = 0;
  for (int i = 0; i < 400; ++i) {
    const bool segment = i % 2 == 0;
    const Shape a = segment ? capsule(0.2, Real(0.2 + 0.4 * (u(rng) + 1))) : sphere(0.3);
    const Shape b = i % 3 == 0 ? box(0.5, 0.3, 0.8) : oracle::random_hull(rng, 8 + i % 24, 0.8);
    const double reach = i % 3 == 1 ? 0.3 : 1.6;  // a third close enough to overlap
    const Vec3 centre_a = test::draw3(rng, u, Real(reach));
    const Transform xa = test::pose(centre_a, oracle::random_rotation(rng));
    const Vec3 centre_b = test::draw3(rng, u, Real(0.2));
    const Transform xb = test::pose(centre_b, oracle::random_rotation(rng));
    const GjkResult ref = gjk_distance(a, xa, b, xb, false);
    const Quat to_b = xb.rotation.conjugate();
    const Vec3 centre = to_b * (xa.position - xb.position);
    const Vec3 half = to_b * (xa.rotation * Vec3(0, a.half_height, 0));
    const Vec3 ends[2] = {centre - half, centre + half};
    Simplex simplex;
    const GjkResult g = gjk_core_in_frame_of_b(
        segment ? std::span<const Vec3>(ends, 2) : std::span<const Vec3>(&centre, 1), b, simplex);
    expect_finite(g);
    if (ref.distance > 1e-3) {
      ++apart;
      ASSERT_FALSE(g.overlap) << i;
      EXPECT_NEAR(g.distance, ref.distance, 1e-4 * ref.distance + 1e-6) << i;
      EXPECT_LE(g.lower_bound, g.distance) << i;
      // As tight as the distance, to the float rounding of dot products of points a metre or two
      // from the origin (a few 1e-7 m each, summed over GJK's last search).
      EXPECT_GE(g.lower_bound, ref.distance * (1 - 1e-4) - 3e-5) << i;
      // The witness on A lies on its core, the one on B at the distance from it.
      const Vec3 on_a = xb.rotation * g.point_a + xb.position;
      const Vec3 on_b = xb.rotation * g.point_b + xb.position;
      const Vec3 axis = xa.rotation * Vec3(0, a.half_height, 0);
      const Real t = segment ? std::clamp((on_a - xa.position).dot(axis) / axis.squaredNorm(),
                                          Real(-1), Real(1))
                             : Real(0);
      EXPECT_LT((on_a - (xa.position + t * axis)).norm(), 1e-4) << i;
      EXPECT_NEAR((on_b - on_a).norm(), ref.distance, 1e-4 * ref.distance + 1e-6) << i;
    } else if (ref.overlap) {
      ++overlapping;
      EXPECT_TRUE(g.overlap || g.distance < 1e-4) << i;
    }
  }
  EXPECT_GT(apart, 100);
  EXPECT_GT(overlapping, 40);
}

TEST(Gjk, WarmStartGivesTheSameDistance) {
  const Shape a = box(1, 0.5, 0.7), b = capsule(0.2, 0.6);
  const Transform xa = at(0, 0, 0, axis_angle(0.3, Vec3(1, 2, 3)));
  const Transform xb = at(1.5, 1.2, -0.4, axis_angle(1.1, Vec3(-1, 0, 2)));
  const GjkResult cold = gjk_distance(a, xa, b, xb);
  const Vec3 n = (cold.point_b - cold.point_a).normalized();
  const GjkResult warm = gjk_distance(a, xa, b, xb, true, &n);
  EXPECT_NEAR(warm.distance, cold.distance, kTol);
  EXPECT_LE(warm.iterations, cold.iterations);
}

TEST(Gjk, DegenerateInputsStayFiniteAndTerminate) {
  const Shape unit = box(1, 1, 1);
  // Touching exactly: distance 0 within rounding, overlap or not.
  GjkResult g = gjk_distance(unit, at(0, 0, 0), unit, at(2, 0.5, 0));
  expect_finite(g);
  EXPECT_LT(g.distance, 1e-5);
  // Identical shapes at the same pose, and coincident sphere centres.
  g = gjk_distance(unit, at(0, 0, 0), unit, at(0, 0, 0));
  expect_finite(g);
  EXPECT_TRUE(g.overlap);
  g = gjk_distance(sphere(1), at(1, 1, 1), sphere(1), at(1, 1, 1), false);
  expect_finite(g);
  EXPECT_NEAR(g.distance, 0, 1e-6);
  // Very thin boxes, 1e-3 thick, stacked 0.01 apart.
  const Shape thin = box(1, Real(1e-3), 1);
  g = gjk_distance(thin, at(0, 0, 0), thin, at(0.3, 0.012, 0.1));
  expect_finite(g);
  EXPECT_NEAR(g.distance, 0.01, 1e-5);
  // Huge next to tiny: a 1e3 box and a 1e-2 sphere 0.05 above its face.
  g = gjk_distance(box(1000, 1000, 1000), at(0, 0, 0), sphere(0.01), at(3, 1000.06, -7));
  expect_finite(g);
  EXPECT_NEAR(g.distance, 0.05, 1e-3);
  EXPECT_LE(g.iterations, 64);
}

// The early-stop tests' shapes, every kind GJK meets with a core (round and flat), paired in
// turn.
std::array<Shape, 4> stop_test_shapes() {
  return {capsule(Real(0.2), Real(0.4)), box(Real(0.3), Real(0.2), Real(0.5)),
          cylinder(Real(0.3), Real(0.2)), test::round_hull(20, Real(0.4))};
}

// A search told to stop that did not is the plain one: every field the same, bit for bit.
::testing::AssertionResult same_search(const GjkResult& cut, const GjkResult& full) {
  if (cut.overlap == full.overlap && cut.distance == full.distance &&
      cut.lower_bound == full.lower_bound && cut.point_a == full.point_a &&
      cut.point_b == full.point_b) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
         << "stopped search: overlap " << cut.overlap << ", distance " << cut.distance
         << ", lower bound " << cut.lower_bound << "; plain search: overlap " << full.overlap
         << ", distance " << full.distance << ", lower bound " << full.lower_bound;
}

// A contact's GJK between two shapes told to stop past a distance: when it stops early its lower
// bound is past that distance and the full search finds the shapes at least that far apart (to
// GJK's relative tolerance, 1e-5); when it does not, it is the same contact search with no such
// distance, bit for bit.
TEST(Gjk, StopsEarlyOnlyPastTheRejectDistance) {
  const std::array<Shape, 4> shapes = stop_test_shapes();
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> u(-1, 1);
  int stopped = 0, ran = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Shape& sa = shapes[trial % 4];
    const Shape& sb = shapes[(trial / 4) % 4];
    const Quat qa = test::random_turn(rng, u), qb = test::random_turn(rng, u);
    const PlacedShape a = place(sa, at(0, 0, 0, qa), true);
    const PlacedShape b = place(sb, test::pose(test::draw3(rng, u, Real(1.2)), qb), true);
    const Real reject = Real(0.05) + Real(0.1) * (u(rng) + 1);
    Simplex s0, s1, s2;
    const GjkResult full = gjk_placed(a, b, Vec3::Zero(), s0);
    const GjkResult cut = gjk_contact(a, b, Vec3::Zero(), s1, reject);
    const GjkResult uncut =
        gjk_contact(a, b, Vec3::Zero(), s2, std::numeric_limits<Real>::infinity());
    ASSERT_FALSE(full.beyond);
    ASSERT_FALSE(uncut.beyond);
    if (cut.beyond) {
      ++stopped;
      ASSERT_GT(cut.lower_bound, reject);
      ASSERT_FALSE(full.overlap);
      ASSERT_GE(full.distance, cut.lower_bound * (1 - Real(1e-5))) << trial;
      continue;
    }
    ++ran;
    ASSERT_TRUE(same_search(cut, uncut)) << trial;
  }
  EXPECT_GT(stopped, 500);
  EXPECT_GT(ran, 500);
}

// What the contact precision tests count: the pairs that overlap, those within 1 cm, and the
// supports the two searches took for the latter.
struct ContactTally {
  int overlapping = 0, near = 0;
  long full_supports = 0, contact_supports = 0;
};

// A contact's search (`fast`, gjk_contact or gjk_triangle_contact) against the full search of
// the same pair, `size` bounding the simplex's size: its distance is the full search's within the
// band it stops in (1e-4 of the distance plus 1e-5 of the size) plus the full search's own 1e-5.
// Within 1 cm, each search's closest point v lies beyond the exact normal's plane at the exact
// distance and within the band of it, so within acos(d / (d + band)) of the exact normal: the two
// normals are within twice that (d taken a band low). A search that ends in overlap is the full
// one, bit for bit.
::testing::AssertionResult within_contact_band(const GjkResult& full, const GjkResult& fast,
                                               double size, ContactTally& tally) {
  if (full.overlap) {
    if (fast.overlap) {
      ++tally.overlapping;
      return same_search(fast, full);
    }
    if (fast.distance <= 1e-5 * size) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "apart by " << fast.distance << " in overlap";
  }
  if (fast.beyond) {
    if (full.distance >= fast.lower_bound * (1 - Real(1e-5))) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "stopped past " << fast.lower_bound << " at a distance of " << full.distance;
  }
  const double d = full.distance;
  const double band = 1e-4 * d + 1e-5 * size + 1e-5 * d;
  if (std::abs(fast.distance - d) > band) {
    return ::testing::AssertionFailure() << "distance " << fast.distance << " against " << d;
  }
  if (d > 0.01) return ::testing::AssertionSuccess();
  ++tally.near;
  tally.full_supports += full.iterations;
  tally.contact_supports += fast.iterations;
  const Eigen::Vector3d n_full = (full.point_b - full.point_a).cast<double>().normalized();
  const Eigen::Vector3d n_fast = (fast.point_b - fast.point_a).cast<double>().normalized();
  const double angle = std::acos(std::clamp(n_full.dot(n_fast), -1.0, 1.0));
  const double bound = 2 * std::acos(std::max(d - band, 0.0) / (d + band));
  if (angle > bound) {
    return ::testing::AssertionFailure()
           << "normals " << angle << " rad apart (bound " << bound << ") at " << d;
  }
  return ::testing::AssertionSuccess();
}

// Two cylinders in random poses. On those within 1 cm, whose rims GJK converges on linearly, the
// contact's search takes fewer supports.
TEST(Gjk, ContactPrecisionStopsWithinItsBand) {
  const Shape c = cylinder(Real(0.3), Real(0.25));
  std::mt19937 rng(53);
  std::uniform_real_distribution<float> u(-1, 1);
  ContactTally tally;
  for (int trial = 0; trial < 6000; ++trial) {
    const Quat qa = test::random_turn(rng, u), qb = test::random_turn(rng, u);
    const PlacedShape a = place(c, at(0, 0, 0, qa), true);
    const PlacedShape b = place(c, test::pose(test::draw3(rng, u, Real(0.7)), qb), true);
    Simplex s0, s1;
    const GjkResult full = gjk_placed(a, b, Vec3::Zero(), s0);
    const GjkResult fast = gjk_contact(a, b, Vec3::Zero(), s1, Real(0.05));
    const double size = b.position.norm() + 2 * c.bounding_radius;
    ASSERT_TRUE(within_contact_band(full, fast, size, tally)) << trial;
  }
  EXPECT_GT(tally.near, 100);
  EXPECT_GT(tally.overlapping, 300);
  // 20 % fewer, here.
  EXPECT_LT(tally.contact_supports, tally.full_supports * 9 / 10);
}

// The same for a cylinder near a triangle of 1 m sides (gjk_triangle_contact, the triangle
// contact's search).
TEST(Gjk, TriangleContactPrecisionStopsWithinItsBand) {
  const Shape c = cylinder(Real(0.3), Real(0.25));
  const Vec3 triangle[3] = {Vec3(-0.5, 0, -0.3), Vec3(0.5, 0, -0.3), Vec3(0, 0.1, 0.6)};
  std::mt19937 rng(59);
  std::uniform_real_distribution<float> u(-1, 1);
  ContactTally tally;
  for (int trial = 0; trial < 6000; ++trial) {
    // determinism: drawn one after the other (as arguments, each compiler would order them).
    const Vec3 centre = test::draw3(rng, u, Real(0.6));
    const Quat turn = test::random_turn(rng, u);
    const PlacedShape a = place(c, test::pose(centre, turn), true);
    Simplex s0, s1;
    const GjkResult full = gjk_triangle(a, triangle, Vec3::Zero(), s0);
    const GjkResult fast = gjk_triangle_contact(a, triangle, Vec3::Zero(), s1, Real(0.05));
    const double size = a.position.norm() + 1 + c.bounding_radius;
    ASSERT_TRUE(within_contact_band(full, fast, size, tally)) << trial;
  }
  EXPECT_GT(tally.near, 100);
  EXPECT_GT(tally.overlapping, 300);
  // 22 % fewer, here.
  EXPECT_LT(tally.contact_supports, tally.full_supports * 9 / 10);
}

// The sweep bound (conservative advancement's question): where GJK stops early, the shapes do stay
// farther apart than the reach over the motion (sampled: B slides by -delta, no turn); elsewhere
// the search is the plain one, bit for bit.
TEST(Gjk, StopsEarlyOnlyWhereTheMotionStaysClear) {
  const std::array<Shape, 4> shapes = stop_test_shapes();
  std::mt19937 rng(37);
  std::uniform_real_distribution<float> u(-1, 1);
  int stopped = 0, ran = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Shape& sa = shapes[trial % 4];
    const Shape& sb = shapes[(trial / 4) % 4];
    const Quat qa = test::random_turn(rng, u), qb = test::random_turn(rng, u);
    const Transform xb = test::pose(test::draw3(rng, u, Real(1.5)), qb);
    const PlacedShape a = place(sa, at(0, 0, 0, qa), true);
    const PlacedShape b = place(sb, xb, true);
    SweepBound bound;
    bound.delta = test::draw3(rng, u, Real(0.6));
    bound.reach = Real(0.01) + Real(0.05) * (u(rng) + 1);
    Simplex s0, s1;
    const GjkResult full = gjk_placed(a, b, Vec3::Zero(), s0);
    const GjkResult cut = gjk_placed(a, b, Vec3::Zero(), s1, bound);
    if (cut.beyond) {
      ++stopped;
      ASSERT_GT(cut.lower_bound, bound.reach);
      for (int k = 0; k <= 32; ++k) {
        // A moves by delta relative to B: B's pose moves by -delta.
        Transform moved = xb;
        moved.position -= bound.delta * (Real(k) / 32);
        const GjkResult g = gjk_distance(sa, at(0, 0, 0, qa), sb, moved);
        ASSERT_FALSE(g.overlap) << trial << " " << k;
        ASSERT_GT(g.distance, bound.reach * (1 - Real(1e-5))) << trial << " " << k;
      }
      continue;
    }
    ++ran;
    ASSERT_TRUE(same_search(cut, full)) << trial;
  }
  EXPECT_GT(stopped, 500);
  EXPECT_GT(ran, 500);
}

// The hull of the sliver findings: 11 points, most of them clustered within 1 mm of one corner,
// and its pose; the sphere's (5 cm) pose.
ShapeDef clustered_hull() {
  ShapeDef d;
  d.type = ShapeType::ConvexHull;
  d.points = {
      {0x1.8fb59p-1f, -0x1.d521ep-4f, -0x1.f94bfap+0f},
      {-0x1.0ba1p-4f, 0x1.b973b8p+0f, 0x1.31c93p-2f},
      {0x1.47094p-2f, -0x1.90bd9p-1f, -0x1.561b56p+0f},
      {-0x1.1ee12p-4f, -0x1.91ab92p+0f, -0x1.ff68p+0f},
      {-2, -0x1.07ff08p+0f, -2},
      {-2, -2, -2},
      {-2, -2, -2},
      {-2, -2, -0x1.fe8bfep+0f},
      {-2, -2, -0x1.fffp+0f},
      {-2, -2, -2},
      {-2, -2, -2},
  };
  return d;
}
const Transform kClusteredHullPose{
    Vec3(-0x1.67ffe8p+1f, -0x1.2734a8p+1f, -0x1.2767a8p+1f),
    Quat(-0x1.962a14p-1f, 0x1.46a7f8p-2f, 0x1.aed7b6p-6f, 0x1.092c82p-1f)};
const Transform kNearBallPose{Vec3(-3, -0x1.91ce92p+0f, -0x1.7d2cfep+1f),
                              Quat(-0.5f, -0.5f, -0.5f, -0.5f)};

// The sliver tests' check: the sphere's exact distance from the hull of `d` (the least over every
// triangle of the hull's vertices, in double, less the radius) is `expected` (to 1e-6), and GJK
// finds no overlap and that distance within 1e-5: its relative gap (1e-5 of the 5 cm between the
// cores) and float supports of coordinates near 5 m (a few 1e-7 m each).
void expect_gjk_reaches_the_ball(const ShapeDef& d, double expected) {
  const Shape hull = make_shape(d);
  const Transform& xa = kClusteredHullPose;
  const Shape ball = sphere(0x1.99999ap-5f);
  const Transform& xb = kNearBallPose;

  const oracle::Poly poly = oracle::place_hull(hull, xa);
  const double exact =
      oracle::point_set_distance(poly.v, {xb.position.cast<double>()}) - double(ball.radius);
  ASSERT_NEAR(exact, expected, 1e-6);

  const GjkResult g = gjk_distance(hull, xa, ball, xb);
  EXPECT_FALSE(g.overlap);
  EXPECT_NEAR(g.distance, exact, 1e-5);
}

// A hull whose points include a cluster near one corner (found by fuzz_narrowphase,
// corpus/narrowphase/regression_gjk_sliver_1) against a sphere 4.6 mm away. GJK's float simplex
// solver, given the new support point of a sliver tetrahedron, rounded back to the old closest
// point, and GJK stopped there 0.34 mm (7 %) long, the new point far beyond the old point's
// plane.
TEST(Gjk, SliverSimplexStillReachesTheClosestPoint) {
  expect_gjk_reaches_the_ball(clustered_hull(), 0.0045677);
}

// The hull above with one clustered point moved (found by fuzz_narrowphase,
// corpus/narrowphase/regression_gjk_sliver_refined) and the sphere 0.17 mm from it. The search
// went on once from its simplex's own closest point, solved in double, then stalled again on a
// sliver and stopped 0.18 mm (twice the distance) long. Going on twice left it 50 um long, four
// times 16 um; it may now go on up to eight times (kMaxRefines).
TEST(Gjk, SliverSimplexTwiceStillReachesTheClosestPoint) {
  ShapeDef d = clustered_hull();
  d.points[7] = Vec3(-0x1.37ff38p+0f, -2, -0x1.fe8bfep+0f);
  expect_gjk_reaches_the_ball(d, 0.000167);
}

}  // namespace narrowphase_gjk_test
}  // namespace elan::detail
