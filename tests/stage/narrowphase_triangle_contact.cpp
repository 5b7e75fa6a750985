// SPDX-License-Identifier: MIT
// Convex shapes against one triangle: normals and separations against closed forms, active and
// inactive edges (no ghost collisions), one-sided triangles, feature ids under a small slide.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "core/base/heightfield.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase/shape_point.hpp"
#include "narrowphase/triangle_contact.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_triangle_contact_test {

using test::at;
using test::axis_angle;
using test::box;
using test::box_hull;
using test::capsule;
using test::cylinder;
using test::sphere;

// GJK's relative tolerance (1e-5 in float) on distances of about 1 m, and EPA's (1e-5 of the
// depth plus rounding of the polytope's size, about 1e-6 m): 1e-4 m covers both. The closed forms
// (sphere) are exact to rounding.
constexpr Real kTol = sizeof(Real) == 4 ? Real(1e-4) : Real(1e-8);
constexpr Real kSpec = Real(0.02);

// The triangle (-5, 0, -5), (-5, 0, 15), (15, 0, -5): its front faces +y; edge 0 lies on
// x = -5, edge 2 on z = -5, edge 1 (the hypotenuse, x + z = 10) is far from the tests.
MeshTriangle big_triangle(uint8_t active = 7, bool two_sided = true) {
  MeshTriangle t;
  t.v[0] = Vec3(-5, 0, -5);
  t.v[1] = Vec3(-5, 0, 15);
  t.v[2] = Vec3(15, 0, -5);
  t.active_edges = active;
  t.two_sided = two_sided;
  t.index = 3;
  return t;
}

void expect_vec(const Vec3& got, const Vec3& want, Real tol) {
  EXPECT_NEAR(got.x(), want.x(), tol);
  EXPECT_NEAR(got.y(), want.y(), tol);
  EXPECT_NEAR(got.z(), want.z(), tol);
}

// Every point of a face contact: separation s and height (from A's centre) of the midpoint.
void expect_face_points(const TriangleContact& c, const Transform& xa, Real s, int count) {
  ASSERT_EQ(c.count, count);
  expect_vec(c.normal, -Vec3::UnitY(), kTol);
  for (int k = 0; k < c.count; ++k) {
    EXPECT_NEAR(c.separation[k], s, kTol);
    // Midway between A's surface (at height s) and the plane y = 0.
    EXPECT_NEAR(xa.position.y() + c.points[k].y(), Real(0.5) * s, kTol);
  }
}

TEST(TriangleContact, SphereRestingOnTheFace) {
  TriangleContact c;
  const Transform xa = at(1, Real(0.49), 1);
  ASSERT_TRUE(collide_triangle(sphere(Real(0.5)), xa, big_triangle(), kSpec, c));
  expect_face_points(c, xa, Real(-0.01), 1);
  // From below (two-sided): the normal turns with the side the centre is on.
  const Transform below = at(1, Real(-0.49), 1);
  ASSERT_TRUE(collide_triangle(sphere(Real(0.5)), below, big_triangle(), kSpec, c));
  expect_vec(c.normal, Vec3::UnitY(), kTol);
  EXPECT_NEAR(c.separation[0], Real(-0.01), kTol);
}

TEST(TriangleContact, SphereApartWithinAndBeyondTheSpeculativeDistance) {
  TriangleContact c;
  ASSERT_TRUE(collide_triangle(sphere(Real(0.5)), at(0, Real(0.515), 0), big_triangle(), kSpec, c));
  EXPECT_NEAR(c.separation[0], Real(0.015), kTol);
  EXPECT_FALSE(collide_triangle(sphere(Real(0.5)), at(0, Real(0.53), 0), big_triangle(), kSpec, c));
}

TEST(TriangleContact, SphereBesideAnActiveEdgeTakesTheEdgeNormal) {
  // Centre 0.3 m beyond edge 0 (x = -5) and 0.1 m up: the closest point is (-5, 0, 0).
  TriangleContact c;
  const Transform xa = at(Real(-5.3), Real(0.1), 0);
  ASSERT_TRUE(collide_triangle(sphere(Real(0.5)), xa, big_triangle(), kSpec, c));
  const Vec3 d(Real(0.3), Real(-0.1), 0);
  expect_vec(c.normal, d.normalized(), kTol);
  EXPECT_NEAR(c.separation[0], d.norm() - Real(0.5), kTol);
}

TEST(TriangleContact, SphereBesideAnInactiveEdgeTakesTheFaceNormal) {
  // Edge 0 inactive: the surface goes on past it, so the sphere is 0.1 m above that plane.
  TriangleContact c;
  const Transform xa = at(Real(-5.3), Real(0.1), 0);
  ASSERT_TRUE(collide_triangle(sphere(Real(0.5)), xa, big_triangle(0b110), kSpec, c));
  expect_vec(c.normal, -Vec3::UnitY(), kTol);
  EXPECT_NEAR(c.separation[0], Real(0.1) - Real(0.5), kTol);
}

TEST(TriangleContact, SphereBesideAVertex) {
  // Beyond vertex 0 in x and z: its closest point is (-5, 0, -5).
  const Transform xa = at(Real(-5.2), Real(0.2), Real(-5.3));
  const Vec3 d = Vec3(-5, 0, -5) - xa.position;
  TriangleContact c;
  // Both edges at the vertex active: the vertex's normal.
  ASSERT_TRUE(collide_triangle(sphere(Real(0.5)), xa, big_triangle(), kSpec, c));
  expect_vec(c.normal, d.normalized(), kTol);
  EXPECT_NEAR(c.separation[0], d.norm() - Real(0.5), kTol);
  // Both inactive (edges 0 and 2): the face's.
  ASSERT_TRUE(collide_triangle(sphere(Real(0.5)), xa, big_triangle(0b010), kSpec, c));
  expect_vec(c.normal, -Vec3::UnitY(), kTol);
  EXPECT_NEAR(c.separation[0], Real(0.2) - Real(0.5), kTol);
  // Edge 0 (x = -5) active, edge 2 (z = -5) inactive: the vertex's normal leans out past z = -5
  // (the surface goes on there), so the face's again.
  ASSERT_TRUE(collide_triangle(sphere(Real(0.5)), xa, big_triangle(0b011), kSpec, c));
  expect_vec(c.normal, -Vec3::UnitY(), kTol);
}

TEST(TriangleContact, CapsuleLyingAlongTheFaceGivesTwoPoints) {
  const Shape s = capsule(Real(0.2), Real(0.5));
  const Transform xa = at(1, Real(0.19), 0, axis_angle(Real(std::numbers::pi / 2), Vec3::UnitZ()));
  TriangleContact c;
  ASSERT_TRUE(collide_triangle(s, xa, big_triangle(), kSpec, c));
  expect_face_points(c, xa, Real(-0.01), 2);
  // The two points are the segment's ends, 1 m apart along x.
  EXPECT_NEAR(std::abs(c.points[0].x() - c.points[1].x()), 1, kTol);
  // Upright: one point under the lower end.
  const Transform up = at(1, Real(0.69), 0);
  ASSERT_TRUE(collide_triangle(s, up, big_triangle(), kSpec, c));
  expect_face_points(c, up, Real(-0.01), 1);
}

TEST(TriangleContact, BoxHullAndCylinderRestingOnTheFace) {
  TriangleContact c;
  const Transform xa = at(0, Real(0.49), 0, axis_angle(Real(0.3), Vec3::UnitY()));
  ASSERT_TRUE(collide_triangle(box(Real(0.5), Real(0.5), Real(0.5)), xa, big_triangle(), kSpec, c));
  expect_face_points(c, xa, Real(-0.01), 4);
  ASSERT_TRUE(
      collide_triangle(box_hull(Real(0.5), Real(0.5), Real(0.5)), xa, big_triangle(), kSpec, c));
  expect_face_points(c, xa, Real(-0.01), 4);
  // A cylinder standing on its cap: the cap's polygon, reduced to four.
  ASSERT_TRUE(collide_triangle(cylinder(Real(0.3), Real(0.5)), xa, big_triangle(), kSpec, c));
  expect_face_points(c, xa, Real(-0.01), 4);
  // Apart within the speculative distance, and beyond it.
  ASSERT_TRUE(collide_triangle(box(Real(0.5), Real(0.5), Real(0.5)), at(0, Real(0.51), 0),
                               big_triangle(), kSpec, c));
  expect_face_points(c, at(0, Real(0.51), 0), Real(0.01), 4);
  EXPECT_FALSE(collide_triangle(box(Real(0.5), Real(0.5), Real(0.5)), at(0, Real(0.53), 0),
                                big_triangle(), kSpec, c));
}

TEST(TriangleContact, BoxBesideAnEdge) {
  // A box 0.1 m beyond edge 0 (x = -5), reaching 0.3 m below the plane: apart from the triangle.
  const Shape b = box(Real(0.5), Real(0.5), Real(0.5));
  const Transform xa = at(Real(-5.6), Real(0.2), 0);
  TriangleContact c;
  // Active (a boundary): the edge pushes the box sideways, 0.1 m away.
  ASSERT_TRUE(collide_triangle(b, xa, big_triangle(), Real(0.2), c));
  expect_vec(c.normal, Vec3::UnitX(), kTol);
  for (int k = 0; k < c.count; ++k) EXPECT_NEAR(c.separation[k], Real(0.1), kTol);
  // Inactive: the surface goes on past the edge, and the box is 0.3 m into it. That is the
  // neighbour's contact, the triangle the box is over: this one's plane, carried out under a box
  // beside it, would say the same on a flat surface and a depth that is not there on a curved one
  // (a box on a bumpy terrain held up by the plane of a triangle it does not reach).
  EXPECT_FALSE(collide_triangle(b, xa, big_triangle(0b110), Real(0.2), c));
  MeshTriangle neighbour;
  neighbour.v[0] = Vec3(-5, 0, 15), neighbour.v[1] = Vec3(-5, 0, -5);
  neighbour.v[2] = Vec3(-25, 0, -5);
  neighbour.active_edges = 0b110;  // edge 0 is the shared one
  ASSERT_TRUE(collide_triangle(b, xa, neighbour, Real(0.2), c));
  expect_vec(c.normal, -Vec3::UnitY(), kTol);
  EXPECT_EQ(c.count, 4);
  for (int k = 0; k < c.count; ++k) EXPECT_NEAR(c.separation[k], Real(-0.3), kTol);
}

// A hull needle, tip down: a tetrahedron 1 m tall on a base of radius 0.05 m. Sunk by p, it is
// only about p / 20 wide at the plane.
Shape needle() {
  ShapeDef d;
  d.type = ShapeType::ConvexHull;
  d.points.emplace_back(0, Real(-0.5), 0);
  for (int k = 0; k < 3; ++k) {
    const Real t = Real(2 * std::numbers::pi / 3) * Real(k);
    d.points.emplace_back(Real(0.05) * std::cos(t), Real(0.5), Real(0.05) * std::sin(t));
  }
  return make_shape(d);
}

Real deepest_of(const TriangleContact& c) {
  Real deepest = c.separation[0];
  for (int k = 1; k < c.count; ++k) deepest = std::min(deepest, c.separation[k]);
  return deepest;
}

// A body sunk into the face near an active edge: once its foot is farther from the edge than it
// is deep, the least push is along the face's normal (sunk_within_face), and the contact is the
// face's exactly; nearer the edge than it is deep, a narrow body is pushed out over the edge.
TEST(TriangleContact, SunkNearAnActiveEdgeTakesTheFaceUntilTheEdgeIsNearer) {
  const Shape s = needle();
  const Real depth = Real(0.02);
  const Vec3 tip = support(s, -Vec3::UnitY());
  TriangleContact c;
  // Foot 0.03 m from edge 0 (x = -5): the face's contact, its normal and depth exact.
  Transform xa = at(Real(-4.97) - tip.x(), -depth - tip.y(), -tip.z());
  ASSERT_TRUE(collide_triangle(s, xa, big_triangle(), kSpec, c));
  EXPECT_EQ(c.normal, -Vec3::UnitY());
  EXPECT_NEAR(deepest_of(c), -depth, kTol);
  // Foot 0.01 m from it: out over the edge (about 0.011 m, less than the depth), along -x.
  xa.position.x() = Real(-4.99) - tip.x();
  ASSERT_TRUE(collide_triangle(s, xa, big_triangle(), kSpec, c));
  EXPECT_GT(c.normal.x(), Real(0.9));
  for (int k = 0; k < c.count; ++k) EXPECT_GT(c.separation[k], -depth + Real(0.005));
}

// The quad [-1, 1] x [-1, 1] at y = 0 as two triangles sharing the diagonal (-1, -1)-(1, 1),
// which is inactive in both (coplanar neighbours); the outer edges are active.
MeshTriangle quad_half(int which) {
  MeshTriangle t;
  if (which == 0) {
    t.v[0] = Vec3(-1, 0, -1), t.v[1] = Vec3(1, 0, 1), t.v[2] = Vec3(1, 0, -1);
    t.active_edges = 0b110;  // edge 0 is the diagonal
  } else {
    t.v[0] = Vec3(1, 0, 1), t.v[1] = Vec3(-1, 0, -1), t.v[2] = Vec3(-1, 0, 1);
    t.active_edges = 0b110;
  }
  t.index = uint32_t(which);
  return t;
}

TEST(TriangleContact, BoxAcrossTheInternalEdgeGetsTheFaceNormal) {
  const Shape b = box(Real(0.3), Real(0.3), Real(0.3));
  // Across the diagonal at several offsets and turns, 1 cm deep: every triangle's contact takes
  // the face normal and its points sit at the face's height, whichever feature GJK/EPA found.
  for (const Real offset : {Real(0), Real(0.1), Real(0.25), Real(0.35)}) {
    for (const Real turn : {Real(0), Real(0.4), Real(0.785398)}) {
      const Transform xa = at(offset, Real(0.29), -offset, axis_angle(turn, Vec3::UnitY()));
      int touching = 0;
      for (int which = 0; which < 2; ++which) {
        TriangleContact c;
        if (!collide_triangle(b, xa, quad_half(which), kSpec, c)) continue;
        ++touching;
        SCOPED_TRACE(testing::Message()
                     << "offset " << offset << " turn " << turn << " tri " << which);
        expect_vec(c.normal, -Vec3::UnitY(), kTol);
        for (int k = 0; k < c.count; ++k) EXPECT_NEAR(c.separation[k], Real(-0.01), kTol);
      }
      EXPECT_GE(touching, 1);
    }
  }
  // Entirely over triangle 1 (x < z), 2 cm below the plane, its corner (x + 0.3, z - 0.3) 1 mm
  // from the diagonal: triangle 0 sees a box beside its edge (GJK would push it sideways, a ghost
  // collision), and must not push; triangle 1 gives the face normal with the box's depth.
  const Real cx = Real(-0.5), cz = cx + Real(0.6) + Real(0.001) * Real(1.41421356);
  const Transform xa = at(cx, Real(0.28), cz);
  TriangleContact c;
  if (collide_triangle(b, xa, quad_half(0), kSpec, c)) {
    expect_vec(c.normal, -Vec3::UnitY(), kTol);
    for (int k = 0; k < c.count; ++k) EXPECT_NEAR(c.separation[k], Real(-0.02), kTol);
  }
  ASSERT_TRUE(collide_triangle(b, xa, quad_half(1), kSpec, c));
  expect_vec(c.normal, -Vec3::UnitY(), kTol);
  EXPECT_EQ(c.count, 4);
  for (int k = 0; k < c.count; ++k) EXPECT_NEAR(c.separation[k], Real(-0.02), kTol);
}

TEST(TriangleContact, OneSidedTriangleFromBehindGivesNothing) {
  const MeshTriangle t = big_triangle(7, false);
  TriangleContact c;
  EXPECT_FALSE(collide_triangle(sphere(Real(0.5)), at(0, Real(-0.3), 0), t, kSpec, c));
  EXPECT_FALSE(
      collide_triangle(box(Real(0.5), Real(0.5), Real(0.5)), at(0, Real(-0.3), 0), t, kSpec, c));
  EXPECT_FALSE(collide_triangle(capsule(Real(0.2), Real(0.5)), at(0, Real(-0.3), 0), t, kSpec, c));
  // From the front it collides as a two-sided one.
  ASSERT_TRUE(collide_triangle(sphere(Real(0.5)), at(0, Real(0.3), 0), t, kSpec, c));
  expect_vec(c.normal, -Vec3::UnitY(), kTol);
}

TEST(TriangleContact, FeatureIdsStayWhileSlidingOnOneTriangle) {
  const Shape shapes[] = {box(Real(0.5), Real(0.2), Real(0.4)), capsule(Real(0.2), Real(0.5)),
                          cylinder(Real(0.3), Real(0.5)), sphere(Real(0.5))};
  for (const Shape& s : shapes) {
    const Quat q = s.type == ShapeType::Capsule
                       ? axis_angle(Real(std::numbers::pi / 2), Vec3::UnitZ())
                       : axis_angle(Real(0.3), Vec3::UnitY());
    // The centre's height when A's lowest point is 1 cm into the face.
    const Real h = -(q * support(s, q.conjugate() * Vec3(-Vec3::UnitY()))).y();
    TriangleContact c0, c1;
    const Transform x0 = at(Real(0.3), h - Real(0.01), Real(-1), q);
    const Transform x1 = at(Real(0.301), h - Real(0.01), Real(-1), q);
    ASSERT_TRUE(collide_triangle(s, x0, big_triangle(), kSpec, c0));
    ASSERT_TRUE(collide_triangle(s, x1, big_triangle(), kSpec, c1));
    ASSERT_EQ(c0.count, c1.count);
    std::vector<uint32_t> a(c0.feature, c0.feature + c0.count);
    std::vector<uint32_t> b(c1.feature, c1.feature + c1.count);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << "shape type " << int(s.type);
    // Distinct points have distinct ids (warm starting matches by id).
    EXPECT_EQ(std::adjacent_find(a.begin(), a.end()), a.end());
  }
}

// One of each convex shape, about the size of a heightfield cell below.
std::array<Shape, 6> every_shape() {
  return {sphere(Real(0.3)),
          capsule(Real(0.2), Real(0.4)),
          box(Real(0.3), Real(0.2), Real(0.5)),
          cylinder(Real(0.3), Real(0.2)),
          test::round_hull(20, Real(0.4)),
          box_hull(Real(0.2), Real(0.3), Real(0.4))};
}

// A columns x columns heightfield, 0.5 m cells, heights drawn in [-0.15, 0.15] from rng.
HeightField bumpy_field(uint32_t columns, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<Real> heights(columns * columns);
  for (Real& h : heights) h = Real(0.15) * u(rng);
  return build_heightfield(heights, columns, Real(0.5), Real(0.5));
}

// Heightfield cell (i, j)'s box: x and z between its samples, y between its least and greatest
// height (the composite walk's box for the cell).
void cell_box(const HeightField& field, uint32_t i, uint32_t j, Vec3& lo, Vec3& hi) {
  const Real h[4] = {field.height(i, j), field.height(i + 1, j), field.height(i, j + 1),
                     field.height(i + 1, j + 1)};
  lo = Vec3(Real(i) * field.spacing_x, std::min({h[0], h[1], h[2], h[3]}),
            Real(j) * field.spacing_z);
  hi = Vec3(Real(i + 1) * field.spacing_x, std::max({h[0], h[1], h[2], h[3]}),
            Real(j + 1) * field.spacing_z);
}

// The claim sunk_within_face rests on, over every convex shape at random turns: sunk by p with
// its lowest point's foot farther than p from every edge, no direction separates A from the
// triangle by less than p (EPA's least depth is p, to its tolerance), and the contact is the
// face's.
TEST(TriangleContact, SunkWithinTheFaceLeastDepthIsAlongTheNormal) {
  const std::array<Shape, 6> shapes = every_shape();
  const MeshTriangle t = big_triangle();
  std::mt19937 rng(47);
  std::uniform_real_distribution<float> u(-1, 1);
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Shape& s = shapes[1 + trial % 5];  // the sphere has its closed form
    const Quat q = test::random_turn(rng, u);
    const Vec3 lowest = q * support(s, q.conjugate() * -Vec3::UnitY());
    const Real depth = Real(0.001) + Real(0.02) * (u(rng) + 1);
    // The foot between 1.01 p and 0.3 m from edge 0 (x = -5), near edge 2 (z = -5) as often.
    const Real from_edge = depth * Real(1.01) + Real(0.15) * (u(rng) + 1);
    // Under 5 mm from an edge, EPA's witness may lie within region_of's weight of it (the
    // triangle is 20 m wide), and its own normal stand: only the depth is compared there.
    const bool clear_of_edges = from_edge > depth * Real(1.01) + Real(0.005);
    const Real along = Real(0.5) * (u(rng) + 1);
    const Vec3 foot = trial % 2 == 0 ? Vec3(-5 + from_edge, 0, -5 + from_edge + along)
                                     : Vec3(-5 + from_edge + along, 0, -5 + from_edge);
    const Transform xa = test::pose(foot - depth * Vec3::UnitY() - lowest, q);
    const TriangleQuery query = make_triangle_query(s, xa, kSpec);
    TriangleReach r;
    ASSERT_TRUE(reach_triangle(query, t, r)) << trial;
    Simplex simplex;
    const GjkResult g = gjk_triangle(query.full, r.v, Vec3(-r.face), simplex);
    ASSERT_TRUE(g.overlap) << trial;
    const EpaResult e = epa_triangle(query.full, r.v, simplex);
    ASSERT_TRUE(e.ok) << trial;
    EXPECT_NEAR(e.depth, depth, kTol) << trial;
    if (!clear_of_edges) continue;
    TriangleContact c;
    ASSERT_TRUE(collide_reached_triangle(query, t, r, c)) << trial;
    EXPECT_EQ(c.normal, -Vec3::UnitY()) << trial;
    const Real deepest = deepest_of(c);
    // A cylinder's cap is an octagon in the contact, whose corners need not reach its lowest
    // point on the rim; every other shape's supporting feature holds it.
    if (s.type == ShapeType::Cylinder) {
      EXPECT_GT(deepest, -depth - kTol) << trial;
    } else {
      EXPECT_NEAR(deepest, -depth, kTol) << trial;
    }
    ++checked;
  }
  EXPECT_GT(checked, 2900);
}

// Random shapes and poses about random triangles (slivers, shapes centred on the plane, touching
// exactly): the result is always finite, its normal unit, at most four points, each within the
// speculative distance.
TEST(TriangleContact, FiniteOnRandomAndDegenerateInput) {
  const std::array<Shape, 6> shapes = every_shape();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  int touching = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    MeshTriangle t;
    for (int k = 0; k < 3; ++k) t.v[k] = Vec3{u(rng), Real(0.1) * u(rng), u(rng)};
    if (trial % 5 == 0) t.v[2] = t.v[0] + Real(1e-3) * (t.v[1] - t.v[0]) + Vec3(0, 0, Real(1e-4));
    if (!((t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]).norm() > 0)) continue;
    t.active_edges = uint8_t(trial % 8);
    t.two_sided = trial % 3 != 0;
    const Shape& s = shapes[trial % 6];
    Vec3 p{u(rng), Real(0.5) * u(rng), u(rng)};
    if (trial % 7 == 0) p = (t.v[0] + t.v[1] + t.v[2]) / 3;  // centred on the plane
    const Quat q = test::random_turn(rng, u);
    TriangleContact c;
    if (!collide_triangle(s, at(p.x(), p.y(), p.z(), q), t, kSpec, c)) continue;
    ++touching;
    ASSERT_TRUE(c.normal.allFinite());
    ASSERT_NEAR(c.normal.norm(), 1, 1e-3);
    ASSERT_GE(c.count, 1);
    ASSERT_LE(c.count, kMaxManifoldPoints);
    for (int k = 0; k < c.count; ++k) {
      ASSERT_TRUE(c.points[k].allFinite());
      ASSERT_TRUE(std::isfinite(c.separation[k]));
      ASSERT_LE(c.separation[k], kSpec);
    }
  }
  EXPECT_GT(touching, 500);
}

// GJK against a triangle told to stop past a distance: when it stops early, the search run to the
// end finds the shapes at least that far apart; when it does not, it is the search run to the end,
// bit for bit. 1e-5 relative: GJK's own tolerance on the distance it converges to.
TEST(TriangleContact, GjkStopsEarlyOnlyPastTheRejectDistance) {
  const Shape shapes[] = {capsule(Real(0.2), Real(0.4)), box(Real(0.3), Real(0.2), Real(0.5)),
                          cylinder(Real(0.3), Real(0.2)), test::round_hull(20, Real(0.4))};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1, 1);
  int stopped = 0, ran = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    Vec3 v[3];
    for (int k = 0; k < 3; ++k) v[k] = Vec3{u(rng), Real(0.2) * u(rng), u(rng)};
    const Shape& s = shapes[trial % 4];
    const Quat q = test::random_turn(rng, u);
    const PlacedShape a = place(s, test::pose(Vec3{u(rng), Real(0.6) * u(rng), u(rng)}, q), false);
    const Real reject = Real(0.05) + Real(0.1) * (u(rng) + 1);
    Simplex s0, s1;
    const GjkResult full = gjk_triangle(a, v, Vec3::UnitY(), s0);
    const GjkResult cut = gjk_triangle(a, v, Vec3::UnitY(), s1, reject);
    ASSERT_FALSE(full.beyond);
    if (cut.beyond) {
      ++stopped;
      ASSERT_FALSE(full.overlap);
      ASSERT_GT(full.distance, reject * (1 - Real(1e-5))) << trial;
      continue;
    }
    ++ran;
    ASSERT_EQ(cut.overlap, full.overlap);
    ASSERT_EQ(cut.distance, full.distance);
    ASSERT_EQ(cut.point_a, full.point_a);
    ASSERT_EQ(cut.point_b, full.point_b);
  }
  EXPECT_GT(stopped, 500);
  EXPECT_GT(ran, 500);
}

// GJK against a triangle started toward the triangle's closest point to A's centre (what
// reach_triangle leaves for the contact routine) rather than along the face's normal: the same
// distance and direction to GJK's tolerance, in fewer iterations over shapes beside and over
// random triangles.
TEST(TriangleContact, GjkFromTheClosestPointAgreesInFewerIterations) {
  const Shape shapes[] = {capsule(Real(0.2), Real(0.4)), box(Real(0.3), Real(0.2), Real(0.5)),
                          cylinder(Real(0.3), Real(0.2)), test::round_hull(20, Real(0.4))};
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> u(-1, 1);
  int compared = 0, from_face = 0, from_closest = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    MeshTriangle t;
    for (int k = 0; k < 3; ++k) t.v[k] = Vec3{u(rng), Real(0.2) * u(rng), u(rng)};
    const Shape& s = shapes[trial % 4];
    const Quat q = test::random_turn(rng, u);
    const TriangleQuery query = make_triangle_query(
        s,
        test::pose(Vec3{Real(1.5) * u(rng), Real(0.2) + Real(0.4) * u(rng), Real(1.5) * u(rng)}, q),
        Real(0.5));
    TriangleReach r;
    if (!reach_triangle(query, t, r)) continue;
    Simplex s0, s1;
    const GjkResult a = gjk_triangle(query.core, r.v, Vec3(-r.face), s0);
    const GjkResult b = gjk_triangle(query.core, r.v, r.closest, s1);
    ASSERT_EQ(a.overlap, b.overlap) << trial;
    if (a.overlap) continue;
    ++compared;
    from_face += a.iterations;
    from_closest += b.iterations;
    ASSERT_NEAR(a.distance, b.distance, kTol * (1 + a.distance)) << trial;
    if (a.distance > Real(0.01)) {
      const Vec3 na = (a.point_b - a.point_a) / a.distance;
      const Vec3 nb = (b.point_b - b.point_a) / b.distance;
      EXPECT_GT(na.dot(nb), 1 - Real(1e-3)) << trial;
    }
  }
  EXPECT_GT(compared, 1000);
  EXPECT_LT(from_closest, from_face);
}

// A heightfield's triangles walked as the composite pairs walk them (corners first, the query's
// reach, active edges derived only where a contact reads them) give what the whole triangle
// gives, bit for bit, for every shape over a bumpy field.
TEST(TriangleContact, HeightfieldQueryMatchesWholeTriangles) {
  constexpr uint32_t kColumns = 9;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1, 1);
  const HeightField field = bumpy_field(kColumns, rng);
  const std::array<Shape, 6> shapes = every_shape();
  int contacts = 0, rejected = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const Shape& s = shapes[trial % 6];
    const Quat q = test::random_turn(rng, u);
    // Over the field's middle, from well clear of it to half sunk.
    const Transform xa = test::pose(
        Vec3{2 + Real(1.2) * u(rng), Real(0.35) + Real(0.3) * u(rng), 2 + Real(1.2) * u(rng)}, q);
    TriangleQuery query = make_triangle_query(s, xa, kSpec);
    query.field = &field;
    for (uint32_t t = 0; t < 2 * (kColumns - 1) * (kColumns - 1); ++t) {
      TriangleContact whole, walked;
      const bool want = collide_triangle(s, xa, field.triangle(t), kSpec, whole);
      TriangleReach reach;
      const MeshTriangle corners = field.corners(t);
      const bool got = reach_triangle(query, corners, reach) &&
                       collide_reached_triangle(query, corners, reach, walked);
      ASSERT_EQ(got, want) << "trial " << trial << " triangle " << t;
      if (!want) {
        ++rejected;
        continue;
      }
      ++contacts;
      ASSERT_EQ(walked.count, whole.count);
      ASSERT_EQ(walked.normal, whole.normal);
      for (int k = 0; k < whole.count; ++k) {
        ASSERT_EQ(walked.points[k], whole.points[k]);
        ASSERT_EQ(walked.separation[k], whole.separation[k]);
        ASSERT_EQ(walked.feature[k], whole.feature[k]);
      }
    }
  }
  EXPECT_GT(contacts, 1000);
  EXPECT_GT(rejected, 1000);
}

// reach_triangle before its distance test: the corners, the plane, the lateral and the lowest
// point's tests alone (what collide_reached_triangle was given before the test was added).
bool reach_without_distance(const TriangleQuery& q, const MeshTriangle& t, TriangleReach& r) {
  for (int k = 0; k < 3; ++k) r.v[k] = t.v[k] - q.position;
  Vec3 g = (r.v[1] - r.v[0]).cross(r.v[2] - r.v[0]);
  if (!(g.norm() > 0)) return false;
  g.normalize();
  const Real centre_height = -g.dot(r.v[0]);
  if (!t.two_sided && centre_height < 0) return false;
  r.geometric = g;
  r.face = centre_height >= 0 ? g : Vec3(-g);
  r.speculative = q.speculative + std::max(Real(0), -r.face.dot(q.motion));
  if (q.shape->type == ShapeType::Sphere) return true;
  const Real lateral = q.shape->bounding_radius + r.speculative;
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = r.v[(k + 1) % 3] - r.v[k];
    const Real beyond = -e.cross(g).dot(r.v[k]);
    if (beyond > 0 && beyond * beyond > lateral * lateral * e.squaredNorm()) return false;
  }
  r.lowest = support_world(q.full, -r.face);
  r.plane_gap = r.face.dot(r.lowest - r.v[0]);
  return !(r.plane_gap > r.speculative);
}

// Oracle: the contact routine itself. Every triangle reach_triangle's distance test rejects,
// given to collide_reached_triangle as it was before that test, gives no contact: the test drops
// nothing but triangles with nothing to give. Bodies of every shape, tilted, resting on and
// hovering over a bumpy field and some moving towards it, so that both of the routine's paths
// (the face's, the closest features') are reached.
TEST(TriangleContact, ReachRejectsOnlyTrianglesWithoutAContact) {
  constexpr uint32_t kColumns = 9;
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1, 1);
  const HeightField field = bumpy_field(kColumns, rng);
  const std::array<Shape, 6> shapes = every_shape();  // the sphere (0) left out below
  int dropped = 0, kept = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    const Shape& s = shapes[1 + trial % 5];
    const Quat q = test::random_turn(rng, u);
    const Transform xa = test::pose(
        Vec3{2 + Real(1.2) * u(rng), Real(0.3) + Real(0.25) * u(rng), 2 + Real(1.2) * u(rng)}, q);
    TriangleQuery query = make_triangle_query(s, xa, kSpec);
    if (trial % 3 == 0) query.motion = Vec3{Real(0.05) * u(rng), Real(-0.1), Real(0.05) * u(rng)};
    for (uint32_t t = 0; t < 2 * (kColumns - 1) * (kColumns - 1); ++t) {
      const MeshTriangle tri = field.triangle(t);
      TriangleReach before, now;
      if (!reach_without_distance(query, tri, before)) {
        ASSERT_FALSE(reach_triangle(query, tri, now)) << "trial " << trial << " triangle " << t;
        continue;
      }
      if (reach_triangle(query, tri, now)) {
        ++kept;
        continue;
      }
      ++dropped;
      TriangleContact c;
      ASSERT_FALSE(collide_reached_triangle(query, tri, before, c))
          << "trial " << trial << " triangle " << t << " separation " << c.separation[0];
    }
  }
  EXPECT_GT(dropped, 2000);
  EXPECT_GT(kept, 2000);
}

// Oracle: the contact routine, given the triangle past reach_triangle's tests but its distance
// test (which the cell's test would otherwise hide). Every triangle of a heightfield cell the body
// is clear of (with the cell's speculative distance: the base plus the whole motion, as the
// composite walk gives it) gives no contact at its own speculative distance; and when the body is
// over the cell's box (its centre inside it), the box is never clear.
TEST(TriangleContact, ClearOfBoxOnlyWhenItsTrianglesGiveNothing) {
  constexpr uint32_t kColumns = 9;
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> u(-1, 1);
  const HeightField field = bumpy_field(kColumns, rng);
  const std::array<Shape, 6> shapes = every_shape();
  int clear = 0, not_clear = 0;
  for (int trial = 0; trial < 1200; ++trial) {
    const Shape& s = shapes[trial % 6];
    const Quat q = test::random_turn(rng, u);
    const Transform xa = test::pose(
        Vec3{2 + Real(1.2) * u(rng), Real(0.3) + Real(0.25) * u(rng), 2 + Real(1.2) * u(rng)}, q);
    TriangleQuery query = make_triangle_query(s, xa, kSpec);
    if (trial % 3 == 0) query.motion = Vec3{Real(0.05) * u(rng), Real(-0.1), Real(0.05) * u(rng)};
    query.field = &field;
    const Real cell_speculative = kSpec + query.motion.norm();
    for (uint32_t j = 0; j + 1 < kColumns; ++j) {
      for (uint32_t i = 0; i + 1 < kColumns; ++i) {
        Vec3 lo, hi;
        cell_box(field, i, j, lo, hi);
        const bool inside =
            (xa.position.array() >= lo.array()).all() && (xa.position.array() <= hi.array()).all();
        const uint32_t cell = j * (kColumns - 1) + i;
        const MeshTriangle pair[2] = {field.corners(2 * cell), field.corners(2 * cell + 1)};
        if (!clear_of_box(query, lo, hi, cell_speculative, pair)) {
          ++not_clear;
          continue;
        }
        ASSERT_FALSE(inside) << "trial " << trial;
        ++clear;
        for (int k = 0; k < 2; ++k) {
          const MeshTriangle& tri = pair[k];
          const uint32_t t = 2 * cell + uint32_t(k);
          TriangleReach reach;
          TriangleContact c;
          ASSERT_FALSE(reach_without_distance(query, tri, reach) &&
                       collide_reached_triangle(query, tri, reach, c))
              << "trial " << trial << " triangle " << t;
        }
      }
    }
  }
  EXPECT_GT(clear, 5000);
  EXPECT_GT(not_clear, 5000);
}

// The contact routine's face path reports a piece's points under a smooth triangle at any depth.
// A thin piece whose centre is just over a steep plane (y = x + z, every edge inactive) and which
// reaches under it from the upper side has its box bound's direction pointing up the slope, along
// which the cells below it look clear though the piece's far end is under their triangles: such
// a cell must be kept (the oracle as above; with the faces' check left out, 500 trials find it).
TEST(TriangleContact, ClearOfBoxKeepsACellAThinPieceReachesUnder) {
  constexpr uint32_t kColumns = 6;
  std::vector<Real> heights(kColumns * kColumns);
  for (uint32_t j = 0; j < kColumns; ++j) {
    for (uint32_t i = 0; i < kColumns; ++i) heights[j * kColumns + i] = Real(i + j);
  }
  const HeightField field = build_heightfield(heights, kColumns, Real(1), Real(1));
  const Vec3 up = Vec3(-1, 1, -1).normalized();
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> u(-1, 1);
  const Shape shapes[] = {box(Real(1.2), Real(0.03), Real(0.03)),
                          box_hull(Real(0.03), Real(1.0), Real(0.05)),
                          capsule(Real(0.02), Real(1.1))};
  int clear = 0, not_clear = 0, under = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Shape& s = shapes[trial % 3];
    const Quat q = Quat{u(rng), u(rng), u(rng), u(rng)}.normalized();
    const Real x = Real(2.5) + Real(0.8) * u(rng), z = Real(2.5) + Real(0.8) * u(rng);
    const Vec3 centre = Vec3(x, x + z, z) + (Real(0.1) + Real(0.1) * u(rng)) * up;
    TriangleQuery query = make_triangle_query(s, at(centre.x(), centre.y(), centre.z(), q), kSpec);
    query.field = &field;
    if (up.dot(support_world(query.full, -up)) < Real(-0.2)) ++under;
    for (uint32_t j = 0; j + 1 < kColumns; ++j) {
      for (uint32_t i = 0; i + 1 < kColumns; ++i) {
        const Vec3 lo(Real(i), Real(i + j), Real(j)), hi(Real(i + 1), Real(i + j + 2), Real(j + 1));
        const uint32_t cell = j * (kColumns - 1) + i;
        const MeshTriangle pair[2] = {field.corners(2 * cell), field.corners(2 * cell + 1)};
        if (!clear_of_box(query, lo, hi, kSpec, pair)) {
          ++not_clear;
          continue;
        }
        ++clear;
        for (int k = 0; k < 2; ++k) {
          TriangleReach reach;
          TriangleContact c;
          ASSERT_FALSE(reach_without_distance(query, pair[k], reach) &&
                       collide_reached_triangle(query, pair[k], reach, c))
              << "trial " << trial << " cell " << i << ", " << j << " triangle " << k;
        }
      }
    }
  }
  EXPECT_GT(under, 100);  // pieces do reach 20 cm under the plane
  EXPECT_GT(clear, 1000);
  EXPECT_GT(not_clear, 1000);
}

// reach_triangle as it was before its shortcuts, every test made with A's own support: the
// oracle the shortcuts must agree with, bit for bit.
bool reach_with_supports(const TriangleQuery& q, const MeshTriangle& t, TriangleReach& r) {
  Vec3(&v)[3] = r.v;
  for (int k = 0; k < 3; ++k) v[k] = t.v[k] - q.position;
  Vec3 geometric = (v[1] - v[0]).cross(v[2] - v[0]);
  const Real area2 = geometric.norm();
  if (!(area2 > 0)) return false;
  geometric /= area2;
  const Real centre_height = -geometric.dot(v[0]);
  if (!t.two_sided && centre_height < 0) return false;
  r.geometric = geometric;
  r.face = centre_height >= 0 ? geometric : Vec3(-geometric);
  r.speculative = q.speculative + std::max(Real(0), -r.face.dot(q.motion));
  if (q.shape->type == ShapeType::Sphere) {
    const Real margin = Real(1e-4) * (q.shape->radius + r.speculative + v[0].cwiseAbs().sum());
    return !(std::abs(centre_height) - q.shape->radius > r.speculative + margin);
  }
  const Real lateral =
      q.shape->bounding_radius + r.speculative +
      Real(1e-4) * (q.shape->bounding_radius + r.speculative + v[0].cwiseAbs().sum());
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = v[(k + 1) % 3] - v[k];
    const Real beyond = -e.cross(geometric).dot(v[k]);
    if (beyond > 0 && beyond * beyond > lateral * lateral * e.squaredNorm()) return false;
  }
  r.lowest = support_world(q.full, -r.face);
  r.plane_gap = r.face.dot(r.lowest - v[0]);
  if (r.plane_gap > r.speculative) return false;
  // The same operations as triangle_contact.cpp's closest point (Ericson 5.1.5), with the query
  // point at the origin: the same bits, but for the sign of a zero.
  r.closest = closest_on_triangle(Vec3::Zero(), v[0], v[1], v[2]);
  const Real dist2 = r.closest.squaredNorm();
  if (dist2 > 0) {
    const Real dist = std::sqrt(dist2);
    const Vec3 u = r.closest / dist;
    const Real gap = dist - u.dot(support_world(q.full, u));
    const Real margin =
        Real(1e-4) * (q.shape->bounding_radius + r.speculative + v[0].cwiseAbs().sum() +
                      (v[1] - v[0]).cwiseAbs().sum() + (v[2] - v[0]).cwiseAbs().sum());
    if (gap > r.speculative + margin) return false;
  }
  return true;
}

// clear_of_box as it was before its shortcut: the oracle, with A's own support.
bool clear_with_support(const TriangleQuery& q, const Vec3& lo, const Vec3& hi, Real speculative,
                        std::span<const MeshTriangle> in_box) {
  const Vec3 c = q.position.cwiseMax(lo).cwiseMin(hi) - q.position;
  const Real dist2 = c.squaredNorm();
  if (!(dist2 > 0)) return false;
  const Real dist = std::sqrt(dist2);
  const Vec3 u = c / dist;
  for (const MeshTriangle& t : in_box) {
    const Vec3 geometric = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
    const Vec3 face = geometric.dot(q.position - t.v[0]) >= 0 ? geometric : Vec3(-geometric);
    if (!(u.dot(face) <= 0)) return false;
  }
  const Real margin = Real(1e-4) * (q.shape->bounding_radius + speculative +
                                    q.position.cwiseAbs().sum() + 2 * (hi - lo).cwiseAbs().sum());
  return dist - u.dot(support_world(q.full, u)) > speculative + margin;
}

void expect_same_reach(const TriangleReach& a, const TriangleReach& b, bool sphere) {
  for (int k = 0; k < 3; ++k) ASSERT_EQ(a.v[k], b.v[k]);
  ASSERT_EQ(a.geometric, b.geometric);
  ASSERT_EQ(a.face, b.face);
  ASSERT_EQ(a.speculative, b.speculative);
  if (sphere) return;
  ASSERT_EQ(a.lowest, b.lowest);
  ASSERT_EQ(a.plane_gap, b.plane_gap);
  ASSERT_EQ(a.closest, b.closest);
}

// perf shortcuts against their oracles: reach_triangle keeps a triangle on the gap to A's lowest
// point, and clear_of_box keeps a cell on the gap to A's point q.down, before (or instead of) the
// support along the gap's direction. Both must decide as the support alone does, and a kept
// triangle's reach must be the same bits. Every shape, resting on, sunk into, hovering over and
// falling onto a bumpy field (one-sided triangles) and random two-sided triangles.
TEST(TriangleContact, ShortcutsDecideAsTheSupportDoes) {
  constexpr uint32_t kColumns = 9;
  std::mt19937 rng(43);
  std::uniform_real_distribution<float> u(-1, 1);
  const HeightField field = bumpy_field(kColumns, rng);
  const std::array<Shape, 6> shapes = every_shape();
  int kept = 0, rejected = 0, clear = 0, not_clear = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    const Shape& s = shapes[trial % 6];
    const Quat q = test::random_turn(rng, u);
    const Transform xa = test::pose(
        Vec3{2 + Real(1.2) * u(rng), Real(0.3) + Real(0.3) * u(rng), 2 + Real(1.2) * u(rng)}, q);
    TriangleQuery query = make_triangle_query(s, xa, kSpec);
    if (trial % 3 == 0) query.motion = Vec3{Real(0.05) * u(rng), Real(-0.2), Real(0.05) * u(rng)};
    query.field = &field;
    query.down = support_world(query.full, Vec3(0, -1, 0));
    const Real cell_speculative = kSpec + query.motion.norm();
    for (uint32_t cell = 0; cell < (kColumns - 1) * (kColumns - 1); ++cell) {
      const uint32_t i = cell % (kColumns - 1), j = cell / (kColumns - 1);
      Vec3 lo, hi;
      cell_box(field, i, j, lo, hi);
      const MeshTriangle pair[2] = {field.corners(2 * cell), field.corners(2 * cell + 1)};
      const bool want_clear = clear_with_support(query, lo, hi, cell_speculative, pair);
      ASSERT_EQ(clear_of_box(query, lo, hi, cell_speculative, pair), want_clear)
          << "trial " << trial << " cell " << cell;
      ++(want_clear ? clear : not_clear);
      for (const MeshTriangle& t : pair) {
        TriangleReach want, got;
        const bool keep = reach_with_supports(query, t, want);
        ASSERT_EQ(reach_triangle(query, t, got), keep) << "trial " << trial << " cell " << cell;
        ++(keep ? kept : rejected);
        if (keep) expect_same_reach(got, want, s.type == ShapeType::Sphere);
      }
    }
    // Random two-sided triangles around A, as a mesh gives them.
    for (int k = 0; k < 20; ++k) {
      MeshTriangle t;
      for (Vec3& p : t.v) p = xa.position + Vec3{u(rng), Real(0.6) * u(rng), u(rng)};
      TriangleReach want, got;
      const bool keep = reach_with_supports(query, t, want);
      ASSERT_EQ(reach_triangle(query, t, got), keep) << "trial " << trial << " triangle " << k;
      ++(keep ? kept : rejected);
      if (keep) expect_same_reach(got, want, s.type == ShapeType::Sphere);
    }
  }
  EXPECT_GT(kept, 5000);
  EXPECT_GT(rejected, 5000);
  EXPECT_GT(clear, 5000);
  EXPECT_GT(not_clear, 5000);
}

}  // namespace narrowphase_triangle_contact_test
}  // namespace elan::detail
