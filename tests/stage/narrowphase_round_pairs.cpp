// SPDX-License-Identifier: MIT
// Closed-form round-shape and plane manifolds: depth, normal, points, feature ids, degeneracies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "narrowphase/manifold_reduce.hpp"
#include "narrowphase/round_pairs.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_round_pairs_test {

using test::at;
using test::axis_angle;
using test::box;
using test::capsule;
using test::cylinder;
using test::sphere;

constexpr double kTol = sizeof(Real) == 4 ? 2e-5 : 1e-10;
constexpr Real kSpec = Real(0.02);

Shape ground() {
  ShapeDef d;
  d.type = ShapeType::Plane;
  d.normal = Vec3::UnitY();
  d.offset = 0;
  return make_shape(d);
}
Shape box_hull(Real h) {
  ShapeDef d;
  d.type = ShapeType::ConvexHull;
  for (int i = 0; i < 8; ++i) d.points.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
  return make_shape(d);
}

void expect_sane(const Manifold& m) {
  EXPECT_NEAR(m.normal.norm(), 1, 1e-5);
  for (int i = 0; i < m.point_count; ++i) {
    EXPECT_TRUE(m.points[i].anchor_a.allFinite());
    EXPECT_TRUE(std::isfinite(m.points[i].separation));
  }
}

// World contact point of point i.
Vec3 point(const Manifold& m, const Transform& xa, int i) {
  return xa.position + m.points[i].anchor_a;
}

TEST(RoundPairs, SphereSphereMatchesClosedForm) {
  Manifold m;
  const Vec3 d(0.3, 0.4, 0);  // centre distance 0.5, radii 0.6: separation -0.1
  ASSERT_TRUE(
      collide_sphere_sphere(sphere(0.4), at(0, 0, 0), sphere(0.2), at(0.3, 0.4, 0), kSpec, m));
  expect_sane(m);
  ASSERT_EQ(m.point_count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.1, kTol);
  EXPECT_TRUE(m.normal.isApprox(d / Real(0.5), Real(1e-6)));
  // Midway between the surface points 0.4 and 0.3 along the normal.
  EXPECT_TRUE(point(m, at(0, 0, 0), 0).isApprox(Real(0.35) * d / Real(0.5), Real(1e-5)));
  // Beyond the speculative distance: nothing.
  EXPECT_FALSE(
      collide_sphere_sphere(sphere(0.4), at(0, 0, 0), sphere(0.2), at(0.63, 0, 0), kSpec, m));
  EXPECT_EQ(m.point_count, 0);
  // Coincident centres: fixed +Y normal, depth the sum of radii.
  ASSERT_TRUE(collide_sphere_sphere(sphere(0.4), at(1, 1, 1), sphere(0.2), at(1, 1, 1), kSpec, m));
  expect_sane(m);
  EXPECT_EQ(m.normal, Vec3::UnitY());
  EXPECT_NEAR(m.points[0].separation, -0.6, kTol);
}

TEST(RoundPairs, SphereCapsuleMatchesClosedForm) {
  Manifold m;
  const Shape cap = capsule(0.2, 1);
  // Capsule along x (turned about z); sphere above its middle and past its end.
  const Transform xc = at(0, 0, 0, axis_angle(std::numbers::pi / 2, Vec3::UnitZ()));
  ASSERT_TRUE(collide_sphere_capsule(sphere(0.3), at(0.5, 0.45, 0), cap, xc, kSpec, m));
  EXPECT_NEAR(m.points[0].separation, -0.05, kTol);
  EXPECT_TRUE(m.normal.isApprox(-Vec3::UnitY(), Real(1e-6)));
  ASSERT_TRUE(collide_sphere_capsule(sphere(0.3), at(1.4, 0, 0), cap, xc, kSpec, m));
  EXPECT_NEAR(m.points[0].separation, -0.1, kTol);
  EXPECT_TRUE(m.normal.isApprox(-Vec3::UnitX(), Real(1e-6)));
  // Centre on the segment: normal across the axis.
  ASSERT_TRUE(collide_sphere_capsule(sphere(0.3), at(0.2, 0, 0), cap, xc, kSpec, m));
  expect_sane(m);
  EXPECT_NEAR(m.normal.x(), 0, 1e-6);
  EXPECT_NEAR(m.points[0].separation, -0.5, kTol);
}

TEST(RoundPairs, CapsuleCapsuleParallelGivesTwoClippedPoints) {
  Manifold m;
  // A along x on [-1, 1], B along x on [0.5, 2.5], 0.35 above: overlap [0.5, 1].
  const Quat qx = axis_angle(std::numbers::pi / 2, Vec3::UnitZ());
  ASSERT_TRUE(collide_capsule_capsule(capsule(0.2, 1), at(0, 0, 0, qx), capsule(0.2, 1),
                                      at(1.5, 0.35, 0, qx), kSpec, m));
  expect_sane(m);
  ASSERT_EQ(m.point_count, 2);
  EXPECT_TRUE(m.normal.isApprox(Vec3::UnitY(), Real(1e-6)));
  std::vector<Real> xs;
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.05, kTol);
    xs.push_back(point(m, at(0, 0, 0), i).x());
  }
  EXPECT_NEAR(std::min(xs[0], xs[1]), 0.5, 1e-5);
  EXPECT_NEAR(std::max(xs[0], xs[1]), 1.0, 1e-5);
  // Feature ids: B's lower end (id 2) and A's upper end (id 1); unchanged after a small slide.
  const uint32_t id0 = m.points[0].feature_id, id1 = m.points[1].feature_id;
  EXPECT_NE(id0, id1);
  ASSERT_TRUE(collide_capsule_capsule(capsule(0.2, 1), at(0, 0, 0, qx), capsule(0.2, 1),
                                      at(1.52, 0.35, 0.01, qx), kSpec, m));
  ASSERT_EQ(m.point_count, 2);
  EXPECT_EQ(m.points[0].feature_id, id0);
  EXPECT_EQ(m.points[1].feature_id, id1);
  // Identical capsules at one pose: finite, two points, normal across the axis.
  ASSERT_TRUE(collide_capsule_capsule(capsule(0.2, 1), at(0, 0, 0), capsule(0.2, 1), at(0, 0, 0),
                                      kSpec, m));
  expect_sane(m);
  EXPECT_EQ(m.point_count, 2);
  EXPECT_NEAR(m.normal.y(), 0, 1e-6);
  EXPECT_NEAR(m.points[0].separation, -0.4, kTol);
}

TEST(RoundPairs, CapsuleCapsuleSkewMatchesClosedForm) {
  Manifold m;
  // A along y, B along z through (0.45, 0.3, *): gap 0.45 - 0.5.
  ASSERT_TRUE(collide_capsule_capsule(
      capsule(0.3, 1), at(0, 0, 0), capsule(0.2, 1),
      at(0.45, 0.3, 0.2, axis_angle(std::numbers::pi / 2, Vec3::UnitX())), kSpec, m));
  ASSERT_EQ(m.point_count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.05, kTol);
  EXPECT_TRUE(m.normal.isApprox(Vec3::UnitX(), Real(1e-6)));
  EXPECT_TRUE(point(m, at(0, 0, 0), 0).isApprox(Vec3(0.275, 0.3, 0), Real(1e-5)));
}

TEST(RoundPairs, SphereBoxOutsideAndInside) {
  Manifold m;
  const Shape b = box(1, 2, 3);
  const Transform xb = at(1, 0, 0, axis_angle(0.4, Vec3::UnitZ()));
  const Mat3 r = xb.rotation.toRotationMatrix();
  // Face region: 0.25 from the +x face in box coordinates, radius 0.3.
  Transform xa = at(0, 0, 0);
  xa.position = xb.apply(Vec3(1.25, 0.5, -1));
  ASSERT_TRUE(collide_sphere_box(sphere(0.3), xa, b, xb, kSpec, m));
  EXPECT_NEAR(m.points[0].separation, -0.05, kTol);
  EXPECT_TRUE(m.normal.isApprox(-r.col(0), Real(1e-5)));
  // Edge region: distance sqrt(0.2^2 + 0.1^2) from the +x+y edge.
  xa.position = xb.apply(Vec3(1.2, 2.1, 0));
  ASSERT_TRUE(collide_sphere_box(sphere(0.3), xa, b, xb, kSpec, m));
  EXPECT_NEAR(m.points[0].separation, std::sqrt(0.05) - 0.3, kTol);
  // Inside: least penetration through the +y face (0.1 below it).
  xa.position = xb.apply(Vec3(0.2, 1.9, 0.5));
  ASSERT_TRUE(collide_sphere_box(sphere(0.3), xa, b, xb, kSpec, m));
  EXPECT_NEAR(m.points[0].separation, -0.4, kTol);
  EXPECT_TRUE(m.normal.isApprox(-r.col(1), Real(1e-5)));
  // Centre at the box centre: finite, pushed through the nearest (x) face.
  ASSERT_TRUE(collide_sphere_box(sphere(0.3), xb, b, xb, kSpec, m));
  expect_sane(m);
  EXPECT_NEAR(m.points[0].separation, -1.3, kTol);
}

TEST(RoundPairs, SphereConvexMatchesSphereBox) {
  Manifold m, ref;
  const Shape hull = box_hull(1), cube = box(1, 1, 1);
  const Transform xb = at(0, 1, 0, axis_angle(0.3, Vec3(1, 1, 0)));
  for (const Vec3& local : {Vec3(1.2, 0.3, 0.1), Vec3(1.1, 1.1, 0.2), Vec3(0.7, 0.2, -0.1)}) {
    Transform xa;
    xa.position = xb.apply(local);
    ASSERT_TRUE(collide_sphere_convex(sphere(0.35), xa, hull, xb, kSpec, m));
    ASSERT_TRUE(collide_sphere_box(sphere(0.35), xa, cube, xb, kSpec, ref));
    expect_sane(m);
    EXPECT_NEAR(m.points[0].separation, ref.points[0].separation, 1e-4);
    EXPECT_TRUE(m.normal.isApprox(ref.normal, Real(1e-3)));
  }
  // Everywhere around and inside the cube (over a face: the face's distance; beside the faces:
  // GJK; inside: the nearest face's depth), against the closed form. The normals are compared
  // away from the cube's diagonal planes, where two faces are equally near and either is right.
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> u(Real(-1.6), Real(1.6));
  int over = 0, beside = 0, inside = 0;
  for (int i = 0; i < 600; ++i) {
    const Vec3 local{u(rng), u(rng), u(rng)};
    Transform xa;
    xa.position = xb.apply(local);
    ASSERT_TRUE(collide_sphere_convex(sphere(0.35), xa, hull, xb, 10, m)) << i;
    ASSERT_TRUE(collide_sphere_box(sphere(0.35), xa, cube, xb, 10, ref)) << i;
    EXPECT_NEAR(m.points[0].separation, ref.points[0].separation, 1e-4) << i;
    const Vec3 a = local.cwiseAbs();
    const int outside = (a.array() > 1).count();
    outside == 0 ? ++inside : outside == 1 ? ++over : ++beside;
    Real sorted[3] = {a.x(), a.y(), a.z()};
    std::sort(sorted, sorted + 3);
    if (outside > 0 || sorted[2] - sorted[1] > Real(1e-3)) {
      EXPECT_TRUE(m.normal.isApprox(ref.normal, Real(1e-3))) << i;
    }
  }
  EXPECT_GT(over, 100);
  EXPECT_GT(beside, 100);
  EXPECT_GT(inside, 20);
  // Against a cylinder side: the gap is the radial distance minus both radii.
  ASSERT_TRUE(collide_sphere_convex(sphere(0.2), at(0.65, 0.1, 0), cylinder(0.5, 1), at(0, 0, 0),
                                    kSpec, m));
  EXPECT_NEAR(m.points[0].separation, -0.05, 1e-4);
  EXPECT_TRUE(m.normal.isApprox(-Vec3::UnitX(), Real(1e-4)));
}

TEST(RoundPairs, ShapesOnPlaneGiveExpectedPoints) {
  Manifold m;
  const Shape g = ground();
  const Transform xg = at(0, 0, 0);
  ASSERT_TRUE(collide_convex_plane(sphere(0.5), at(0, 0.45, 0), g, xg, kSpec, m));
  ASSERT_EQ(m.point_count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.05, kTol);
  EXPECT_EQ(m.normal, -Vec3::UnitY());
  // Capsule lying along x: both ends touch.
  ASSERT_TRUE(collide_convex_plane(capsule(0.2, 1),
                                   at(0, 0.19, 0, axis_angle(std::numbers::pi / 2, Vec3::UnitZ())),
                                   g, xg, kSpec, m));
  ASSERT_EQ(m.point_count, 2);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].separation, -0.01, kTol);
  // Box resting flat: 4 corners; tilted 0.5 rad about x (lowest corners at 0.91 - 0.5 cos 0.5 -
  // sin 0.5 = -0.008): the 2 lower corners only.
  ASSERT_TRUE(collide_convex_plane(box(1, 0.5, 1), at(3, 0.49, 0), g, xg, kSpec, m));
  ASSERT_EQ(m.point_count, 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.01, kTol);
    EXPECT_NEAR(std::abs(point(m, at(3, 0.49, 0), i).x() - 3), 1, 1e-5);
  }
  ASSERT_TRUE(collide_convex_plane(box(1, 0.5, 1), at(0, 0.91, 0, axis_angle(0.5, Vec3::UnitX())),
                                   g, xg, kSpec, m));
  EXPECT_EQ(m.point_count, 2);
  // Hull (a cube) resting flat: 4 points like the box; deep: still 4 spanning the face.
  ASSERT_TRUE(collide_convex_plane(box_hull(1), at(0, 0.995, 0), g, xg, kSpec, m));
  EXPECT_EQ(m.point_count, 4);
  ASSERT_TRUE(collide_convex_plane(box_hull(1), at(0, -5, 0), g, xg, kSpec, m));
  EXPECT_EQ(m.point_count, 4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.points[i].separation, -6, kTol * 10);
  // Cylinder on its cap: a square of 4 rim points; on its side: the 2 ends of the lowest line.
  ASSERT_TRUE(collide_convex_plane(cylinder(0.5, 1), at(0, 0.99, 0), g, xg, kSpec, m));
  ASSERT_EQ(m.point_count, 4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.points[i].separation, -0.01, kTol);
  ASSERT_TRUE(collide_convex_plane(cylinder(0.5, 1),
                                   at(0, 0.49, 0, axis_angle(std::numbers::pi / 2, Vec3::UnitX())),
                                   g, xg, kSpec, m));
  ASSERT_EQ(m.point_count, 2);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].separation, -0.01, kTol);
  // Tilted plane with an offset, seen through a moved plane body.
  ASSERT_TRUE(collide_convex_plane(sphere(0.5), at(0, 2.4, 0), g, at(0, 2, 0), kSpec, m));
  EXPECT_NEAR(m.points[0].separation, -0.1, kTol);
  // Above the speculative distance: nothing.
  EXPECT_FALSE(collide_convex_plane(box(1, 1, 1), at(0, 1.1, 0), g, xg, kSpec, m));
}

TEST(RoundPairs, PlaneFeatureIdsStableUnderSmallMotion) {
  Manifold m;
  const Shape g = ground();
  ASSERT_TRUE(collide_convex_plane(box(1, 0.5, 1), at(0, 0.49, 0), g, at(0, 0, 0), kSpec, m));
  uint32_t ids[4];
  for (int i = 0; i < 4; ++i) ids[i] = m.points[i].feature_id;
  ASSERT_TRUE(collide_convex_plane(box(1, 0.5, 1),
                                   at(0.01, 0.492, 0, axis_angle(0.003, Vec3(1, 0, 1))), g,
                                   at(0, 0, 0), kSpec, m));
  ASSERT_EQ(m.point_count, 4);
  for (int i = 0; i < 4; ++i) {
    bool found = false;
    for (uint32_t id : ids) found = found || id == m.points[i].feature_id;
    EXPECT_TRUE(found);
  }
}

TEST(ManifoldReduce, KeepsDeepestAndSpansTheLargestArea) {
  // A 5 x 5 grid on the xz-plane; the deepest point is an interior one.
  std::vector<Vec3> pos;
  std::vector<Real> sep;
  for (int i = 0; i < 5; ++i) {
    for (int k = 0; k < 5; ++k) {
      pos.emplace_back(Real(i), 0, Real(k));
      sep.push_back(i == 2 && k == 1 ? Real(-0.5) : Real(-0.1));
    }
  }
  int out[kMaxManifoldPoints];
  ASSERT_EQ(reduce_to_four(pos, sep, Vec3::UnitY(), out), 4);
  EXPECT_EQ(out[0], 2 * 5 + 1);
  // Farthest from (2, 0, 1): corner (0,0,4) or (4,0,4) (distance^2 13); ties to the lower index.
  EXPECT_EQ(pos[out[1]], Vec3(0, 0, 4));
  // The quadrilateral spans more than half the grid.
  Real area = 0;
  const Vec3 c = (pos[out[0]] + pos[out[1]] + pos[out[2]] + pos[out[3]]) / 4;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      area = std::max(area, std::abs((pos[out[i]] - c).cross(pos[out[j]] - c).y()));
    }
  }
  EXPECT_GT(area, 4);
  // Four or fewer candidates pass through; collinear ones stop at two.
  EXPECT_EQ(reduce_to_four(std::span<const Vec3>(pos.data(), 3),
                           std::span<const Real>(sep.data(), 3), Vec3::UnitY(), out),
            3);
  std::vector<Vec3> line;
  for (int i = 0; i < 6; ++i) line.emplace_back(Real(i), 0, 0);
  const std::vector<Real> zero(6, 0);
  EXPECT_EQ(reduce_to_four(line, zero, Vec3::UnitY(), out), 2);
}

}  // namespace narrowphase_round_pairs_test
}  // namespace elan::detail
