// SPDX-License-Identifier: MIT
// SAT with clipping for boxes and hulls: depths, point counts and normals against closed forms
// for face, edge and vertex contacts; hulls must agree with the boxes they equal.
#include <gtest/gtest.h>

#include <random>

#include "narrowphase/capsule_polyhedron.hpp"
#include "narrowphase/gjk.hpp"
#include "narrowphase/polyhedron.hpp"
#include "narrowphase/sat.hpp"
#include "narrowphase/sat_common.hpp"
#include "narrowphase_oracle.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_sat_test {

using test::axis_angle;
using test::pose;

// Depth tolerance: the contact depths are differences of coordinates of order 1 m in float,
// a few ulps (1e-7 relative) each; 1e-5 m leaves a wide margin yet catches any real error.
constexpr Real kDepthTol = Real(1e-5);

// Lowest world y of the box's corners for a given orientation (closed form of where it rests).
Real lowest_corner_offset(const Vec3& h, const Quat& q) {
  Real lo = 1e9;
  for (int i = 0; i < 8; ++i) {
    const Vec3 c((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
    lo = std::min(lo, (q * c).y());
  }
  return lo;
}

struct PairCase {
  const char* name;
  Shape ground;
  Shape body;
};

std::vector<PairCase> polyhedron_cases() {
  return {{"box-box", test::box(5, Real(0.5), 5), test::box(Real(0.5), Real(0.5), Real(0.5))},
          {"box-hull", test::box(5, Real(0.5), 5), test::box_hull(Real(0.5), Real(0.5), Real(0.5))},
          {"hull-box", test::box_hull(5, Real(0.5), 5), test::box(Real(0.5), Real(0.5), Real(0.5))},
          {"hull-hull", test::box_hull(5, Real(0.5), 5),
           test::box_hull(Real(0.5), Real(0.5), Real(0.5))}};
}

// Rests `body` (orientation q) on the ground's top face (y = 0) with penetration `depth`.
void rest(const PairCase& c, const Quat& q, Real depth, Manifold& m, Transform& xa, Transform& xb) {
  xa = pose(Vec3(0, Real(-0.5), 0));
  xb = pose(
      Vec3(Real(0.1), -lowest_corner_offset(Vec3::Constant(Real(0.5)), q) - depth, Real(-0.2)), q);
  ASSERT_TRUE(collide(c.ground, xa, c.body, xb, Real(0.02), m)) << c.name;
  test::expect_sane(m, xa, xb);
  EXPECT_NEAR(m.normal.y(), 1, 1e-5) << c.name;
}

TEST(SatPolyhedra, FlatBoxRestingGivesFourPointsAtTheDepth) {
  for (const PairCase& c : polyhedron_cases()) {
    Manifold m;
    Transform xa, xb;
    rest(c, Quat::Identity(), Real(1e-3), m, xa, xb);
    ASSERT_EQ(m.point_count, 4) << c.name;
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(m.points[k].separation, -1e-3, kDepthTol) << c.name;
      const Vec3 p = test::contact_point(m, xa, k);
      // At the body's bottom corners, midway between the two surfaces.
      EXPECT_NEAR(std::abs(p.x() - Real(0.1)), 0.5, 1e-5) << c.name;
      EXPECT_NEAR(std::abs(p.z() + Real(0.2)), 0.5, 1e-5) << c.name;
      EXPECT_NEAR(p.y(), -0.5e-3, 1e-5) << c.name;
    }
  }
}

TEST(SatPolyhedra, SwappedOrderFlipsTheNormal) {
  const Shape ground = test::box(5, Real(0.5), 5), b = test::box(Real(0.5), Real(0.5), Real(0.5));
  const Transform xa = pose(Vec3(0, Real(-0.5), 0)), xb = pose(Vec3(0, Real(0.499), 0));
  Manifold m;
  ASSERT_TRUE(collide(b, xb, ground, xa, Real(0.02), m));
  EXPECT_NEAR(m.normal.y(), -1, 1e-6);
  ASSERT_EQ(m.point_count, 4);
  test::expect_sane(m, xb, xa);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(m.points[k].separation, -1e-3, kDepthTol);
}

TEST(SatPolyhedra, BoxTiltedAboutOneAxisGivesAnEdgeContact) {
  for (const PairCase& c : polyhedron_cases()) {
    for (Real angle : {Real(0.3), Real(M_PI / 4), Real(1.1)}) {
      Manifold m;
      Transform xa, xb;
      rest(c, axis_angle(angle, Vec3::UnitZ()), Real(2e-3), m, xa, xb);
      ASSERT_EQ(m.point_count, 2) << c.name << " " << angle;
      for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(m.points[k].separation, -2e-3, kDepthTol) << c.name;
        EXPECT_NEAR(std::abs(test::contact_point(m, xa, k).z() + Real(0.2)), 0.5, 1e-5);
      }
    }
  }
}

TEST(SatPolyhedra, BoxTiltedAboutTwoAxesGivesAVertexContact) {
  for (const PairCase& c : polyhedron_cases()) {
    const Quat q = axis_angle(Real(0.4), Vec3::UnitX()) * axis_angle(Real(0.7), Vec3::UnitZ());
    Manifold m;
    Transform xa, xb;
    rest(c, q, Real(1.5e-3), m, xa, xb);
    ASSERT_EQ(m.point_count, 1) << c.name;
    EXPECT_NEAR(m.points[0].separation, -1.5e-3, kDepthTol) << c.name;
  }
}

TEST(SatPolyhedra, SeparatedWithinSpeculativeDistanceReportsTheGap) {
  const Shape ground = test::box(5, Real(0.5), 5), b = test::box(Real(0.5), Real(0.5), Real(0.5));
  const Transform xa = pose(Vec3(0, Real(-0.5), 0));
  Manifold m;
  ASSERT_TRUE(collide(ground, xa, b, pose(Vec3(0, Real(0.51), 0)), Real(0.02), m));
  ASSERT_EQ(m.point_count, 4);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(m.points[k].separation, 0.01, kDepthTol);
  EXPECT_FALSE(collide(ground, xa, b, pose(Vec3(0, Real(0.53), 0)), Real(0.02), m));
  EXPECT_EQ(m.point_count, 0);
  // Edge on edge, separated: one speculative point with the closed-form gap.
  const Quat q = axis_angle(Real(M_PI / 4), Vec3::UnitX());
  const Quat r = axis_angle(Real(M_PI / 4), Vec3::UnitZ());
  const Real d = Real(std::sqrt(2.0)) * Real(0.5);
  ASSERT_TRUE(
      collide(b, pose(Vec3::Zero(), q), b, pose(Vec3(0, 2 * d + Real(0.01), 0), r), Real(0.02), m));
  ASSERT_EQ(m.point_count, 1);
  EXPECT_NEAR(m.points[0].separation, 0.01, kDepthTol);
  EXPECT_NEAR(m.normal.y(), 1, 1e-5);
}

TEST(SatPolyhedra, CrossedEdgesGiveOnePointAtTheEdgeDepth) {
  // Two boxes rotated 45 degrees about perpendicular horizontal axes: their edges cross.
  const Shape b = test::box(Real(0.5), Real(0.5), Real(0.5));
  const Shape h = test::box_hull(Real(0.5), Real(0.5), Real(0.5));
  const Quat q = axis_angle(Real(M_PI / 4), Vec3::UnitX());
  const Quat r = axis_angle(Real(M_PI / 4), Vec3::UnitZ());
  const Real d = Real(std::sqrt(2.0)) * Real(0.5);
  for (const Shape* s : {&b, &h}) {
    Manifold m;
    const Transform xa = pose(Vec3(1, 2, 3), q), xb = pose(Vec3(1, 2 + 2 * d - Real(0.004), 3), r);
    ASSERT_TRUE(collide(*s, xa, b, xb, Real(0.02), m));
    test::expect_sane(m, xa, xb);
    ASSERT_EQ(m.point_count, 1);
    EXPECT_NEAR(m.points[0].separation, -0.004, kDepthTol);
    EXPECT_NEAR(m.normal.y(), 1, 1e-5);
    EXPECT_LT((test::contact_point(m, xa, 0) - Vec3(1, 2 + d - Real(0.002), 3)).norm(), 1e-4);
  }
}

TEST(SatPolyhedra, RoundHullOnBoxMatchesItsLowestVertex) {
  const Shape ground = test::box(5, Real(0.5), 5);
  for (int n : {8, 32, 128}) {
    const Shape hull = test::round_hull(n, Real(0.5));
    for (Real angle : {Real(0), Real(0.3), Real(1.3)}) {
      const Quat q = axis_angle(angle, Vec3(1, 2, 3));
      Real lo = 1e9;
      for (const Vec3& v : hull.hull->vertices) lo = std::min(lo, (q * v).y());
      const Transform xa = pose(Vec3(0, Real(-0.5), 0)), xb = pose(Vec3(0, -lo - Real(1e-3), 0), q);
      Manifold m;
      ASSERT_TRUE(collide(ground, xa, hull, xb, Real(0.02), m)) << n;
      test::expect_sane(m, xa, xb);
      ASSERT_GE(m.point_count, 1);
      Real deepest = 1;
      for (int k = 0; k < m.point_count; ++k) deepest = std::min(deepest, m.points[k].separation);
      EXPECT_NEAR(deepest, -1e-3, kDepthTol) << n << " " << angle;
      EXPECT_NEAR(m.normal.y(), 1, 1e-5);
    }
  }
}

// The reproducer perf_20_hulls_200pts.json: the SAT's edge query costs E_a x E_b, so a pair of
// 200-point hulls (about 594 edges each, 353,000 edge pairs) goes to GJK/EPA, while boxes, and
// hulls of up to 64 points against each other (186 edges: 34,600 pairs), keep the SAT's
// clipped manifold. The pair that changed route still finds its contact: a round hull of 200
// points pressed 2 cm into another meets it, along the line of their centres.
TEST(SatPolyhedra, LargeHullPairsTakeGjkByTheirEdgeCount) {
  const Shape box = test::box(Real(0.5), Real(0.5), Real(0.5));
  const Shape h64 = test::round_hull(64, Real(0.5));
  const Shape h200 = test::round_hull(200, Real(0.5));
  const Shape h256 = test::round_hull(256, Real(0.5));
  EXPECT_TRUE(sat_is_affordable(box, box));
  EXPECT_TRUE(sat_is_affordable(box, h256));
  EXPECT_TRUE(sat_is_affordable(h64, h64));
  EXPECT_FALSE(sat_is_affordable(h200, h200));
  EXPECT_FALSE(sat_is_affordable(h64, h256));
  Real top = -1e9, bottom = 1e9;
  for (const Vec3& v : h200.hull->vertices) {
    top = std::max(top, v.y());
    bottom = std::min(bottom, v.y());
  }
  const Transform xa = pose(Vec3(0, 0, 0)), xb = pose(Vec3(0, top - bottom - Real(0.02), 0));
  Manifold m;
  ASSERT_TRUE(collide(h200, xa, h200, xb, Real(0.02), m));
  test::expect_sane(m, xa, xb);
  ASSERT_GE(m.point_count, 1);
  Real deepest = 1;
  for (int k = 0; k < m.point_count; ++k) deepest = std::min(deepest, m.points[k].separation);
  // The top and bottom vertices lie off the y axis (by up to 0.5 sqrt(2 / 200) = 5 cm), so the
  // contact is that of the facets there: penetrating, by no more than the 2 cm pressed in.
  EXPECT_LT(deepest, Real(0));
  EXPECT_GT(deepest, Real(-0.02) - Real(1e-4));
  EXPECT_GT(m.normal.y(), Real(0.95));
}

TEST(SatPolyhedra, DegenerateInputStaysFinite) {
  const Shape unit = test::box(Real(0.5), Real(0.5), Real(0.5));
  const Shape thin = test::box(Real(0.5), Real(5e-4), Real(0.5));
  const Shape huge = test::box(1000, 1000, 1000);
  const Shape tiny = test::box(Real(0.01), Real(0.01), Real(0.01));
  const Shape hull = test::round_hull(32, Real(0.5));
  struct Case {
    const Shape* a;
    const Shape* b;
    Transform xa, xb;
  };
  const Quat q = axis_angle(Real(0.3), Vec3(1, 1, 0));
  const Case cases[] = {
      {&unit, &unit, pose(Vec3(1, 2, 3)), pose(Vec3(1, 2, 3))},          // identical, same pose
      {&unit, &unit, pose(Vec3::Zero()), pose(Vec3(0, 1, 0))},           // touching exactly
      {&unit, &hull, pose(Vec3::Zero(), q), pose(Vec3::Zero())},         // coincident centres
      {&hull, &hull, pose(Vec3::Zero(), q), pose(Vec3::Zero(), q)},      // identical hulls
      {&thin, &thin, pose(Vec3::Zero()), pose(Vec3(0, Real(9e-4), 0))},  // very thin boxes
      {&thin, &thin, pose(Vec3::Zero()), pose(Vec3(Real(0.2), 0, 0), q)},
      {&huge, &tiny, pose(Vec3(0, -1000, 0)), pose(Vec3(0, Real(0.009), 0), q)},
      {&tiny, &huge, pose(Vec3(0, Real(0.009), 0), q), pose(Vec3(0, -1000, 0))},
  };
  for (const Case& c : cases) {
    Manifold m;
    ASSERT_TRUE(collide(*c.a, c.xa, *c.b, c.xb, Real(0.02), m));
    test::expect_sane(m, c.xa, c.xb);
    EXPECT_GE(m.point_count, 1);
  }
}

// Two boxes take their own routine (box_box.cpp: 15 axes from one rotation, clipping against the
// reference face's rectangle in its box's frame); the same boxes as hulls take the polyhedron SAT
// (the Gauss-map edge query over all edge pairs, clipping against the face's side planes). Over
// random poses near contact the two must agree: the same outcome, kind of contact, normal,
// points in the same order and depths.
TEST(SatPolyhedra, BoxPairMatchesTheSatOfTheSameBoxesAsHulls) {
  const Shape a = test::box(Real(0.6), Real(0.3), Real(0.45));
  const Shape b = test::box(Real(0.4), Real(0.5), Real(0.2));
  const Shape ha = test::box_hull(Real(0.6), Real(0.3), Real(0.45));
  const Shape hb = test::box_hull(Real(0.4), Real(0.5), Real(0.2));
  std::mt19937 rng(17);
  std::uniform_real_distribution<Real> u(-1, 1);
  int edge_contacts = 0, compared = 0;
  for (int i = 0; i < 800; ++i) {
    const Quat qa = Quat{u(rng), u(rng), u(rng), u(rng)}.normalized();
    const Quat qb = Quat{u(rng), u(rng), u(rng), u(rng)}.normalized();
    const Vec3 dir = test::draw3(rng, u).normalized();
    // Centres a little nearer than the boxes reach along dir (their supports along it touch).
    Real reach = 0;
    for (int k = 0; k < 3; ++k) {
      reach += std::abs(dir.dot(qa * (Vec3::Unit(k) * a.half_extents[k])));
      reach += std::abs(dir.dot(qb * (Vec3::Unit(k) * b.half_extents[k])));
    }
    const Transform xa = pose(Vec3(1, 2, 3), qa);
    const Transform xb = pose(Vec3(1, 2, 3) + (reach - Real(0.08) + Real(0.06) * u(rng)) * dir, qb);
    Manifold box_m, hull_m;
    const bool box_hit = collide(a, xa, b, xb, Real(0.02), box_m);
    const bool hull_hit = collide(ha, xa, hb, xb, Real(0.02), hull_m);
    ASSERT_EQ(box_hit, hull_hit) << i;
    if (!box_hit) continue;
    ++compared;
    edge_contacts += (box_m.points[0].feature_id >> 30) == (kFeatureEdges >> 30);
    ASSERT_EQ(box_m.point_count, hull_m.point_count) << i;
    EXPECT_LT((box_m.normal - hull_m.normal).norm(), 1e-4) << i;
    for (int k = 0; k < box_m.point_count; ++k) {
      EXPECT_NEAR(box_m.points[k].separation, hull_m.points[k].separation, kDepthTol) << i;
      EXPECT_LT((box_m.points[k].anchor_a - hull_m.points[k].anchor_a).norm(), 1e-4) << i;
    }
  }
  EXPECT_GT(compared, 250);
  EXPECT_GT(edge_contacts, 50) << compared;
}

// Over one of the box's faces (the foot of its nearer end on the face), a segment is exactly as
// far from the box as that end is above the face, and the capsule pairs take that distance
// without GJK; beside the faces, the best face's separation is only a lower bound of it. Both
// against GJK's distance of the capsule's core, for 600 random segments around a box.
TEST(SatSegment, FaceQueryGivesTheDistanceOverAFaceAndABoundBesideIt) {
  const Shape box = test::box(1, Real(0.5), Real(0.75));
  const Quat turn = axis_angle(Real(0.4), Vec3(1, 2, 3));
  Polyhedron poly;
  make_polyhedron(box, turn, Vec3::Zero(), poly);
  std::mt19937 rng(5);
  std::uniform_real_distribution<Real> u(-1, 1);
  int over = 0, beside = 0;
  for (int i = 0; i < 600; ++i) {
    const Vec3 centre = turn * Vec3{2 * u(rng), Real(1.1) + Real(0.5) * u(rng), Real(1.5) * u(rng)};
    const Vec3 dir = test::draw3(rng, u).normalized();
    const Real half = Real(0.35) + Real(0.25) * u(rng);
    const SegmentFaceQuery q = query_segment_faces(centre - half * dir, centre + half * dir, poly);
    const Shape core = test::capsule(Real(0.1), half);
    const Transform xc{centre, Quat::FromTwoVectors(Vec3::UnitY(), dir)};
    const GjkResult g = gjk_distance(core, xc, box, Transform{Vec3::Zero(), turn}, false);
    if (g.overlap) continue;
    if (q.foot_on_face && q.separation > 0) {
      ++over;
      EXPECT_NEAR(q.separation, g.distance, kDepthTol) << i;
    } else {
      ++beside;
      EXPECT_LE(q.separation, g.distance + kDepthTol) << i;
    }
  }
  EXPECT_GT(over, 100);
  EXPECT_GT(beside, 100);
}

// Found by fuzz_narrowphase (tests/fuzz/corpus/narrowphase/regression_folded_hull_no_contact): two
// hulls overlapping by 1.75 m (the oracle's SAT depth over all face and edge-pair axes) got no
// contact: the first hull's cloud has three collinear points, two of them 6e-5 m apart, and its
// hull came out folded, so an edge pair of the fold read as separating. The SAT's axis has the
// largest separation (-depth) up to its tolerances: a face is kept against a better edge pair
// within kEdgeRelTol and kAbsTol, and against the better other face within kFaceRelTol and
// kAbsTol; a clipped point of the convex incident face is no deeper than the incident hull
// along that axis. So no point is deeper than (1 + kFaceRelTol) (depth + kAbsTol) /
// (1 - kEdgeRelTol) + kAbsTol.
TEST(Sat, HullWithNearlyCoincidentCollinearPointsTouches) {
  ShapeDef da;
  da.type = ShapeType::ConvexHull;
  da.points = {
      {0x1.8fb59p-1f, -0x1.d521ep-4f, -0x1.b88bb8p+0f},
      {0x1.6fa57p-1f, -0x1.ed25ecp-1f, -0x1.d13fd2p+0f},
      {0x1.51575p+0f, -0x1.aaa9a8p-2f, 0x1.b96db8p-1f},
      {-0x1.885d88p-1f, -0x1.667f66p+0f, 0x1.d56dd8p-1f},
      {0x1.62b96p-2f, -0x1.354b34p+0f, 0x1.669f68p+0f},
      {-0x1.461346p+0f, 0x1.a093ap+0f, 0x1.71618p-4f},
      {-0x1.ab71bp-3f, -0x1.ff94p+0f, -2},
      {-2, -2, -2},
      {-2, -2, -0x1.fffcp+0f},
      {-2, -2, -0x1.ebffecp+0f},
      {0x1.480548p-1f, 0x1.e43de8p-1f, -0x1.dcafdcp+0f},
  };
  ShapeDef db;
  db.type = ShapeType::ConvexHull;
  db.points = {
      {0x1.b973b8p+0f, 0x1.31c93p-2f, 0x1.47094p-2f},
      {-0x1.90bd9p-1f, -0x1.561b56p+0f, -0x1.1ee12p-4f},
      {-0x1.91ab92p+0f, 0x1.44d14p-3f, -0x1.e942p-5f},
      {-0x1.ffc4p+0f, -2, -2},
      {-2, -0x1.4fff5p+0f, -0x1.6a936cp+0f},
      {-0x1.bae1cp-4f, -0x1.10c51p-1f, 0x1.43d54p-1f},
      {0x1.c3c5cp-1f, 0x1.932794p+0f, -0x1.55e756p+0f},
      {0x1.2b2b2cp+0f, 0x1.2b2b2cp+0f, 0x1.2b2b2cp+0f},
      {0x1.2b2b2cp+0f, 0x1.2b2b2cp+0f, -0x1.b4d7b4p+0f},
      {-0x1.bd35bcp-1f, 0x1.c4f7c4p+0f, -2},
  };
  const Shape a = make_shape(da), b = make_shape(db);
  const Transform xa =
      pose(Vec3(-0x1.2734a8p+1f, -0x1.2767a8p+1f, -0x1.55aed6p+1f),
           Quat(0x1.6ea57p-2f, 0x1.e342p-6f, -0x1.9a4998p-3f, -0x1.f94bfap-1f).normalized());
  const Transform xb = pose(Vec3(-3, -3, -3), Quat(-1, -1, -1, -1).normalized());
  const double depth = oracle::sat_depth(oracle::place_hull(a, xa), oracle::place_hull(b, xb));
  ASSERT_NEAR(depth, 1.748, 0.01);

  Manifold m;
  ASSERT_TRUE(collide(a, xa, b, xb, 0, m));
  ASSERT_GE(m.point_count, 1u);
  EXPECT_NEAR(m.normal.norm(), 1, 1e-5);
  const double bound = (1 + kFaceRelTol) * (depth + kAbsTol) / (1 - kEdgeRelTol) + kAbsTol;
  Real deepest = 0;
  for (uint32_t k = 0; k < m.point_count; ++k) {
    deepest = std::min(deepest, m.points[k].separation);
    EXPECT_GE(m.points[k].separation, -bound);
  }
  EXPECT_LT(deepest, 0);
}

// A hull (11 points) and a box 0.65 m apart along an edge pair's axis (found by fuzz_narrowphase,
// corpus/narrowphase/regression_hull_box_edge_gap). The edge query's best pair measured a gap of
// 1.19 m from its two edges, which the supports along its axis contradict (the shapes overlap
// 2.3 m along it); dropping it left the faces, whose best gap is -1 mm: a contact 1 mm deep
// between shapes 0.65 m apart. Measured by the supports, the pairs give the true gap.
TEST(Sat, EdgePairWithAWrongGapDoesNotHideTheSeparatingPair) {
  ShapeDef da;
  da.type = ShapeType::ConvexHull;
  da.points = {
      {0x1.8fb59p-1f, -0x1.9521ap-4f, 0x1.b921cp-4f},
      {0x1.28ab28p+0f, 0x1.2b2b2cp+0f, 0x1.2b2b2cp+0f},
      {0x1.2b2b2cp+0f, 0x1.2b2b2cp+0f, 0x1.2b2b2cp+0f},
      {-0x1.376d38p-1f, -0x1.0adf0cp+0f, -2},
      {-2, -2, -0x1.fffcp+0f},
      {0x1.10871p+0f, -2, -2},
      {-0x1.c8efc8p+0f, -0x1.5ac75cp+0f, -0x1.fdb3fep+0f},
      {-2, -2, -2},
      {-0x1.9ac79cp+0f, 0x1.fe3p+0f, 0x1.aff9bp-2f},
      {2, 2, 2},
      {2, 0x1.16891p-2f, 0x1.54316p-3f},
  };
  ShapeDef db;
  db.type = ShapeType::Box;
  db.half_extents = Vec3(0x1.bababcp-2f, 0x1.971256p+0f, 0x1.983ea6p+0f);
  const Shape a = make_shape(da), b = make_shape(db);
  const Transform xa = pose(Vec3(0x1.5a52dcp+1f, 0x1.1ab39cp+1f, 0x1.4df45p+0f),
                            Quat(0x1.304012p-1f, -0x1.02d40cp-1f, 0x1.c4f43ap-2f, 0x1.c4f43ap-2f));
  const Transform xb =
      pose(Vec3(0x1.c0c0cp+0f, 0x1.c0c0cp+0f, -0x1.4702c8p+1f),
           Quat(-0x1.f2e802p-3f, -0x1.1e5786p-1f, -0x1.1ee03cp-1f, -0x1.1ee03cp-1f));
  const double distance =
      oracle::polytope_distance(oracle::place_hull(a, xa), oracle::place_box(b.half_extents, xb));
  ASSERT_NEAR(distance, 0.6468, 1e-3);

  Manifold m;
  EXPECT_FALSE(collide(a, xa, b, xb, 0, m));
  EXPECT_FALSE(collide(a, xa, b, xb, Real(0.5), m));
  // Within the speculative distance: one contact, at the gap (GJK's tolerance and float supports
  // of coordinates near 4 m: well under 1e-3).
  ASSERT_TRUE(collide(a, xa, b, xb, 1, m));
  for (uint32_t k = 0; k < m.point_count; ++k) {
    EXPECT_NEAR(m.points[k].separation, distance, 1e-3);
  }
}

// Two tetrahedra 57 mm apart, closest tip to edge (found by fuzz_narrowphase,
// corpus/narrowphase/regression_hull_hull_edge_bound). No SAT axis is the direction of a tip-to-
// edge distance: the best, an edge pair's whose segments' nearest points are not their lines',
// measured 53.4 mm, a bound from below. Within a speculative distance of 56 mm it made a contact
// between shapes farther apart than that; GJK over the vertices now decides.
TEST(Sat, EdgeAxisBelowTheDistanceMakesNoContactBeyondTheSpeculativeDistance) {
  ShapeDef da;
  da.type = ShapeType::ConvexHull;
  da.points = {
      {0x1.8fb59p-1f, -0x1.d521ep-4f, -0x1.f94bfap+0f},
      {-0x1.0ba1p-4f, 0x1.31c93p-2f, -0x1.ff92p-3f},
      {0x1.21032p+0f, 0x1.232324p+0f, 0x1.232324p+0f},
      {0x1.232324p+0f, 0x1.232324p+0f, -0x1.128d14p-1f},
  };
  ShapeDef db;
  db.type = ShapeType::ConvexHull;
  db.points = {
      {0x1.69697p-2f, -0x1.fd53fep+0f, -0x1p+1f},
      {-0x1p+1f, -0x1p+1f, 0x1.40054p-1f},
      {-0x1.d445d4p-1f, -0x1.ec3fecp+0f, -0x1.76bd78p-1f},
      {-0x1.e1e7e2p+0f, 0x1.bde3bcp+0f, 0x1.6a1d68p-1f},
      {-0x1.ea29e8p-2f, -0x1.738774p+0f, 0x1.178318p+0f},
  };
  const Shape a = make_shape(da), b = make_shape(db);
  const Transform xa =
      pose(Vec3(0x1.39f1b8p+1f, -0x1.407d4p-2f, -0x1.950a96p+0f),
           Quat(-0x1.7b5d6p-1f, -0x1.aa0f8p-2f, -0x1.715532p-2f, 0x1.89a9f2p-2f).normalized());
  const Transform xb =
      pose(Vec3(0x1.1a0418p+0f, -0x1.1fb92p-3f, -0x1.662d6p-2f),
           Quat(0x1.d32488p-2f, 0x1.d5f7bep-2f, -0x1.4ab2e8p-3f, -0x1.7d7dep-1f).normalized());
  const double distance =
      oracle::polytope_distance(oracle::place_hull(a, xa), oracle::place_hull(b, xb));
  ASSERT_NEAR(distance, 0.05699, 1e-4);

  Manifold m;
  EXPECT_FALSE(collide(a, xa, b, xb, Real(0.056), m));
  EXPECT_FALSE(collide(a, xa, b, xb, Real(0.0565), m));
  // Within the speculative distance the contact stays, its gap no more than the distance (a gap
  // below it only slows the approach).
  ASSERT_TRUE(collide(a, xa, b, xb, Real(0.058), m));
  for (uint32_t k = 0; k < m.point_count; ++k) {
    EXPECT_LE(m.points[k].separation, distance + 1e-4);
    EXPECT_GT(m.points[k].separation, 0);
  }
}

}  // namespace narrowphase_sat_test
}  // namespace elan::detail
