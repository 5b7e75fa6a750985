// SPDX-License-Identifier: MIT
// Bounds stage: every shape type's box contains the shape over the whole step (start, middle and
// end pose), is tight for a body at rest, and planes get infinite or axis-aligned boxes, no NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "broadphase/bounds.hpp"

namespace elan::detail {
namespace broadphase_bounds_test {

constexpr Real kInf = std::numeric_limits<Real>::infinity();

Real uniform(std::mt19937& rng, double lo, double hi) {
  return Real(std::uniform_real_distribution<double>(lo, hi)(rng));
}

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g(0, 1);
  return Vec3{Real(g(rng)), Real(g(rng)), Real(g(rng))}.normalized();
}

// Closed-form support points (principal frame), written here so the test does not lean on the
// code under test or on shape.cpp.
Vec3 support_of(const Shape& s, const Vec3& d) {
  const auto sgn = [](Real v) { return v >= 0 ? Real(1) : Real(-1); };
  switch (s.type) {
    case ShapeType::Sphere:
      return s.radius * d.normalized();
    case ShapeType::Box:
      return Vec3(sgn(d.x()) * s.half_extents.x(), sgn(d.y()) * s.half_extents.y(),
                  sgn(d.z()) * s.half_extents.z());
    case ShapeType::Capsule:
      return Vec3(0, sgn(d.y()) * s.half_height, 0) + s.radius * d.normalized();
    case ShapeType::Cylinder: {
      const Real r = std::hypot(d.x(), d.z());
      const Vec3 rim = r > 0 ? Vec3(Vec3(d.x() / r, 0, d.z() / r) * s.radius) : Vec3(Vec3::Zero());
      return Vec3(0, sgn(d.y()) * s.half_height, 0) + rim;
    }
    case ShapeType::ConvexHull: {
      Vec3 best = s.hull->vertices[0];
      for (const Vec3& v : s.hull->vertices) {
        if (v.dot(d) > best.dot(d)) best = v;
      }
      return best;
    }
    case ShapeType::Plane:
    case ShapeType::Mesh:  // not convex: their bounds are the local box (tested elsewhere)
    case ShapeType::Heightfield:
    case ShapeType::Compound:
      break;
  }
  return Vec3::Zero();
}

Shape random_shape(ShapeType type, std::mt19937& rng) {
  Shape s;
  s.type = type;
  switch (type) {
    case ShapeType::Sphere:
      s.radius = uniform(rng, 0.1, 2);
      s.bounding_radius = s.radius;
      break;
    case ShapeType::Box:
      s.half_extents = Vec3{uniform(rng, 0.05, 2), uniform(rng, 0.05, 2), uniform(rng, 0.05, 2)};
      s.bounding_radius = s.half_extents.norm();
      break;
    case ShapeType::Capsule:
    case ShapeType::Cylinder:
      s.radius = uniform(rng, 0.05, 1);
      s.half_height = uniform(rng, 0.05, 2);
      s.bounding_radius = type == ShapeType::Capsule ? s.radius + s.half_height
                                                     : std::hypot(s.radius, s.half_height);
      break;
    case ShapeType::ConvexHull: {
      auto hull = std::make_shared<ConvexHull>();
      // Off-centre cloud: the principal frame need not centre the local box.
      const Vec3 shift{uniform(rng, -0.3, 0.3), uniform(rng, -0.3, 0.3), uniform(rng, -0.3, 0.3)};
      const Vec3 scale{uniform(rng, 0.2, 2), uniform(rng, 0.2, 2), uniform(rng, 0.2, 2)};
      for (int k = 0; k < 12; ++k) {
        hull->vertices.push_back(random_unit(rng).cwiseProduct(scale) + shift);
      }
      s.local_min = s.local_max = hull->vertices[0];
      for (const Vec3& v : hull->vertices) {
        s.local_min = s.local_min.cwiseMin(v);
        s.local_max = s.local_max.cwiseMax(v);
        s.bounding_radius = std::max(s.bounding_radius, v.norm());
      }
      s.hull = hull;
      break;
    }
    case ShapeType::Plane:
    case ShapeType::Mesh:
    case ShapeType::Heightfield:
    case ShapeType::Compound:
      break;
  }
  return s;
}

struct Box {
  Vec3 lo, hi;
};

Box box_of(const BoundsColumns& b, std::size_t i) {
  return {Vec3(b.min_x[i], b.min_y[i], b.min_z[i]), Vec3(b.max_x[i], b.max_y[i], b.max_z[i])};
}

// Exact world box of the shape at (p, q): support points along the six axis directions.
Box exact_box(const Shape& s, const Vec3& p, const Quat& q) {
  Box box;
  for (int a = 0; a < 3; ++a) {
    const Vec3 e = Vec3::Unit(a);
    box.hi[a] = (q * support_of(s, q.conjugate() * e) + p)[a];
    box.lo[a] = (q * support_of(s, q.conjugate() * -e) + p)[a];
  }
  return box;
}

TEST(Bounds, ContainShapeOverTheStepForEveryShapeType) {
  std::mt19937 rng(11);
  const ShapeType types[] = {ShapeType::Sphere, ShapeType::Box, ShapeType::Capsule,
                             ShapeType::Cylinder, ShapeType::ConvexHull};
  std::vector<Shape> shapes;
  BodyStore bodies;
  for (int k = 0; k < 1000; ++k) {  // more than one block of bodies
    shapes.push_back(random_shape(types[k % 5], rng));
    const std::size_t i = bodies.push_back();
    bodies.shape[i] = uint32_t(shapes.size() - 1);
    bodies.set_position(i, Vec3{uniform(rng, -50, 50), uniform(rng, -50, 50), uniform(rng, -5, 5)});
    bodies.set_orientation(i, Quat{random_unit(rng).x(), random_unit(rng).y(), random_unit(rng).z(),
                                   uniform(rng, -1, 1)}
                                  .normalized());
    const Vec3 along = random_unit(rng);
    bodies.set_linear_velocity(i, along * uniform(rng, 0, 30));
    const Vec3 about = random_unit(rng);
    bodies.set_angular_velocity(i, about * uniform(rng, 0, 40));
  }
  const Real dt = Real(1) / 60, margin = Real(0.01);
  BoundsColumns out;
  compute_bounds(bodies, shapes, dt, margin, out);
  ASSERT_EQ(out.size(), bodies.size());

  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Shape& s = shapes[bodies.shape[i]];
    const Box box = box_of(out, i);
    const Vec3 w = bodies.angular_velocity(i);
    for (Real t : {Real(0), dt / 2, dt}) {
      // Pose after time t: p + v t and the rotation by the angle |w| t about w (world frame).
      const Vec3 p = bodies.position(i) + bodies.linear_velocity(i) * t;
      const Quat turn(Eigen::AngleAxis<Real>(w.norm() * t, w.normalized()));
      const Quat q = (turn * bodies.orientation(i)).normalized();
      const Box exact = exact_box(s, p, q);
      // Float rounding of a sum of terms of size ~60 m: 1e-4 m is some 30 ulp there.
      const Real tol = Real(1e-4);
      for (int a = 0; a < 3; ++a) {
        ASSERT_LE(box.lo[a], exact.lo[a] + tol) << "body " << i << " type " << int(s.type);
        ASSERT_GE(box.hi[a], exact.hi[a] - tol) << "body " << i << " type " << int(s.type);
      }
    }
  }
}

TEST(Bounds, TightForBodiesAtRest) {
  std::mt19937 rng(5);
  const ShapeType types[] = {ShapeType::Sphere, ShapeType::Box, ShapeType::Capsule,
                             ShapeType::Cylinder};
  std::vector<Shape> shapes;
  BodyStore bodies;
  for (int k = 0; k < 400; ++k) {
    shapes.push_back(random_shape(types[k % 4], rng));
    const std::size_t i = bodies.push_back();
    bodies.shape[i] = uint32_t(k);
    bodies.set_position(i, Vec3{uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5)});
    bodies.set_orientation(
        i, Quat{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)}
               .normalized());
  }
  const Real margin = Real(0.05);
  BoundsColumns out;
  compute_bounds(bodies, shapes, Real(1) / 60, margin, out);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    // Sphere, box, capsule and cylinder bounds are exact: the box is the support extent plus the
    // margin, to float rounding of terms of size ~10 m (1e-5 m).
    const Box exact = exact_box(shapes[i], bodies.position(i), bodies.orientation(i));
    const Box box = box_of(out, i);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(box.lo[a], exact.lo[a] - margin, Real(1e-5)) << "type " << int(shapes[i].type);
      EXPECT_NEAR(box.hi[a], exact.hi[a] + margin, Real(1e-5)) << "type " << int(shapes[i].type);
    }
  }
}

TEST(Bounds, ConvexHullBoxIsTheRotatedPrincipalBox) {
  std::mt19937 rng(2);
  std::vector<Shape> shapes = {random_shape(ShapeType::ConvexHull, rng)};
  BodyStore bodies;
  const std::size_t i = bodies.push_back();
  const Quat q(Eigen::AngleAxis<Real>(Real(0.7), Vec3(1, 2, 3).normalized()));
  bodies.set_orientation(i, q);
  bodies.set_position(i, Vec3(1, -2, 3));
  BoundsColumns out;
  compute_bounds(bodies, shapes, Real(0.01), 0, out);
  // Box of the eight rotated corners of [local_min, local_max]: the stated conservative bound.
  Box expected{Vec3::Constant(kInf), Vec3::Constant(-kInf)};
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? shapes[0].local_max.x() : shapes[0].local_min.x(),
                      (c & 2) ? shapes[0].local_max.y() : shapes[0].local_min.y(),
                      (c & 4) ? shapes[0].local_max.z() : shapes[0].local_min.z());
    const Vec3 w = q * corner + bodies.position(i);
    expected.lo = expected.lo.cwiseMin(w);
    expected.hi = expected.hi.cwiseMax(w);
  }
  const Box box = box_of(out, i);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(box.lo[a], expected.lo[a], Real(1e-5));
    EXPECT_NEAR(box.hi[a], expected.hi[a], Real(1e-5));
  }
}

TEST(Bounds, FastSpinIsCappedAtTheBoundingSphere) {
  std::vector<Shape> shapes(1);
  shapes[0].type = ShapeType::Box;
  shapes[0].half_extents = Vec3(2, Real(0.1), Real(0.1));
  shapes[0].bounding_radius = shapes[0].half_extents.norm();
  BodyStore bodies;
  const std::size_t i = bodies.push_back();
  bodies.set_angular_velocity(i, Vec3(0, 0, 1000));
  BoundsColumns out;
  compute_bounds(bodies, shapes, Real(1) / 60, 0, out);
  // Extent on y: |R| h = 0.1, grown by at most the bounding radius.
  EXPECT_NEAR(out.max_y[i], Real(0.1) + shapes[0].bounding_radius, Real(1e-5));
  EXPECT_NEAR(out.min_y[i], -(Real(0.1) + shapes[0].bounding_radius), Real(1e-5));
}

TEST(Bounds, PlanesAreInfiniteOrAxisAlignedAndNeverNaN) {
  std::vector<Shape> shapes(3);
  for (Shape& s : shapes) s.type = ShapeType::Plane;
  shapes[0].plane_normal = Vec3::UnitY();  // y <= 1 in the body frame
  shapes[0].plane_offset = 1;
  shapes[1].plane_normal = -Vec3::UnitX();  // -x <= 2, i.e. x >= -2
  shapes[1].plane_offset = 2;
  shapes[2].plane_normal = Vec3(1, 1, 0).normalized();
  BodyStore bodies;
  for (int k = 0; k < 4; ++k) {
    const std::size_t i = bodies.push_back();
    bodies.shape[i] = uint32_t(std::min(k, 2));
    bodies.set_position(i, Vec3(0, 3, 0));
  }
  // The fourth: the tilted plane turned about z stays tilted, so its box stays infinite.
  bodies.set_orientation(3, Quat(Eigen::AngleAxis<Real>(Real(0.3), Vec3::UnitZ())));
  const Real margin = Real(0.1);
  BoundsColumns out;
  compute_bounds(bodies, shapes, Real(1) / 60, margin, out);
  for (std::size_t i = 0; i < 4; ++i) {
    const Box box = box_of(out, i);
    for (int a = 0; a < 3; ++a) {
      EXPECT_FALSE(std::isnan(box.lo[a]) || std::isnan(box.hi[a]));
    }
  }
  EXPECT_EQ(box_of(out, 0).hi.y(), Real(4) + margin);
  EXPECT_EQ(box_of(out, 0).lo.y(), -kInf);
  EXPECT_EQ(box_of(out, 0).hi.x(), kInf);
  EXPECT_EQ(box_of(out, 0).lo.z(), -kInf);
  EXPECT_EQ(box_of(out, 1).lo.x(), Real(-2) - margin);
  EXPECT_EQ(box_of(out, 1).hi.x(), kInf);
  EXPECT_EQ(box_of(out, 1).lo.y(), -kInf);
  for (std::size_t i : {2u, 3u}) {
    EXPECT_EQ(box_of(out, i).lo, Vec3::Constant(-kInf));
    EXPECT_EQ(box_of(out, i).hi, Vec3::Constant(kInf));
  }
}

}  // namespace broadphase_bounds_test
}  // namespace elan::detail
