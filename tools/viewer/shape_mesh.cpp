// SPDX-License-Identifier: MIT
#include "tools/viewer/shape_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace elan::viewer {
namespace {

constexpr float kPi = 3.14159265358979f;

void push(MeshData& m, const Eigen::Vector3f& p, const Eigen::Vector3f& n) {
  m.vertices.push_back({{p.x(), p.y(), p.z()}, {n.x(), n.y(), n.z()}});
}

// One flat triangle: its own three vertices with the face normal (counter-clockwise seen from
// the side the normal points to).
void flat_triangle(MeshData& m, const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                   const Eigen::Vector3f& c) {
  Eigen::Vector3f n = (b - a).cross(c - a);
  const float len = n.norm();
  if (!(len > 0)) return;
  n /= len;
  const uint32_t base = uint32_t(m.vertices.size());
  push(m, a, n);
  push(m, b, n);
  push(m, c, n);
  m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
}

Eigen::Vector3f f3(const Vec3& v) {
  return v.cast<float>();
}

// A surface of revolution about Y: `profile` gives (radius, y, normal radius, normal y) for
// each ring from bottom to top.
MeshData revolve(const std::vector<Eigen::Vector4f>& profile, int segments) {
  MeshData m;
  for (const Eigen::Vector4f& ring : profile) {
    for (int s = 0; s <= segments; ++s) {
      const float a = 2 * kPi * float(s) / float(segments);
      const float c = std::cos(a), sn = std::sin(a);
      push(m, {ring[0] * c, ring[1], ring[0] * sn},
           Eigen::Vector3f(ring[2] * c, ring[3], ring[2] * sn));
    }
  }
  const uint32_t row = uint32_t(segments + 1);
  for (uint32_t r = 0; r + 1 < profile.size(); ++r) {
    for (uint32_t s = 0; s < uint32_t(segments); ++s) {
      const uint32_t a = r * row + s, b = a + 1, c = a + row, d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
  }
  return m;
}

// A flat disc at height y facing `up` (+1 or -1), radius 1.
void disc(MeshData& m, float y, float up, int segments) {
  for (int s = 0; s < segments; ++s) {
    const float a0 = 2 * kPi * float(s) / float(segments);
    const float a1 = 2 * kPi * float(s + 1) / float(segments);
    const Eigen::Vector3f c(0, y, 0), p0(std::cos(a0), y, std::sin(a0)),
        p1(std::cos(a1), y, std::sin(a1));
    if (up > 0) {
      flat_triangle(m, c, p1, p0);
    } else {
      flat_triangle(m, c, p0, p1);
    }
  }
}

}  // namespace

MeshData unit_sphere(int rings, int segments) {
  std::vector<Eigen::Vector4f> profile;
  for (int r = 0; r <= rings; ++r) {
    const float t = -kPi / 2 + kPi * float(r) / float(rings);
    profile.emplace_back(std::cos(t), std::sin(t), std::cos(t), std::sin(t));
  }
  return revolve(profile, segments);
}

MeshData unit_hemisphere(int rings, int segments) {
  std::vector<Eigen::Vector4f> profile;
  const int half = std::max(rings / 2, 2);
  for (int r = 0; r <= half; ++r) {
    const float t = kPi / 2 * float(r) / float(half);
    profile.emplace_back(std::cos(t), std::sin(t), std::cos(t), std::sin(t));
  }
  return revolve(profile, segments);
}

MeshData unit_tube(int segments) {
  return revolve({{1, -1, 1, 0}, {1, 1, 1, 0}}, segments);
}

MeshData unit_box() {
  MeshData m;
  // Each face: its normal axis and sign; corners counter-clockwise seen from outside.
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      Eigen::Vector3f c[4];
      const float su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
      for (int k = 0; k < 4; ++k) {
        c[k][axis] = sign;
        c[k][u] = su[k];
        c[k][v] = sv[k] * sign;
      }
      flat_triangle(m, c[0], c[1], c[2]);
      flat_triangle(m, c[0], c[2], c[3]);
    }
  }
  return m;
}

MeshData unit_cylinder(int segments) {
  MeshData m = revolve({{1, -1, 1, 0}, {1, 1, 1, 0}}, segments);
  disc(m, 1, 1, segments);
  disc(m, -1, -1, segments);
  return m;
}

MeshData capsule(float radius, float half_height, int rings, int segments) {
  // Two hemispheres joined by the cylinder between their equators.
  std::vector<Eigen::Vector4f> profile;
  const int half = std::max(rings / 2, 2);
  for (int r = 0; r <= half; ++r) {
    const float t = -kPi / 2 + kPi / 2 * float(r) / float(half);
    profile.emplace_back(radius * std::cos(t), -half_height + radius * std::sin(t), std::cos(t),
                         std::sin(t));
  }
  for (int r = 0; r <= half; ++r) {
    const float t = kPi / 2 * float(r) / float(half);
    profile.emplace_back(radius * std::cos(t), half_height + radius * std::sin(t), std::cos(t),
                         std::sin(t));
  }
  return revolve(profile, segments);
}

MeshData convex_hull(const std::vector<Vec3>& input) {
  std::vector<Eigen::Vector3f> p;
  for (const Vec3& v : input) p.push_back(f3(v));
  // Thinning a large cloud: keep the most extreme point along each of a fixed set of directions
  // (a Fibonacci sphere), which keeps the silhouette while bounding the O(n^4) search.
  constexpr std::size_t kMaxPoints = 96;
  if (p.size() > kMaxPoints) {
    std::vector<Eigen::Vector3f> kept;
    for (std::size_t k = 0; k < 2 * kMaxPoints; ++k) {
      const float y = 1 - 2 * (float(k) + 0.5f) / float(2 * kMaxPoints);
      const float r = std::sqrt(std::max(0.0f, 1 - y * y));
      const float a = 2.39996323f * float(k);
      const Eigen::Vector3f d(r * std::cos(a), y, r * std::sin(a));
      std::size_t best = 0;
      for (std::size_t i = 1; i < p.size(); ++i) best = p[i].dot(d) > p[best].dot(d) ? i : best;
      if (std::find(kept.begin(), kept.end(), p[best]) == kept.end()) kept.push_back(p[best]);
      if (kept.size() >= kMaxPoints) break;
    }
    p = kept;
  }
  float scale = 0;
  for (const Eigen::Vector3f& v : p) scale = std::max(scale, v.cwiseAbs().maxCoeff());
  const float eps = 1e-5f * std::max(scale, 1e-6f);
  MeshData m;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        Eigen::Vector3f normal = (p[j] - p[i]).cross(p[k] - p[i]);
        const float len = normal.norm();
        if (!(len > eps * scale)) continue;
        normal /= len;
        bool above = false, below = false;
        for (std::size_t q = 0; q < n && !(above && below); ++q) {
          const float d = normal.dot(p[q] - p[i]);
          above = above || d > eps;
          below = below || d < -eps;
        }
        if (above && below) continue;
        // Every point on one side: a face, wound so that its normal points away from them.
        if (above) {
          flat_triangle(m, p[i], p[k], p[j]);
        } else {
          flat_triangle(m, p[i], p[j], p[k]);
        }
      }
    }
  }
  return m;
}

MeshData triangle_mesh(const std::vector<Vec3>& vertices,
                       const std::vector<std::array<uint32_t, 3>>& triangles) {
  MeshData m;
  m.vertices.reserve(triangles.size() * 3);
  m.indices.reserve(triangles.size() * 3);
  for (const auto& t : triangles) {
    if (t[0] >= vertices.size() || t[1] >= vertices.size() || t[2] >= vertices.size()) continue;
    flat_triangle(m, f3(vertices[t[0]]), f3(vertices[t[1]]), f3(vertices[t[2]]));
  }
  return m;
}

MeshData heightfield(const ShapeDef& def) {
  MeshData m;
  const uint32_t cols = def.columns;
  if (cols < 2 || def.heights.size() < 2 * std::size_t(cols)) return m;
  const uint32_t rows = uint32_t(def.heights.size() / cols);
  const auto at = [&](uint32_t i, uint32_t j) {
    return Eigen::Vector3f(float(i) * float(def.spacing_x), float(def.heights[j * cols + i]),
                           float(j) * float(def.spacing_z));
  };
  for (uint32_t j = 0; j + 1 < rows; ++j) {
    for (uint32_t i = 0; i + 1 < cols; ++i) {
      // Counter-clockwise seen from above (+Y). A triangle with a hole (a NaN height) at a
      // corner is not there.
      const Eigen::Vector3f p00 = at(i, j), p01 = at(i, j + 1), p11 = at(i + 1, j + 1),
                            p10 = at(i + 1, j);
      if (!std::isnan(p00.y() + p01.y() + p11.y())) flat_triangle(m, p00, p01, p11);
      if (!std::isnan(p00.y() + p11.y() + p10.y())) flat_triangle(m, p00, p11, p10);
    }
  }
  return m;
}

MeshData plane_quad(const Vec3& normal_in, Real offset) {
  Eigen::Vector3f n = f3(normal_in);
  n = n.norm() > 0 ? n.normalized() : Eigen::Vector3f::UnitY();
  const Eigen::Vector3f c = n * float(offset);
  const Eigen::Vector3f t1 =
      (std::abs(n.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitZ())
          .cross(n)
          .normalized();
  const Eigen::Vector3f t2 = n.cross(t1);
  const float h = kPlaneHalfSize;
  MeshData m;
  const Eigen::Vector3f a = c - h * t1 - h * t2, b = c + h * t1 - h * t2, d = c + h * t1 + h * t2,
                        e = c - h * t1 + h * t2;
  // t1 x t2 = n: (a, b, d) is counter-clockwise seen from the normal's side.
  flat_triangle(m, a, b, d);
  flat_triangle(m, a, d, e);
  return m;
}

float bounding_radius(const ShapeDef& def) {
  float r = 0;
  switch (def.type) {
    case ShapeType::Sphere:
      return float(def.radius);
    case ShapeType::Box:
      return float(def.half_extents.norm());
    case ShapeType::Capsule:
      return float(def.radius + def.half_height);
    case ShapeType::Cylinder:
      return float(std::hypot(def.radius, def.half_height));
    case ShapeType::ConvexHull:
      for (const Vec3& p : def.points) r = std::max(r, float(p.norm()));
      return r;
    case ShapeType::Plane:
      return std::numeric_limits<float>::infinity();
    case ShapeType::Mesh:
      for (const Vec3& p : def.vertices) r = std::max(r, float(p.norm()));
      return r;
    case ShapeType::Heightfield: {
      float h = 0;
      for (Real v : def.heights) {
        if (!std::isnan(v)) h = std::max(h, std::abs(float(v)));  // NaN: a hole
      }
      const float rows = def.columns ? float(def.heights.size() / def.columns) : 0;
      return std::hypot(float(def.columns) * float(def.spacing_x), rows * float(def.spacing_z), h);
    }
    case ShapeType::Compound:
      for (const CompoundChild& c : def.children) {
        r = std::max(r, float(c.position.norm()) + bounding_radius(c.shape));
      }
      return r;
  }
  return r;
}

MeshKind mesh_kind(const ShapeDef& def) {
  switch (def.type) {
    case ShapeType::Sphere:
      return MeshKind::Sphere;
    case ShapeType::Box:
      return MeshKind::Box;
    case ShapeType::Cylinder:
      return MeshKind::Cylinder;
    default:
      return MeshKind::Own;
  }
}

Eigen::Vector3f instance_scale(const ShapeDef& def) {
  switch (def.type) {
    case ShapeType::Sphere:
      return Eigen::Vector3f::Constant(float(def.radius));
    case ShapeType::Box:
      return f3(def.half_extents);
    case ShapeType::Cylinder:
      return Eigen::Vector3f(float(def.radius), float(def.half_height), float(def.radius));
    default:
      return Eigen::Vector3f::Ones();
  }
}

void append(MeshData& into, const MeshData& part, const Eigen::Affine3f& pose,
            const Eigen::Vector3f& scale) {
  const uint32_t base = uint32_t(into.vertices.size());
  const Eigen::Matrix3f r = pose.linear();
  for (const MeshVertex& v : part.vertices) {
    const Eigen::Vector3f p =
        pose * Eigen::Vector3f(v.position[0], v.position[1], v.position[2]).cwiseProduct(scale);
    // Normals of a scaled surface go through the inverse scale (the inverse transpose).
    const Eigen::Vector3f n =
        (r * Eigen::Vector3f(v.normal[0], v.normal[1], v.normal[2]).cwiseQuotient(scale))
            .normalized();
    push(into, p, n);
  }
  for (uint32_t i : part.indices) into.indices.push_back(base + i);
}

bool is_curved(const ShapeDef& def) {
  switch (def.type) {
    case ShapeType::Sphere:
    case ShapeType::Capsule:
    case ShapeType::Cylinder:
      return true;
    case ShapeType::Compound:
      for (const CompoundChild& c : def.children) {
        if (is_curved(c.shape)) return true;
      }
      return false;
    default:
      return false;
  }
}

MeshData shape_mesh(const ShapeDef& def, Tessellation t) {
  const int rings = t.rings, segments = t.segments;
  switch (def.type) {
    case ShapeType::Sphere:
    case ShapeType::Box:
    case ShapeType::Cylinder: {
      const MeshData unit = def.type == ShapeType::Sphere ? unit_sphere(rings, segments)
                            : def.type == ShapeType::Box  ? unit_box()
                                                          : unit_cylinder(segments);
      MeshData m;
      append(m, unit, Eigen::Affine3f::Identity(), instance_scale(def));
      return m;
    }
    case ShapeType::Capsule:
      return capsule(float(def.radius), float(def.half_height), rings, segments);
    case ShapeType::ConvexHull:
      return convex_hull(def.points);
    case ShapeType::Plane:
      return plane_quad(def.normal, def.offset);
    case ShapeType::Mesh:
      return triangle_mesh(def.vertices, def.triangles);
    case ShapeType::Heightfield:
      return heightfield(def);
    case ShapeType::Compound: {
      MeshData m;
      for (const CompoundChild& c : def.children) {
        Eigen::Affine3f pose = Eigen::Affine3f::Identity();
        pose.translate(f3(c.position));
        pose.rotate(c.orientation.cast<float>().normalized());
        append(m, shape_mesh(c.shape, t), pose);
      }
      return m;
    }
  }
  return {};
}

}  // namespace elan::viewer
