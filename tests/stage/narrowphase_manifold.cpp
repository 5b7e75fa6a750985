// SPDX-License-Identifier: MIT
// Manifolds beyond box pairs: capsule and cylinder against polyhedra, and feature ids that stay
// while the same features touch and change when they change.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <set>

#include "narrowphase/collide.hpp"
#include "narrowphase/gjk.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase/supporting_feature.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_manifold_test {

using test::axis_angle;
using test::pose;

constexpr Real kDepthTol = Real(1e-5);  // m; see narrowphase_sat.cpp

std::set<uint32_t> ids_of(const Manifold& m) {
  std::set<uint32_t> s;
  for (int k = 0; k < m.point_count; ++k) s.insert(m.points[k].feature_id);
  return s;
}

TEST(CapsulePolyhedron, LyingOnABoxGivesTwoPointsAtTheEnds) {
  const Shape ground = test::box(5, Real(0.5), 5);
  const Shape hull_ground = test::box_hull(5, Real(0.5), 5);
  const Shape cap = test::capsule(Real(0.2), Real(0.6));
  const Quat lying = axis_angle(Real(M_PI / 2), Vec3::UnitZ());  // axis along x
  for (const Shape* g : {&ground, &hull_ground}) {
    const Transform xa = pose(Vec3(Real(0.3), Real(0.2) - Real(1e-3), 0), lying);
    const Transform xb = pose(Vec3(0, Real(-0.5), 0));
    Manifold m;
    ASSERT_TRUE(collide(cap, xa, *g, xb, Real(0.02), m));
    test::expect_sane(m, xa, xb);
    EXPECT_NEAR(m.normal.y(), -1, 1e-5);  // capsule (A) to ground (B)
    ASSERT_EQ(m.point_count, 2);
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(m.points[k].separation, -1e-3, kDepthTol);
      EXPECT_NEAR(std::abs(test::contact_point(m, xa, k).x() - Real(0.3)), 0.6, 1e-5);
    }
  }
}

TEST(CapsulePolyhedron, StandingOnABoxGivesOnePoint) {
  const Shape ground = test::box(5, Real(0.5), 5);
  const Shape cap = test::capsule(Real(0.2), Real(0.6));
  const Transform xa = pose(Vec3(0, Real(0.8) - Real(2e-3), 0)), xb = pose(Vec3(0, -0.5, 0));
  Manifold m;
  ASSERT_TRUE(collide(ground, xb, cap, xa, Real(0.02), m));  // box first: the swapped routine
  test::expect_sane(m, xb, xa);
  EXPECT_NEAR(m.normal.y(), 1, 1e-5);
  ASSERT_EQ(m.point_count, 1);
  EXPECT_NEAR(m.points[0].separation, -2e-3, kDepthTol);
  EXPECT_LT(test::contact_point(m, xb, 0).head<1>().norm(), 1e-5);
}

TEST(CapsulePolyhedron, CapsuleAcrossABoxEdgeGivesOnePointAtTheEdgeDepth) {
  // Capsule along z lying across the top edge (x = 0.5, y = 0.5) of a unit box, approached
  // diagonally: closest features are the segment and the edge.
  const Shape b = test::box(Real(0.5), Real(0.5), Real(0.5));
  const Shape cap = test::capsule(Real(0.1), Real(1));
  const Quat along_z = axis_angle(Real(M_PI / 2), Vec3::UnitX());
  const Vec3 dir = Vec3(1, 1, 0).normalized();
  const Transform xa =
      pose(Vec3(Real(0.5), Real(0.5), 0) + dir * (Real(0.1) - Real(3e-3)), along_z);
  Manifold m;
  ASSERT_TRUE(collide(cap, xa, b, pose(Vec3::Zero()), Real(0.02), m));
  ASSERT_EQ(m.point_count, 1);
  EXPECT_NEAR(m.points[0].separation, -3e-3, kDepthTol);
  EXPECT_NEAR(m.normal.dot(-dir), 1, 1e-5);
}

TEST(CylinderManifold, StandingOnABoxGivesRimPoints) {
  const Shape ground = test::box(5, Real(0.5), 5);
  const Shape cyl = test::cylinder(Real(0.3), Real(0.4));
  const Transform xa = pose(Vec3(0, Real(-0.5), 0));
  const Transform xb = pose(Vec3(Real(0.2), Real(0.4) - Real(1e-3), Real(0.1)));
  Manifold m;
  ASSERT_TRUE(collide(ground, xa, cyl, xb, Real(0.02), m));
  test::expect_sane(m, xa, xb);
  EXPECT_NEAR(m.normal.y(), 1, 1e-4);
  ASSERT_GE(m.point_count, 3);
  for (int k = 0; k < m.point_count; ++k) {
    const Vec3 p = test::contact_point(m, xa, k);
    EXPECT_NEAR(m.points[k].separation, -1e-3, 1e-4);
    EXPECT_NEAR(Vec3(p.x() - Real(0.2), 0, p.z() - Real(0.1)).norm(), 0.3, 1e-4);  // on the rim
  }
}

TEST(CylinderManifold, LyingOnAHullGivesALineContact) {
  const Shape ground = test::box_hull(5, Real(0.5), 5);
  const Shape cyl = test::cylinder(Real(0.3), Real(0.4));
  const Transform xa =
      pose(Vec3(0, Real(0.3) - Real(1e-3), 0), axis_angle(Real(M_PI / 2), Vec3::UnitX()));
  const Transform xb = pose(Vec3(0, Real(-0.5), 0));
  Manifold m;
  ASSERT_TRUE(collide(cyl, xa, ground, xb, Real(0.02), m));
  test::expect_sane(m, xa, xb);
  EXPECT_NEAR(m.normal.y(), -1, 1e-4);
  ASSERT_EQ(m.point_count, 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(m.points[k].separation, -1e-3, 1e-4);
    EXPECT_NEAR(std::abs(test::contact_point(m, xa, k).z()), 0.4, 1e-4);
  }
}

// Small translations and rotations keep every feature id; a tilt that changes the touching
// features (face contact to edge contact) changes them.
TEST(ManifoldFeatureIds, StableUnderSmallMotionAndChangedWithFeatures) {
  const Shape ground = test::box(5, Real(0.5), 5);
  const Shape b = test::box(Real(0.5), Real(0.5), Real(0.5));
  const Shape hull = test::box_hull(Real(0.5), Real(0.5), Real(0.5));
  const Shape cap = test::capsule(Real(0.2), Real(0.5));
  const Quat lying = axis_angle(Real(M_PI / 2), Vec3::UnitZ());
  struct Case {
    const Shape* s;
    Quat q;
    Real y;
  };
  const Case cases[] = {{&b, Quat::Identity(), Real(0.499)},
                        {&hull, Quat::Identity(), Real(0.499)},
                        {&b, axis_angle(Real(0.4), Vec3::UnitZ()), Real(0)},
                        {&cap, lying, Real(0.199)}};
  const Transform xg = pose(Vec3(0, Real(-0.5), 0));
  for (const Case& c : cases) {
    Transform xb = pose(Vec3(0, c.y, 0), c.q);
    if (c.y == 0) {
      Real lo = 1e9;
      for (int i = 0; i < 8; ++i) {
        const Vec3 v((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5);
        lo = std::min(lo, (c.q * v).y());
      }
      xb.position.y() = -lo - Real(1e-3);
    }
    Manifold m0;
    ASSERT_TRUE(collide(ground, xg, *c.s, xb, Real(0.02), m0));
    const std::set<uint32_t> ids0 = ids_of(m0);
    ASSERT_EQ(int(ids0.size()), m0.point_count) << "ids unique within a manifold";
    const Transform moved[] = {
        pose(xb.position + Vec3(Real(1e-3), Real(-1e-4), Real(-1e-3)), xb.rotation),
        pose(xb.position, axis_angle(Real(1e-3), Vec3(1, 0, 1)) * xb.rotation),
        pose(xb.position, axis_angle(Real(1e-3), Vec3::UnitY()) * xb.rotation)};
    for (const Transform& x : moved) {
      Manifold m;
      ASSERT_TRUE(collide(ground, xg, *c.s, x, Real(0.02), m));
      EXPECT_EQ(ids_of(m), ids0);
    }
  }
  // Flat (4 points) to tilted past 45 degrees onto an edge of another face (2 points): the
  // incident face changed, so do the ids. (A small tilt keeps the same face and vertices.)
  Manifold flat, tilted;
  ASSERT_TRUE(collide(ground, xg, b, pose(Vec3(0, Real(0.499), 0)), Real(0.02), flat));
  const Quat q = axis_angle(Real(1.2), Vec3::UnitX());
  ASSERT_TRUE(collide(ground, xg, b,
                      pose(Vec3(0, Real(0.5) * (std::cos(Real(1.2)) + std::sin(Real(1.2))), 0), q),
                      Real(0.02), tilted));
  std::set<uint32_t> common;
  for (uint32_t id : ids_of(tilted)) {
    if (ids_of(flat).count(id)) common.insert(id);
  }
  EXPECT_TRUE(common.empty());
}

// A pose turned at random, its centre within `reach` of `around` on each axis.
Transform random_pose(std::mt19937& rng, std::uniform_real_distribution<float>& u,
                      const Vec3& around, Real reach) {
  const Vec3 offset{u(rng), u(rng), u(rng)};
  return pose(around + reach * offset,
              Quat{u(rng), u(rng), u(rng), u(rng) + Real(1.1)}.normalized());
}

// A rejection reports what it measured: a gap above the speculative distance and no larger than
// the distance between the shapes (any separating axis's gap is at most the distance), in the
// frame the routine measured it. Random poses of every pair of the engine's shape types.
TEST(Collide, RejectionsReportAGapNoLargerThanTheDistance) {
  const Shape shapes[] = {
      test::box(Real(0.4), Real(0.3), Real(0.5)), test::sphere(Real(0.4)),
      test::capsule(Real(0.25), Real(0.4)),       test::cylinder(Real(0.35), Real(0.3)),
      test::round_hull(16, Real(0.45)),           test::box_hull(Real(0.3), Real(0.5), Real(0.4))};
  constexpr Real kSpeculative = Real(0.02);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1, 1);
  int rejected = 0, reported = 0, faces = 0;
  for (int i = 0; i < 6000; ++i) {
    const Shape& a = shapes[i % 6];
    const Shape& b = shapes[(i / 6) % 6];
    const Transform xa = random_pose(rng, u, Vec3::Zero(), 1);
    const Transform xb = random_pose(rng, u, xa.position, Real(1.2));
    Manifold m;
    PolyhedronCache cache;
    Separation separation;
    if (collide(a, xa, b, xb, kSpeculative, m, cache, separation)) {
      EXPECT_EQ(separation.kind, Separation::Kind::Unknown) << i;
      continue;
    }
    ++rejected;
    if (separation.kind == Separation::Kind::Unknown) continue;
    ++reported;
    faces += separation.kind == Separation::Kind::Distance ? 0 : 1;
    // The distance of the cores less the radii is exact for rounded shapes, and GJK converges
    // on cores in a few iterations.
    const GjkResult g = gjk_distance(a, xa, b, xb, false);
    const Real distance = g.distance - core_radius(a) - core_radius(b);
    EXPECT_GT(separation.gap, kSpeculative) << i;
    EXPECT_LE(separation.gap, distance + Real(1e-5)) << i;
  }
  EXPECT_GT(rejected, 1500);
  EXPECT_GT(reported, rejected * 9 / 10) << "edge axes and parallel capsules only";
  EXPECT_GT(faces, 100);
}

// An SAT rejection on an edge axis names its two edges, and re-testing that one pair gives the
// SAT's gap to the bit: above the gap less one ulp, not above the gap itself. That is what lets
// the separation cache skip the SAT while the pair still separates (collide_pairs) and still give
// the exact tests' bits. Boxes against boxes (the nine direction pairs) and hulls, random poses.
TEST(Collide, AnEdgeAxisRejectionIsFoundAgainBitForBit) {
  const Shape shapes[] = {test::box(Real(0.4), Real(0.3), Real(0.5)),
                          test::round_hull(16, Real(0.45)),
                          test::box_hull(Real(0.3), Real(0.5), Real(0.4))};
  constexpr Real kSpeculative = Real(0.02);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1, 1);
  int box_pairs = 0, hull_pairs = 0;
  for (int i = 0; i < 20000; ++i) {
    const Shape& a = shapes[i % 3];
    const Shape& b = shapes[(i / 3) % 3];
    const Transform xa = random_pose(rng, u, Vec3::Zero(), 1);
    const Transform xb = random_pose(rng, u, xa.position, Real(1.2));
    Manifold m;
    PolyhedronCache cache;
    Separation separation;
    if (collide(a, xa, b, xb, kSpeculative, m, cache, separation)) continue;
    if (separation.kind != Separation::Kind::EdgePair) continue;
    (a.type == ShapeType::Box && b.type == ShapeType::Box ? box_pairs : hull_pairs) += 1;
    const Real gap = separation.gap;
    EXPECT_GT(gap, kSpeculative) << i;
    PolyhedronCache fresh;
    EXPECT_TRUE(edge_pair_separates(a, xa, b, xb, separation.edge_a, separation.edge_b,
                                    std::nextafter(gap, Real(0)), fresh))
        << i;
    EXPECT_FALSE(
        edge_pair_separates(a, xa, b, xb, separation.edge_a, separation.edge_b, gap, fresh))
        << i;
    // Edges that are not the shapes' are refused, not read.
    EXPECT_FALSE(edge_pair_separates(a, xa, b, xb, 100000, separation.edge_b, 0, fresh)) << i;
  }
  EXPECT_GT(box_pairs, 40);
  EXPECT_GT(hull_pairs, 200);
}

// A face kept in the memo is the face made again, bit for bit: for directions that pick the same
// face over and over (a body's normals over a surface) and ones that move between faces, caps,
// sides and single points.
TEST(SupportingFeature, KeptFaceIsTheFaceMadeAgain) {
  const Shape shapes[] = {test::box(Real(0.35), Real(0.3), Real(0.4)),
                          test::box_hull(Real(0.3), Real(0.5), Real(0.4)),
                          test::round_hull(16, Real(0.45)),
                          test::cylinder(Real(0.35), Real(0.3)),
                          test::capsule(Real(0.25), Real(0.4)),
                          test::sphere(Real(0.4))};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1, 1);
  int same_face = 0, new_face = 0;
  for (const Shape& s : shapes) {
    const Transform x = pose(test::draw3(rng, u), test::random_turn(rng, u));
    const Vec3 origin = test::draw3(rng, u);
    FeatureMemo memo;
    uint32_t last_id = ~0u;
    for (int i = 0; i < 400; ++i) {
      // Mostly about one direction (down), now and then anywhere.
      const Vec3 d = (i % 7 == 0 ? test::draw3(rng, u)
                                 : Vec3(Vec3(0, -1, 0) + Real(0.3) * test::draw3(rng, u)))
                         .normalized();
      Feature kept, made;
      supporting_feature(s, x, d, origin, kept, &memo);
      supporting_feature(s, x, d, origin, made);
      ASSERT_EQ(kept.count, made.count) << "shape " << int(s.type) << ", direction " << i;
      ASSERT_EQ(kept.id, made.id);
      ASSERT_EQ(std::memcmp(kept.points, made.points, sizeof(Vec3) * std::size_t(made.count)), 0);
      if (made.count >= 3) (made.id == last_id ? same_face : new_face) += 1;
      last_id = made.count >= 3 ? made.id : ~0u;
    }
  }
  EXPECT_GT(same_face, 500) << "faces met again, taken from the memo";
  EXPECT_GT(new_face, 50) << "faces that changed, made and kept";
}

}  // namespace narrowphase_manifold_test
}  // namespace elan::detail
