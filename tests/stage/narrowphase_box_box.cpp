// SPDX-License-Identifier: MIT
// The box-box contact (narrowphase/box_box.cpp): what its rejections report is what the
// separation cache tests again, bit for bit; its feature ids stay while a box slides within a
// face, so that warm starting keeps its impulses; its points are on both boxes' surfaces. (Its
// agreement with the polyhedron SAT of the same boxes as hulls is in narrowphase_sat.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "narrowphase/box_box.hpp"
#include "narrowphase/collide.hpp"
#include "narrowphase/sat.hpp"
#include "narrowphase/sat_common.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_box_box_test {

using test::axis_angle;
using test::pose;

// A random unit quaternion.
Quat random_rotation(std::mt19937& rng) {
  std::uniform_real_distribution<Real> u(-1, 1);
  // Braces: the draws in order, so that every compiler tests the same poses.
  return Quat{u(rng), u(rng), u(rng), u(rng)}.normalized();
}

// How far two boxes turned by qa and qb reach along the unit `dir` together: their centres this
// far apart along it put their supports in touch.
Real reach_along(const Shape& a, const Quat& qa, const Shape& b, const Quat& qb, const Vec3& dir) {
  Real reach = 0;
  for (int k = 0; k < 3; ++k) {
    reach += std::abs(dir.dot(qa * (Vec3::Unit(k) * a.half_extents[k])));
    reach += std::abs(dir.dot(qb * (Vec3::Unit(k) * b.half_extents[k])));
  }
  return reach;
}

// Signed distance of world point p from the surface of box `s` at `x` (negative inside), exact
// for points inside or beside a face and a lower bound of nothing else: enough to check that a
// contact point lies on the surface.
Real box_depth(const Shape& s, const Transform& x, const Vec3& p) {
  const Vec3 local = x.rotation.conjugate() * (p - x.position);
  const Vec3 q = local.cwiseAbs() - s.half_extents;
  return q.cwiseMax(Vec3::Zero()).norm() + std::min(q.maxCoeff(), Real(0));
}

// A rejection on an edge axis reports the two edges and a gap; the cache's test of those two
// edges (edge_pair_separates) computes that gap again, bit for bit, from the same poses, and
// keeps computing it as the boxes move (the cache re-tests it each step). Boxes of a leg, a table
// top and a cube, at random turns, placed just beyond touching along a random direction.
TEST(BoxBox, EdgeRejectionIsWhatTheCacheTestsAgainBitForBit) {
  const Shape shapes[] = {test::box(Real(0.04), Real(0.2), Real(0.04)),
                          test::box(Real(0.5), Real(0.05), Real(0.35)),
                          test::box(Real(0.2), Real(0.2), Real(0.2))};
  std::mt19937 rng(41);
  std::uniform_real_distribution<Real> u(-1, 1);
  std::uniform_int_distribution<int> pick(0, 2);
  constexpr Real kSpeculative = Real(0.02);
  int edge_rejections = 0, face_rejections = 0;
  PolyhedronCache cache;
  for (int i = 0; i < 4000; ++i) {
    const Shape& a = shapes[pick(rng)];
    const Shape& b = shapes[pick(rng)];
    const Quat qa = random_rotation(rng), qb = random_rotation(rng);
    const Vec3 dir = Vec3{u(rng), u(rng), u(rng)}.normalized();
    const Real reach = reach_along(a, qa, b, qb, dir);
    const Transform xa = pose(Vec3(3, -2, 5), qa);
    const Transform xb = pose(Vec3(3, -2, 5) + (reach + Real(0.05) * u(rng)) * dir, qb);
    Manifold m;
    Separation s;
    if (collide(a, xa, b, xb, kSpeculative, m, cache, s)) continue;
    if (s.kind == Separation::Kind::FaceOfA || s.kind == Separation::Kind::FaceOfB) {
      ++face_rejections;
      EXPECT_GT(s.gap, kSpeculative) << i;
      continue;
    }
    // No axis separates by more than the speculative distance, yet no point is within it (the
    // clipped face lies beyond it and the boxes do not overlap): nothing measured that lasts.
    if (s.kind == Separation::Kind::Unknown) continue;
    ASSERT_EQ(s.kind, Separation::Kind::EdgePair) << i;
    ++edge_rejections;
    ASSERT_GE(s.edge_a, 0);
    ASSERT_LT(s.edge_a, 12);
    ASSERT_GE(s.edge_b, 0);
    ASSERT_LT(s.edge_b, 12);
    EXPECT_GT(s.gap, kSpeculative) << i;
    EXPECT_EQ(box_edge_pair_separation(a, xa, b, xb, s.edge_a, s.edge_b), s.gap) << i;
    EXPECT_TRUE(edge_pair_separates(a, xa, b, xb, s.edge_a, s.edge_b, kSpeculative, cache)) << i;
    // The same edges tested at the next step's poses give what the exact test measures there
    // along that axis: while it stays above the speculative distance, the exact test rejects too.
    const Transform xb_next = pose(xb.position - Real(0.01) * dir, qb);
    if (edge_pair_separates(a, xa, b, xb_next, s.edge_a, s.edge_b, kSpeculative, cache)) {
      EXPECT_FALSE(collide(a, xa, b, xb_next, kSpeculative, m)) << i;
    }
  }
  EXPECT_GT(edge_rejections, 300);
  EXPECT_GT(face_rejections, 300);
}

// A box resting on a larger one, slid within its face in small steps and turned a little: the
// four points keep their feature ids, the ids warm starting matches impulses by.
TEST(BoxBox, FeatureIdsStayWhileABoxSlidesWithinAFace) {
  const Shape ground = test::box(2, Real(0.5), 2),
              block = test::box(Real(0.3), Real(0.2), Real(0.4));
  const Transform xa = pose(Vec3(0, Real(-0.5), 0));
  std::set<uint32_t> first;
  for (int k = 0; k < 50; ++k) {
    const Real t = Real(k) / 50;
    const Transform xb = pose(Vec3(Real(-0.8) + Real(1.6) * t, Real(0.199), Real(0.3) * t),
                              axis_angle(Real(0.3) * t, Vec3::UnitY()));
    Manifold m;
    ASSERT_TRUE(collide(ground, xa, block, xb, Real(0.02), m)) << k;
    ASSERT_EQ(m.point_count, 4) << k;
    EXPECT_NEAR(m.normal.y(), 1, 1e-6);
    std::set<uint32_t> ids;
    for (int p = 0; p < 4; ++p) {
      ids.insert(m.points[p].feature_id);
      EXPECT_NEAR(m.points[p].separation, -1e-3, 1e-5) << k;
    }
    ASSERT_EQ(ids.size(), 4u) << k;
    if (k == 0) first = ids;
    EXPECT_EQ(ids, first) << k;
  }
}

// Random overlapping and nearly touching pairs: the normal is unit, every point's separation is
// at most the speculative distance, and every point of the clipped incident face lies midway
// between the two surfaces (moved half its separation along the normal, it is on each box). Not
// an edge pair's point (the midpoint of the edges' closest points, which are off the normal's
// line where a segment's end is nearest) nor the deepest vertex kept when the clip leaves none
// (it may lie beside the reference face).
TEST(BoxBox, PointsLieMidwayBetweenTheTwoSurfaces) {
  const Shape a = test::box(Real(0.6), Real(0.3), Real(0.45));
  const Shape b = test::box(Real(0.4), Real(0.5), Real(0.2));
  std::mt19937 rng(23);
  std::uniform_real_distribution<Real> u(-1, 1);
  constexpr Real kSpeculative = Real(0.02);
  int touching = 0, clipped_points = 0;
  for (int i = 0; i < 2000; ++i) {
    const Quat qa = random_rotation(rng), qb = random_rotation(rng);
    const Vec3 dir = Vec3{u(rng), u(rng), u(rng)}.normalized();
    const Real reach = reach_along(a, qa, b, qb, dir);
    const Transform xa = pose(Vec3(-4, 1, 2), qa);
    const Transform xb = pose(xa.position + (reach - Real(0.1) + Real(0.1) * u(rng)) * dir, qb);
    Manifold m;
    if (!collide(a, xa, b, xb, kSpeculative, m)) continue;
    ++touching;
    ASSERT_NEAR(m.normal.norm(), 1, 1e-5) << i;
    for (uint32_t k = 0; k < m.point_count; ++k) {
      const ContactPoint& c = m.points[k];
      EXPECT_LE(c.separation, kSpeculative) << i;
      const bool edges = (c.feature_id >> 30) == (kFeatureEdges >> 30);
      if (edges || (c.feature_id & 0x3FFFu) == 0x3FFFu) continue;
      ++clipped_points;
      const Vec3 p = xa.position + c.anchor_a;
      // The point on A's side and on B's side, half the separation either way along the normal.
      const Vec3 on_a = p - Real(0.5) * c.separation * m.normal;
      const Vec3 on_b = p + Real(0.5) * c.separation * m.normal;
      // Each is on or inside its box (a point of the incident face may lie inside the reference
      // box's side where the reference face's plane is not its nearest): never outside by more
      // than rounding.
      EXPECT_LE(box_depth(a, xa, on_a), 1e-4) << i << " point " << k;
      EXPECT_LE(box_depth(b, xb, on_b), 1e-4) << i << " point " << k;
    }
  }
  EXPECT_GT(touching, 800);
  EXPECT_GT(clipped_points, 600);
}

// A box clear of another along one of that box's face normals by more than the speculative
// distance is rejected on a face, and the face gap it reports is at least that clearance, within
// rounding.
// Boxes placed so that their extent along one of the other box's axes lies within 1e-4 m either
// side of the speculative distance past its face, across the face at random, at random
// orientations: parts of scenes/compounds.json's tables against its ground slab and a cube.
TEST(BoxBox, ClearAlongAFaceNormalIsRejectedOnAFace) {
  const Shape parts[] = {test::box(Real(0.04), Real(0.2), Real(0.04)),
                         test::box(Real(0.5), Real(0.05), Real(0.35)),
                         test::box(Real(0.2), Real(0.2), Real(0.2))};
  const Shape others[] = {test::box(40, 1, 40), test::box(Real(0.3), Real(0.3), Real(0.3))};
  constexpr Real kSpeculative = Real(0.02);
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> u(-1, 1);
  PolyhedronCache cache;
  int clear_by_more = 0;
  for (int i = 0; i < 20000; ++i) {
    const Shape& p = parts[i % 3];
    const Shape& q = others[(i / 3) % 2];
    const Quat qp = random_rotation(rng), qq = random_rotation(rng);
    const int axis = i % 3;
    const Real side = u(rng) < 0 ? Real(-1) : Real(1);
    // p's extent along q's axis, and a random offset across it within q's face.
    const Vec3 n = qq * (side * Vec3::Unit(axis));
    Real extent = 0;
    for (int k = 0; k < 3; ++k) extent += std::abs(n.dot(qp * (Vec3::Unit(k) * p.half_extents[k])));
    const Real gap = kSpeculative + Real(1e-4) * u(rng);
    Vec3 across = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      if (k != axis) across[k] = q.half_extents[k] * u(rng);
    }
    const Transform xq = pose(Vec3(3, -1, 2), qq);
    const Transform xp =
        pose(xq.position + qq * across + (q.half_extents[axis] + extent + gap) * n, qp);
    if (!(gap > kSpeculative + Real(5e-5))) continue;
    ++clear_by_more;
    Manifold m;
    Separation s;
    ASSERT_FALSE(collide(p, xp, q, xq, kSpeculative, m, cache, s)) << i << " gap " << gap;
    // q's face, or a face of p's tested first that separates them as far.
    ASSERT_TRUE(s.kind == Separation::Kind::FaceOfA || s.kind == Separation::Kind::FaceOfB) << i;
    // Positions as far as the slab's 40 m from its centre round to about 5e-6 m, and the gap
    // passes through a few dozen such roundings: 2e-5 of the larger box's size.
    EXPECT_GE(s.gap, gap - Real(2e-5) * std::max(Real(1), q.half_extents.maxCoeff())) << i;
  }
  EXPECT_GT(clear_by_more, 4000);
}

}  // namespace narrowphase_box_box_test
}  // namespace elan::detail
