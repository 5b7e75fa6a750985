// SPDX-License-Identifier: MIT
// Support functions of every shape against a brute-force maximum over sampled surface points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/base/shape.hpp"

namespace elan::detail {
namespace shape_support_test {

constexpr double kPi = std::numbers::pi;

// Signed distance (or a function with the same zero set and sign) in the principal frame.
double signed_distance(const Shape& s, const Vec3& p) {
  switch (s.type) {
    case ShapeType::Sphere:
      return p.norm() - s.radius;
    case ShapeType::Box:
      return (p.cwiseAbs() - s.half_extents).maxCoeff();
    case ShapeType::Capsule: {
      const Real y = std::clamp(p.y(), -s.half_height, s.half_height);
      return (p - Vec3(0, y, 0)).norm() - s.radius;
    }
    case ShapeType::Cylinder:
      return std::max(std::hypot(p.x(), p.z()) - s.radius, std::abs(p.y()) - s.half_height);
    case ShapeType::ConvexHull: {
      double d = -1e30;
      for (const HullFace& f : s.hull->faces) d = std::max(d, double(f.normal.dot(p) - f.offset));
      return d;
    }
    default:
      return 0;
  }
}

// Dense samples of the surface, built from the shape's own parameters.
std::vector<Vec3> surface_samples(const Shape& s) {
  std::vector<Vec3> out;
  const int n = 32;
  auto sphere_patch = [&](const Vec3& centre, double r, double y_sign) {
    for (int i = 0; i <= n; ++i) {
      const double phi = kPi * i / n;
      if (y_sign != 0 && (std::cos(phi) * y_sign < 0)) continue;
      for (int k = 0; k < 2 * n; ++k) {
        const double th = kPi * k / n;
        out.push_back(centre + Vec3(Real(r * std::sin(phi) * std::cos(th)), Real(r * std::cos(phi)),
                                    Real(r * std::sin(phi) * std::sin(th))));
      }
    }
  };
  switch (s.type) {
    case ShapeType::Sphere:
      sphere_patch(Vec3::Zero(), s.radius, 0);
      break;
    case ShapeType::Box:
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
          const Real u = Real(2.0 * i / n - 1), v = Real(2.0 * j / n - 1);
          for (Real sign : {Real(-1), Real(1)}) {
            out.push_back(s.half_extents.cwiseProduct(Vec3(sign, u, v)));
            out.push_back(s.half_extents.cwiseProduct(Vec3(u, sign, v)));
            out.push_back(s.half_extents.cwiseProduct(Vec3(u, v, sign)));
          }
        }
      }
      break;
    case ShapeType::Capsule:
    case ShapeType::Cylinder: {
      const bool capsule = s.type == ShapeType::Capsule;
      for (int i = 0; i <= n; ++i) {
        const Real y = Real(s.half_height * (2.0 * i / n - 1));
        for (int k = 0; k < 2 * n; ++k) {
          const double th = kPi * k / n;
          out.emplace_back(Real(s.radius * std::cos(th)), y, Real(s.radius * std::sin(th)));
          if (!capsule) {
            const double rr = s.radius * i / n;
            out.emplace_back(Real(rr * std::cos(th)), s.half_height, Real(rr * std::sin(th)));
            out.emplace_back(Real(rr * std::cos(th)), -s.half_height, Real(rr * std::sin(th)));
          }
        }
      }
      if (capsule) {
        sphere_patch(Vec3(0, s.half_height, 0), s.radius, 1);
        sphere_patch(Vec3(0, -s.half_height, 0), s.radius, -1);
      }
      break;
    }
    case ShapeType::ConvexHull:
      // Points spread over each face polygon (fans of convex combinations), not only vertices.
      for (const HullFace& f : s.hull->faces) {
        const Vec3& o = s.hull->vertices[s.hull->face_vertices[f.first]];
        for (uint32_t k = 1; k + 1 < f.count; ++k) {
          const Vec3& a = s.hull->vertices[s.hull->face_vertices[f.first + k]];
          const Vec3& b = s.hull->vertices[s.hull->face_vertices[f.first + k + 1]];
          for (int i = 0; i <= 8; ++i) {
            for (int j = 0; i + j <= 8; ++j) {
              out.push_back(o + (a - o) * Real(i / 8.0) + (b - o) * Real(j / 8.0));
            }
          }
        }
      }
      break;
    default:
      break;
  }
  return out;
}

std::vector<Shape> test_shapes() {
  std::vector<Shape> shapes;
  ShapeDef d;
  d.type = ShapeType::Sphere;
  d.radius = 0.7f;
  shapes.push_back(make_shape(d));
  d.type = ShapeType::Box;
  d.half_extents = Vec3(0.3f, 1.1f, 0.6f);
  shapes.push_back(make_shape(d));
  d.type = ShapeType::Capsule;
  d.radius = 0.4f;
  d.half_height = 0.9f;
  shapes.push_back(make_shape(d));
  d.type = ShapeType::Cylinder;
  d.radius = 0.8f;
  d.half_height = 0.35f;
  shapes.push_back(make_shape(d));
  d.type = ShapeType::ConvexHull;
  std::mt19937 rng(21);
  std::normal_distribution<Real> g(0, 1);
  for (int i = 0; i < 40; ++i) d.points.push_back(Vec3{g(rng), g(rng) * 0.6f, g(rng) * 1.3f});
  shapes.push_back(make_shape(d));
  return shapes;
}

std::string name_of(const Shape& s) {
  return "shape type " + std::to_string(static_cast<int>(s.type));
}

TEST(ShapeSupport, MatchesBruteForceOverSurfaceSamples) {
  std::mt19937 rng(8);
  std::normal_distribution<Real> g(0, 1);
  std::vector<Vec3> dirs = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(),
                            Vec3::UnitZ(), -Vec3::UnitZ(), Vec3(1, 1, 0), Vec3(0, -1, 1)};
  for (int i = 0; i < 150; ++i) dirs.push_back(Vec3{g(rng), g(rng), g(rng)});
  for (const Shape& s : test_shapes()) {
    SCOPED_TRACE(name_of(s));
    const std::vector<Vec3> samples = surface_samples(s);
    for (const Vec3& d0 : dirs) {
      const Vec3 u = d0.normalized();
      double best = -1e30;
      for (const Vec3& q : samples) best = std::max(best, double(u.dot(q)));
      // Non-unit lengths, down to ones whose squared norm underflows in float.
      for (const Real scale : {Real(1e-30), Real(1e-3), Real(1), Real(250)}) {
        const Vec3 d = d0 * scale;
        const Vec3 p = support(s, d);
        // The support point is on the surface (so its height is at most the true maximum)...
        EXPECT_NEAR(signed_distance(s, p), 0, 1e-5) << p.transpose();
        // ...and at least as high as every sample. Samples lie on the surface, so together these
        // pin the height to the true maximum; 1e-5 is float rounding of coordinates of size ~2.
        EXPECT_GE(u.dot(p), best - 1e-5) << "d = " << d.transpose();
      }
    }
  }
}

TEST(ShapeSupport, HullSupportIsAVertex) {
  const Shape s = test_shapes().back();
  std::mt19937 rng(2);
  std::normal_distribution<Real> g(0, 1);
  for (int i = 0; i < 100; ++i) {
    const Vec3 p = support(s, Vec3{g(rng), g(rng), g(rng)});
    EXPECT_NE(std::find(s.hull->vertices.begin(), s.hull->vertices.end(), p),
              s.hull->vertices.end());
  }
}

TEST(ShapeSupport, ZeroDirectionGivesAFiniteSurfacePoint) {
  for (const Shape& s : test_shapes()) {
    SCOPED_TRACE(name_of(s));
    for (const Vec3& d : {Vec3(Vec3::Zero()), Vec3(0, 1e-30f, 0), Vec3(1e-30f, 0, -1e-30f)}) {
      const Vec3 p = support(s, d);
      ASSERT_TRUE(p.allFinite()) << p.transpose();
      EXPECT_NEAR(signed_distance(s, p), 0, 1e-5) << p.transpose();
    }
  }
}

}  // namespace shape_support_test
}  // namespace elan::detail
