// SPDX-License-Identifier: MIT
// Shapes and poses shared by the narrowphase stage tests.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/base/contact.hpp"
#include "core/base/shape.hpp"
#include "narrowphase/collide.hpp"

namespace elan::detail::test {

inline Shape box(Real hx, Real hy, Real hz) {
  ShapeDef d;
  d.type = ShapeType::Box;
  d.half_extents = Vec3(hx, hy, hz);
  return make_shape(d);
}

inline Shape capsule(Real radius, Real half_height) {
  ShapeDef d;
  d.type = ShapeType::Capsule;
  d.radius = radius;
  d.half_height = half_height;
  return make_shape(d);
}

inline Shape cylinder(Real radius, Real half_height) {
  ShapeDef d;
  d.type = ShapeType::Cylinder;
  d.radius = radius;
  d.half_height = half_height;
  return make_shape(d);
}

inline Shape sphere(Real radius) {
  ShapeDef d;
  d.type = ShapeType::Sphere;
  d.radius = radius;
  return make_shape(d);
}

// The randomised tests draw in braces ({d(rng), d(rng), ...}), whose elements are evaluated in
// order: a call's arguments are not, and GCC and Clang evaluate them in opposite orders, so draws
// passed as arguments give each compiler other cases to test.

// Three draws of `d`, in order (scaled by `scale`).
template <class Distribution>
Vec3 draw3(std::mt19937& rng, Distribution& d, Real scale = 1) {
  const Vec3 v{Real(d(rng)), Real(d(rng)), Real(d(rng))};
  return scale * v;
}

// A random rotation for the randomised tests: a normalised quaternion of uniform components with
// w biased positive (away from the double cover's far side).
inline Quat random_turn(std::mt19937& rng, std::uniform_real_distribution<float>& u) {
  const Quat q{u(rng), u(rng), u(rng), u(rng) + Real(1.5)};
  return q.normalized();
}

// The hull of a box's eight corners: must collide exactly like the box.
inline Shape box_hull(Real hx, Real hy, Real hz) {
  ShapeDef d;
  d.type = ShapeType::ConvexHull;
  for (int i = 0; i < 8; ++i) {
    d.points.emplace_back((i & 1) ? hx : -hx, (i & 2) ? hy : -hy, (i & 4) ? hz : -hz);
  }
  return make_shape(d);
}

// Points on a sphere (golden-angle spiral), symmetric enough that the centroid is near 0.
inline Shape round_hull(int n, Real radius) {
  ShapeDef d;
  d.type = ShapeType::ConvexHull;
  for (int i = 0; i < n; ++i) {
    const double y = 1 - 2 * (i + 0.5) / n;
    const double r = std::sqrt(1 - y * y);
    const double t = 2.399963229728653 * i;
    d.points.emplace_back(Real(radius * r * std::cos(t)), Real(radius * y),
                          Real(radius * r * std::sin(t)));
  }
  return make_shape(d);
}

inline Transform pose(const Vec3& p, const Quat& q = Quat::Identity()) {
  return {p, q};
}

inline Transform at(Real x, Real y, Real z, const Quat& q = Quat::Identity()) {
  return pose(Vec3(x, y, z), q);
}

inline Quat axis_angle(Real angle, const Vec3& axis) {
  return Quat(Eigen::AngleAxis<Real>(angle, axis.normalized()));
}

// World contact point of point k (midpoint between the surfaces).
inline Vec3 contact_point(const Manifold& m, const Transform& xa, int k) {
  return xa.position + m.points[k].anchor_a;
}

inline void expect_sane(const Manifold& m, const Transform& xa, const Transform& xb) {
  ASSERT_TRUE(m.normal.allFinite());
  EXPECT_NEAR(m.normal.norm(), 1, 1e-4);
  ASSERT_LE(m.point_count, kMaxManifoldPoints);
  for (int k = 0; k < m.point_count; ++k) {
    ASSERT_TRUE(m.points[k].anchor_a.allFinite());
    ASSERT_TRUE(std::isfinite(m.points[k].separation));
    // Measured from A's centre: each body is convex with its centre inside and the point is on
    // both surfaces to within the separation, so it lies between the centres along the normal.
    const Real slack = std::abs(m.points[k].separation) + Real(1e-4);
    EXPECT_GE(m.normal.dot(m.points[k].anchor_a), -slack);
    EXPECT_LE(m.normal.dot(m.points[k].anchor_a - (xb.position - xa.position)), slack);
  }
}

}  // namespace elan::detail::test
