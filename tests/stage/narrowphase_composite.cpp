// SPDX-License-Identifier: MIT
// Composite pairs (meshes, heightfields, compounds) through collide() and time_of_impact(): one
// merged manifold, no ghost normal across an internal edge, the same manifold as a lone part,
// stable feature ids, and impacts against a wall one triangle thick.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "core/base/body_store.hpp"
#include "core/base/compound.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/triangle_mesh.hpp"
#include "narrowphase/collide.hpp"
#include "narrowphase/composite.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_composite_test {

using test::at;
using test::axis_angle;
using test::box;
using test::sphere;

// GJK's and EPA's tolerances (about 1e-5 relative in float) on sizes of about 1 m.
constexpr Real kTol = sizeof(Real) == 4 ? Real(1e-4) : Real(1e-8);
constexpr Real kSpec = Real(0.02);

Shape mesh_shape(const std::vector<Vec3>& v, const std::vector<std::array<uint32_t, 3>>& t) {
  Shape s;
  s.type = ShapeType::Mesh;
  auto m = std::make_shared<TriangleMesh>(build_triangle_mesh(v, t));
  s.local_min = m->min;
  s.local_max = m->max;
  for (const Vec3& p : v) s.bounding_radius = std::max(s.bounding_radius, p.norm());
  s.mesh = std::move(m);
  return s;
}

// A flat square [-n, n]^2 at y = 0 of 2 n x 2 n cells, each cut into two triangles.
Shape floor_mesh(int n) {
  std::vector<Vec3> v;
  std::vector<std::array<uint32_t, 3>> t;
  const int side = 2 * n + 1;
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) v.emplace_back(Real(i - n), 0, Real(j - n));
  }
  for (int j = 0; j + 1 < side; ++j) {
    for (int i = 0; i + 1 < side; ++i) {
      const uint32_t a = uint32_t(j * side + i), b = a + 1, c = a + uint32_t(side), d = c + 1;
      t.push_back({a, c, d});  // counter-clockwise seen from +y
      t.push_back({a, d, b});
    }
  }
  return mesh_shape(v, t);
}

// One part per (shape, pose); poses in the compound's principal frame.
Shape compound_of(const std::vector<std::pair<Shape, Transform>>& parts) {
  auto c = std::make_shared<Compound>();
  Shape s;
  s.type = ShapeType::Compound;
  s.local_min = Vec3::Constant(1e30f);
  s.local_max = -s.local_min;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    CompoundPart p;
    p.shape = parts[k].first;
    p.pose = parts[k].second;
    const Mat3 r = p.pose.rotation.toRotationMatrix();
    const Vec3 centre = r * (Real(0.5) * (p.shape.local_min + p.shape.local_max)) + p.pose.position;
    const Vec3 half = r.cwiseAbs() * (Real(0.5) * (p.shape.local_max - p.shape.local_min));
    p.box.min = centre - half;
    p.box.max = centre + half;
    s.local_min = s.local_min.cwiseMin(p.box.min);
    s.local_max = s.local_max.cwiseMax(p.box.max);
    s.bounding_radius =
        std::max(s.bounding_radius, p.pose.position.norm() + p.shape.bounding_radius);
    c->parts.push_back(p);
    c->child_of.push_back(uint32_t(k));
  }
  describe_parts(*c);
  s.compound = std::move(c);
  return s;
}

Shape ground_plane() {
  ShapeDef d;
  d.type = ShapeType::Plane;
  return make_shape(d);
}

TEST(Composite, BoxAcrossInternalEdgesGetsTheFaceNormalAndHeight) {
  const Shape floor = floor_mesh(3);
  const Shape b = box(Real(0.7), Real(0.3), Real(0.45));
  // Over many shared edges, turned and shifted: one manifold, the face normal, every point 1 cm
  // deep at the face's height (y = 0 midway: -0.005).
  for (const Real turn : {Real(0), Real(0.3), Real(0.785398), Real(1.2)}) {
    for (const Real shift : {Real(0), Real(0.02), Real(0.5), Real(0.77)}) {
      const Transform xa = at(shift, Real(0.29), -shift, axis_angle(turn, Vec3::UnitY()));
      Manifold m;
      ASSERT_TRUE(collide(b, xa, floor, at(0, 0, 0), kSpec, m));
      EXPECT_EQ(m.point_count, 4u);
      EXPECT_NEAR(m.normal.x(), 0, kTol);
      EXPECT_NEAR(m.normal.y(), -1, kTol);
      EXPECT_NEAR(m.normal.z(), 0, kTol);
      for (int k = 0; k < int(m.point_count); ++k) {
        EXPECT_NEAR(m.points[k].separation, Real(-0.01), kTol);
        EXPECT_NEAR(xa.position.y() + m.points[k].anchor_a.y(), Real(-0.005), kTol);
      }
    }
  }
}

TEST(Composite, SurfaceMotionKeepsTheAllowanceAlongTheApproachOnly) {
  const Shape floor = floor_mesh(3);
  const Shape b = box(Real(0.35), Real(0.3), Real(0.4));
  // The box's bottom 0.1 m above the floor; the step moves it 0.2 m, the base distance 2 cm.
  const Transform xa = at(Real(0.2), Real(0.4), Real(-0.1));
  const Real step = Real(0.2), speculative = kSpec + step;
  // Falling: every triangle under the box is approached by 0.2 m, so the bottom face's four
  // corners are speculative points 0.1 m apart along the face normal.
  const SurfaceMotion falling{Vec3(0, -step, 0), kSpec};
  Manifold m;
  ASSERT_TRUE(collide_composite(b, xa, floor, at(0, 0, 0), speculative, m, &falling));
  EXPECT_EQ(m.point_count, 4u);
  EXPECT_NEAR(m.normal.y(), -1, kTol);
  for (int k = 0; k < int(m.point_count); ++k) {
    EXPECT_NEAR(m.points[k].separation, Real(0.1), kTol);
  }
  // Sliding or rising as fast: nothing closes the 0.1 m gap, which is past the base distance;
  // the same distance given without the motion keeps the points.
  for (const Vec3& d : {Vec3(step, 0, 0), Vec3(0, 0, -step), Vec3(0, step, 0)}) {
    const SurfaceMotion moving{d, kSpec};
    EXPECT_FALSE(collide_composite(b, xa, floor, at(0, 0, 0), speculative, m, &moving));
  }
  EXPECT_TRUE(collide_composite(b, xa, floor, at(0, 0, 0), speculative, m));
  // The surface as A: its motion relative to the box is the box's, reversed.
  const SurfaceMotion rising{Vec3(0, step, 0), kSpec};
  ASSERT_TRUE(collide_composite(floor, at(0, 0, 0), b, xa, speculative, m, &rising));
  EXPECT_EQ(m.point_count, 4u);
  EXPECT_NEAR(m.normal.y(), 1, kTol);
  const SurfaceMotion sinking{Vec3(0, -step, 0), kSpec};
  EXPECT_FALSE(collide_composite(floor, at(0, 0, 0), b, xa, speculative, m, &sinking));
}

TEST(Composite, FourPointsAreTheSupportNotTheWidestHovering) {
  // A plateau 0.4 m square at y = 0 in a ring sloping down 5 cm a metre (2.9 degrees, one
  // manifold) to a 2 m square. A 1 m box 0.5 mm into the plateau touches it at the plateau's
  // edge; its corners over the ring hover 1.5 cm up, within the speculative distance. The four
  // points must be the touching ones, the plateau's corners: a manifold of the widest points
  // would hold the box on one touching point and three hovering ones, and it would rock.
  std::vector<Vec3> v;
  for (const Real h : {Real(0.2), Real(1)}) {
    const Real y = h == Real(1) ? Real(-0.04) : Real(0);
    v.emplace_back(-h, y, -h), v.emplace_back(h, y, -h), v.emplace_back(h, y, h),
        v.emplace_back(-h, y, h);
  }
  std::vector<std::array<uint32_t, 3>> t;
  const auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    if ((v[b] - v[a]).cross(v[c] - v[a]).y() < 0) std::swap(b, c);  // front up
    t.push_back({a, b, c});
  };
  add(0, 1, 2), add(0, 2, 3);
  for (uint32_t k = 0; k < 4; ++k) {
    const uint32_t n = (k + 1) % 4;
    add(k, n, n + 4), add(k, n + 4, k + 4);
  }
  const Shape ground = mesh_shape(v, t);
  const Shape b = box(Real(0.5), Real(0.3), Real(0.5));
  for (const Real turn : {Real(0), Real(0.3)}) {
    const Transform xa = at(0, Real(0.2995), 0, axis_angle(turn, Vec3::UnitY()));
    Manifold m;
    ASSERT_TRUE(collide(b, xa, ground, at(0, 0, 0), kSpec, m));
    ASSERT_EQ(m.point_count, 4u);
    EXPECT_LT(m.normal.y(), -std::cos(Real(0.051)));  // the plateau's or a ring triangle's
    for (int k = 0; k < 4; ++k) {
      const ContactPoint& p = m.points[k];
      EXPECT_NEAR(p.separation, Real(-0.0005), Real(1e-4));
      EXPECT_NEAR(std::abs(p.anchor_a.x()), Real(0.2), Real(1e-3));
      EXPECT_NEAR(std::abs(p.anchor_a.z()), Real(0.2), Real(1e-3));
    }
  }
}

TEST(Composite, SurfaceAsAFlipsTheNormal) {
  const Shape floor = floor_mesh(1);
  const Transform xs = at(Real(0.2), Real(0.49), Real(0.1));
  Manifold m;
  ASSERT_TRUE(collide(floor, at(0, 0, 0), sphere(Real(0.5)), xs, kSpec, m));
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.normal.y(), 1, kTol);
  EXPECT_NEAR(m.points[0].separation, Real(-0.01), kTol);
  // Measured from A (the mesh's origin): the midpoint between the surfaces.
  EXPECT_NEAR(m.points[0].anchor_a.y(), Real(-0.005), kTol);
  EXPECT_NEAR(m.points[0].anchor_a.x(), Real(0.2), kTol);
}

TEST(Composite, StaticPairsGiveNothing) {
  const Shape floor = floor_mesh(1);
  Manifold m;
  EXPECT_FALSE(collide(floor, at(0, 0, 0), floor, at(0, Real(0.001), 0), kSpec, m));
  EXPECT_FALSE(collide(ground_plane(), at(0, 0, 0), floor, at(0, 0, 0), kSpec, m));
  EXPECT_FALSE(collide(floor, at(0, 0, 0), ground_plane(), at(0, 0, 0), kSpec, m));
  EXPECT_FALSE(exact_test_is_closed_form(sphere(1), floor));
}

TEST(Composite, CompoundOfOneBoxMatchesTheBoxAlone) {
  const Shape b = box(Real(0.5), Real(0.3), Real(0.4));
  const Shape c = compound_of({{b, Transform{}}});
  const Transform xa = at(Real(1.5), Real(0.28), Real(-2), axis_angle(Real(0.2), Vec3(1, 2, 3)));
  const Transform xg = at(0, 0, 0);
  Manifold alone, part;
  ASSERT_TRUE(collide(b, xa, ground_plane(), xg, kSpec, alone));
  ASSERT_TRUE(collide(c, xa, ground_plane(), xg, kSpec, part));
  ASSERT_EQ(alone.point_count, part.point_count);
  EXPECT_EQ(std::memcmp(alone.normal.data(), part.normal.data(), sizeof(Vec3)), 0);
  for (int k = 0; k < int(alone.point_count); ++k) {
    EXPECT_EQ(
        std::memcmp(alone.points[k].anchor_a.data(), part.points[k].anchor_a.data(), sizeof(Vec3)),
        0);
    EXPECT_EQ(alone.points[k].separation, part.points[k].separation);
  }
  EXPECT_FALSE(exact_test_is_closed_form(c, ground_plane()));
  // Two compounds of one box each, one on the other: the box pair's manifold.
  const Transform top = at(Real(0.1), Real(0.58), Real(0.05), axis_angle(Real(0.3), Vec3::UnitY()));
  const Transform bottom = at(0, 0, 0);
  ASSERT_TRUE(collide(b, top, b, bottom, kSpec, alone));
  ASSERT_TRUE(collide(c, top, c, bottom, kSpec, part));
  ASSERT_EQ(alone.point_count, part.point_count);
  EXPECT_EQ(std::memcmp(alone.normal.data(), part.normal.data(), sizeof(Vec3)), 0);
  for (int k = 0; k < int(alone.point_count); ++k) {
    EXPECT_EQ(
        std::memcmp(alone.points[k].anchor_a.data(), part.points[k].anchor_a.data(), sizeof(Vec3)),
        0);
    EXPECT_EQ(alone.points[k].separation, part.points[k].separation);
  }
}

TEST(Composite, CompoundPartsMergeIntoOneManifold) {
  // A dumbbell: two boxes 2 m apart on a bar; resting level, its manifold spans both ends.
  const Shape end = box(Real(0.2), Real(0.2), Real(0.2));
  const Shape c = compound_of({{end, at(-1, 0, 0)}, {end, at(1, 0, 0)}});
  Manifold m;
  ASSERT_TRUE(collide(c, at(0, Real(0.19), 0), ground_plane(), at(0, 0, 0), kSpec, m));
  ASSERT_EQ(m.point_count, 4u);
  Real lo = 1e9f, hi = -1e9f;
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(m.points[k].separation, Real(-0.01), kTol);
    lo = std::min(lo, m.points[k].anchor_a.x());
    hi = std::max(hi, m.points[k].anchor_a.x());
  }
  EXPECT_NEAR(lo, Real(-1.2), kTol);
  EXPECT_NEAR(hi, Real(1.2), kTol);
  // The same against a mesh floor.
  ASSERT_TRUE(collide(c, at(0, Real(0.19), 0), floor_mesh(2), at(0, 0, 0), kSpec, m));
  EXPECT_EQ(m.point_count, 4u);
  EXPECT_NEAR(m.normal.y(), -1, kTol);
}

TEST(Composite, FeatureIdsStayWhileSlidingOnOneTriangle) {
  const Shape floor = floor_mesh(3);
  const Shape b = box(Real(0.1), Real(0.1), Real(0.1));
  // Inside the triangle (a, d, b) of the cell [0, 1]^2: x > z.
  Manifold m0, m1;
  ASSERT_TRUE(collide(b, at(Real(0.6), Real(0.095), Real(0.3)), floor, at(0, 0, 0), kSpec, m0));
  ASSERT_TRUE(collide(b, at(Real(0.601), Real(0.095), Real(0.3)), floor, at(0, 0, 0), kSpec, m1));
  ASSERT_EQ(m0.point_count, m1.point_count);
  std::vector<uint32_t> a, c;
  for (int k = 0; k < int(m0.point_count); ++k) a.push_back(m0.points[k].feature_id);
  for (int k = 0; k < int(m1.point_count); ++k) c.push_back(m1.points[k].feature_id);
  std::sort(a.begin(), a.end());
  std::sort(c.begin(), c.end());
  EXPECT_EQ(a, c);
  EXPECT_EQ(std::adjacent_find(a.begin(), a.end()), a.end());
}

TEST(Composite, HeightfieldFromAboveOnly) {
  auto field = std::make_shared<HeightField>();
  const std::vector<Real> heights(16, Real(0));
  *field = build_heightfield(heights, 4, 1, 1);
  Shape s;
  s.type = ShapeType::Heightfield;
  s.local_min = Vec3(0, 0, 0);
  s.local_max = Vec3(3, 0, 3);
  s.bounding_radius = Real(5);
  s.heightfield = field;
  Manifold m;
  ASSERT_TRUE(
      collide(sphere(Real(0.5)), at(Real(1.3), Real(0.49), Real(1.6)), s, at(0, 0, 0), kSpec, m));
  EXPECT_NEAR(m.normal.y(), -1, kTol);
  EXPECT_NEAR(m.points[0].separation, Real(-0.01), kTol);
  // From below: the front is up, so nothing.
  EXPECT_FALSE(
      collide(sphere(Real(0.5)), at(Real(1.3), Real(-0.3), Real(1.6)), s, at(0, 0, 0), kSpec, m));
}

// A vertical wall one triangle thick: two triangles making the quad x = 0, y in [0, 2],
// z in [-1, 1].
Shape wall() {
  return mesh_shape({Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(0, 2, 1), Vec3(0, 2, -1)},
                    {{{0, 1, 2}}, {{0, 2, 3}}});
}

TEST(Composite, TimeOfImpactAgainstAWallOneTriangleThick) {
  // A 5 cm sphere at 150 m/s over a 60 Hz step: 2.5 m, from 1.2 m before the wall to 1.3 m past.
  const Shape ball = sphere(Real(0.05));
  const Real target = Real(0.005);
  const Real t = time_of_impact(ball, at(Real(-1.2), 1, Real(0.3)), at(Real(1.3), 1, Real(0.3)),
                                wall(), at(0, 0, 0), at(0, 0, 0), target);
  // Contact (gap 0) at t = (1.2 - 0.05) / 2.5; it stops between target and target plus its
  // tolerance (max(target / 4, 1e-4 r)) before that.
  const Real touch = (Real(1.2) - Real(0.05)) / Real(2.5);
  EXPECT_LE(t, touch - target / Real(2.5) + kTol);
  EXPECT_GE(t, touch - (target + target / 4) / Real(2.5) - kTol);
  // Beside the wall (z = 1.2): no impact.
  EXPECT_EQ(time_of_impact(ball, at(Real(-1.2), 1, Real(1.2)), at(Real(1.3), 1, Real(1.2)), wall(),
                           at(0, 0, 0), at(0, 0, 0), target),
            1);
  // A small box, turning as it goes.
  const Shape small = box(Real(0.05), Real(0.05), Real(0.05));
  const Real tb = time_of_impact(small, at(Real(-1.2), 1, 0),
                                 at(Real(1.3), 1, 0, axis_angle(Real(0.5), Vec3::UnitZ())), wall(),
                                 at(0, 0, 0), at(0, 0, 0), target);
  EXPECT_GT(tb, 0);
  EXPECT_LT(tb, touch);
  // A compound of two small spheres: its first part decides.
  const Shape pair = compound_of({{ball, at(Real(0.2), 0, 0)}, {ball, at(Real(-0.2), 0, 0)}});
  const Real tc = time_of_impact(pair, at(Real(-1.2), 1, 0), at(Real(1.3), 1, 0), wall(),
                                 at(0, 0, 0), at(0, 0, 0), target);
  EXPECT_NEAR(tc, touch - Real(0.2) / Real(2.5), Real(0.01) / Real(2.5));
}

// A part's poses at the ends of the motion, as the time of impact composes them.
Transform part_pose(const Transform& body, const Transform& part) {
  return {body.rotation * part.position + body.position, body.rotation * part.rotation};
}

// Fast bodies of every kind, a compound among them, passing, grazing and hitting a turning
// compound whose parts sit up to 0.9 m from its centre: the time of impact is the least over the
// part pairs, each advanced alone, bit for bit. The time of impact tests a part only when the
// other piece comes near the whole compound's bounding sphere; that may skip only parts whose own
// advancement finds no impact.
TEST(Composite, CompoundTimeOfImpactIsTheLeastOverItsParts) {
  const Shape target_compound = compound_of(
      {{box(Real(0.3), Real(0.1), Real(0.2)), at(Real(0.9), 0, 0, axis_angle(1, Vec3::UnitY()))},
       {sphere(Real(0.15)), at(Real(-0.7), Real(0.2), 0)},
       {test::capsule(Real(0.1), Real(0.3)), at(0, Real(0.6), Real(0.3))},
       {test::cylinder(Real(0.2), Real(0.1)), at(0, Real(-0.5), Real(-0.4))}});
  const Shape movers[] = {sphere(Real(0.1)), box(Real(0.1), Real(0.05), Real(0.2)),
                          test::capsule(Real(0.05), Real(0.2)),
                          test::cylinder(Real(0.1), Real(0.1)),
                          compound_of({{box(Real(0.1), Real(0.1), Real(0.1)), at(Real(0.3), 0, 0)},
                                       {sphere(Real(0.08)), at(Real(-0.3), 0, 0)}})};
  const Real target = Real(0.005);
  std::mt19937 rng(57);
  std::uniform_real_distribution<float> u(-1, 1);
  // Each piece of `s` at its own poses: the compound's parts, or the shape itself.
  const auto pieces = [](const Shape& s, const Transform& x0, const Transform& x1) {
    std::vector<std::pair<const Shape*, std::array<Transform, 2>>> out;
    if (s.type != ShapeType::Compound) {
      out.push_back({&s, {x0, x1}});
      return out;
    }
    for (const CompoundPart& p : s.compound->parts) {
      out.push_back({&p.shape, {part_pose(x0, p.pose), part_pose(x1, p.pose)}});
    }
    return out;
  };
  int hits = 0, misses = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Shape& mover = movers[trial % 5];
    const Vec3 direction = Vec3{u(rng), u(rng), u(rng)}.normalized();
    const Vec3 start = direction * (Real(1.6) + Real(0.4) * u(rng));
    // Across the compound's region, or past it: the path's closest approach to the compound's
    // centre spreads from 0 to about 2 m, so that many paths meet or graze only an outer part.
    const Vec3 end = -start + Real(2.5) * Vec3{u(rng), u(rng), u(rng)};
    const Transform a0 = at(start.x(), start.y(), start.z(), test::random_turn(rng, u));
    const Real angle = Real(0.6) * u(rng);
    const Vec3 axis = Vec3{u(rng), u(rng), u(rng)}.normalized();
    const Transform a1 =
        at(end.x(), end.y(), end.z(), (axis_angle(angle, axis) * a0.rotation).normalized());
    const Quat q0 = test::random_turn(rng, u);
    const Transform b0 = test::pose(Vec3{Real(0.1) * u(rng), Real(0.1) * u(rng), 0}, q0);
    const Vec3 pb1{Real(0.1) * u(rng), 0, Real(0.1) * u(rng)};
    const Transform b1 =
        test::pose(pb1, (axis_angle(Real(0.3) * u(rng), Vec3::UnitZ()) * q0).normalized());
    const Real t = time_of_impact(mover, a0, a1, target_compound, b0, b1, target);
    Real least = 1;
    for (const auto& [pa, xa] : pieces(mover, a0, a1)) {
      for (const auto& [pb, xb] : pieces(target_compound, b0, b1)) {
        least = std::min(least, time_of_impact(*pa, xa[0], xa[1], *pb, xb[0], xb[1], target));
      }
    }
    ASSERT_EQ(t, least) << "trial " << trial;
    (t < 1 ? hits : misses) += 1;
  }
  EXPECT_GT(hits, 300);
  EXPECT_GT(misses, 300);
}

// collide_pairs: a compound of boxes resting on a mesh keeps its pose for the body pair cache;
// one with a sphere part rolls (its point does not travel with its material), so it does not.
TEST(Composite, PairCacheKeepsOnlyCompoundsWithoutRoundParts) {
  const auto child = [](const ShapeDef& shape, Real x) {
    CompoundChild c;
    c.shape = shape;
    c.position = Vec3(x, 0, 0);
    return c;
  };
  ShapeDef cube, ball;
  cube.type = ShapeType::Box;
  cube.half_extents = Vec3::Constant(Real(0.2));
  ball.type = ShapeType::Sphere;
  ball.radius = Real(0.2);
  ShapeDef boxes, mixed;
  boxes.type = mixed.type = ShapeType::Compound;
  boxes.children = {child(cube, Real(-0.5)), child(cube, Real(0.5))};
  mixed.children = {child(cube, Real(-0.5)), child(ball, Real(0.5))};
  const std::vector<Shape> shapes = {floor_mesh(3), make_shape(boxes), make_shape(mixed)};
  BodyStore bodies;
  for (uint32_t k = 0; k < 3; ++k) {
    const std::size_t b = bodies.push_back();
    bodies.shape[b] = k;
    bodies.motion[b] = uint8_t(k == 0 ? MotionType::Static : MotionType::Dynamic);
    bodies.flags[b] = k == 0 ? 0 : kAwake;
    // Both parts of each compound 1 cm into the floor (the parts' centres at the frame's height).
    bodies.set_position(b, k == 0 ? Vec3::Zero() : Vec3(Real(k) - 1, Real(0.19), Real(k) - 1));
  }
  const std::vector<uint64_t> pairs = {make_pair_key(0, 1), make_pair_key(0, 2)};
  const std::vector<uint8_t> idle = {1, 0, 0};
  ContactStore store;
  collide_pairs(pairs, bodies, shapes, CollideSettings{}, idle, store);
  const std::vector<Manifold> manifolds = store.manifolds();
  ASSERT_EQ(manifolds.size(), 2u);
  EXPECT_EQ(manifolds[0].point_count, 4u);
  ASSERT_EQ(store.pair_cache().size(), 1u);
  EXPECT_EQ(store.pair_cache()[0].key, make_pair_key(0, 1));
}

}  // namespace narrowphase_composite_test
}  // namespace elan::detail
