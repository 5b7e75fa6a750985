// SPDX-License-Identifier: MIT
// Exact reference geometry (in double) for the GJK/EPA tests: point-triangle and segment-segment
// distances, and the distance / penetration depth of two convex polytopes from their features.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/base/shape.hpp"

namespace elan::detail::oracle {

using V3 = Eigen::Vector3d;

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5).
inline V3 closest_on_triangle(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const V3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const V3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double den = 1 / (va + vb + vc);
  return a + ab * (vb * den) + ac * (vc * den);
}

// Distance between segments p1q1 and p2q2 (Ericson 5.1.9).
inline double segment_distance(const V3& p1, const V3& q1, const V3& p2, const V3& q2) {
  const V3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.dot(d1), e = d2.dot(d2), f = d2.dot(r);
  const double c = d1.dot(r), b = d1.dot(d2), den = a * e - b * b;
  double s = den > 0 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) {
    t = 0, s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return ((p1 + d1 * s) - (p2 + d2 * t)).norm();
}

// A hull placed in the world: vertices, fan-triangulated faces, face planes, edges.
struct Poly {
  std::vector<V3> v;
  std::vector<std::array<int, 3>> tris;
  std::vector<V3> normals;
  std::vector<std::array<int, 2>> edges;
};

inline Poly place_hull(const Shape& s, const Transform& x) {
  Poly p;
  const Eigen::Matrix3d r = x.rotation.toRotationMatrix().cast<double>();
  const V3 t = x.position.cast<double>();
  for (const Vec3& v : s.hull->vertices) p.v.push_back(r * v.cast<double>() + t);
  for (const HullFace& f : s.hull->faces) {
    p.normals.push_back(r * f.normal.cast<double>());
    const uint32_t* loop = &s.hull->face_vertices[f.first];
    for (uint32_t k = 1; k + 1 < f.count; ++k) {
      p.tris.push_back({int(loop[0]), int(loop[k]), int(loop[k + 1])});
    }
  }
  for (const auto& e : s.hull->edges) p.edges.push_back({int(e[0]), int(e[1])});
  return p;
}

// A box of half extents h placed in the world: its 8 corners (bit k of the index: + or - along
// axis k), each face as two triangles with its normal, its 12 edges.
inline Poly place_box(const Vec3& h, const Transform& x) {
  Poly p;
  const Eigen::Matrix3d r = x.rotation.toRotationMatrix().cast<double>();
  const V3 t = x.position.cast<double>();
  const V3 hd = h.cast<double>();
  for (int k = 0; k < 8; ++k) {
    const V3 c((k & 1) ? hd.x() : -hd.x(), (k & 2) ? hd.y() : -hd.y(), (k & 4) ? hd.z() : -hd.z());
    p.v.push_back(r * c + t);
  }
  // Each face: the axis, the side, and its corners in a loop (bit `axis` fixed).
  for (int axis = 0; axis < 3; ++axis) {
    const int u = 1 << ((axis + 1) % 3), w = 1 << ((axis + 2) % 3), a = 1 << axis;
    for (int side = 0; side < 2; ++side) {
      const int base = side ? a : 0;
      const int loop[4] = {base, base | u, base | u | w, base | w};
      p.tris.push_back({loop[0], loop[1], loop[2]});
      p.tris.push_back({loop[0], loop[2], loop[3]});
      p.normals.push_back(r.col(axis) * (side ? 1.0 : -1.0));
    }
    for (int k = 0; k < 8; ++k) {
      if (!(k & a)) p.edges.push_back({k, k | a});
    }
  }
  return p;
}

inline std::pair<double, double> project(const Poly& p, const V3& axis) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const V3& v : p.v) lo = std::min(lo, v.dot(axis)), hi = std::max(hi, v.dot(axis));
  return {lo, hi};
}

// Penetration depth by SAT: the minimum overlap over face normals of both and cross products of
// edge pairs (exact for polytopes); <= 0 means a separating axis exists.
inline double sat_depth(const Poly& a, const Poly& b) {
  double best = std::numeric_limits<double>::infinity();
  auto test = [&](V3 axis) {
    const double len = axis.norm();
    if (len < 1e-9) return;
    axis /= len;
    const auto [alo, ahi] = project(a, axis);
    const auto [blo, bhi] = project(b, axis);
    best = std::min(best, std::min(ahi - blo, bhi - alo));
  };
  for (const V3& n : a.normals) test(n);
  for (const V3& n : b.normals) test(n);
  for (const auto& ea : a.edges) {
    for (const auto& eb : b.edges) test((a.v[ea[1]] - a.v[ea[0]]).cross(b.v[eb[1]] - b.v[eb[0]]));
  }
  return best;
}

// Exact distance of disjoint polytopes: the closest pair is vertex-face, face-vertex or
// edge-edge, so the minimum over those feature pairs is the distance.
inline double polytope_distance(const Poly& a, const Poly& b) {
  double best = std::numeric_limits<double>::infinity();
  auto vertex_faces = [&best](const Poly& p, const Poly& q) {
    for (const V3& v : p.v) {
      for (const auto& t : q.tris) {
        best = std::min(best, (v - closest_on_triangle(v, q.v[t[0]], q.v[t[1]], q.v[t[2]])).norm());
      }
    }
  };
  vertex_faces(a, b);
  vertex_faces(b, a);
  for (const auto& ea : a.edges) {
    for (const auto& eb : b.edges) {
      best = std::min(best, segment_distance(a.v[ea[0]], a.v[ea[1]], b.v[eb[0]], b.v[eb[1]]));
    }
  }
  return best;
}

// Exact distance of the convex hulls of two point sets, whatever faces a hull builder made of
// them (merged faces a rounding off their planes): the closest pair lies on a point and a
// triangle of three points, or on two segments of two points each, and every such triangle and
// segment lies in its hull. O(n^4): for the fuzz target's hulls of at most 12 points, boxes
// and single points (a sphere's centre). A degenerate triangle's NaN is passed over by min.
inline double point_set_distance(const std::vector<V3>& a, const std::vector<V3>& b) {
  double best = std::numeric_limits<double>::infinity();
  auto point_triangles = [&best](const std::vector<V3>& p, const std::vector<V3>& q) {
    for (const V3& v : p) {
      best = std::min(best, (v - q[0]).norm());
      for (std::size_t i = 0; i < q.size(); ++i) {
        for (std::size_t j = i + 1; j < q.size(); ++j) {
          for (std::size_t k = j + 1; k < q.size(); ++k) {
            best = std::min(best, (v - closest_on_triangle(v, q[i], q[j], q[k])).norm());
          }
        }
      }
    }
  };
  point_triangles(a, b);
  point_triangles(b, a);
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = i + 1; j < a.size(); ++j) {
      for (std::size_t k = 0; k < b.size(); ++k) {
        for (std::size_t l = k + 1; l < b.size(); ++l) {
          best = std::min(best, segment_distance(a[i], a[j], b[k], b[l]));
        }
      }
    }
  }
  return best;
}

inline Shape random_hull(std::mt19937& rng, int n, double scale) {
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0.3, 1.0);
  ShapeDef d;
  d.type = ShapeType::ConvexHull;
  const V3 stretch{u(rng), u(rng), u(rng)};
  for (int i = 0; i < n; ++i) {
    V3 p{g(rng), g(rng), g(rng)};
    p = p.normalized() * (scale * u(rng));
    d.points.push_back(p.cwiseProduct(stretch).cast<Real>());
  }
  return make_shape(d);
}

inline Quat random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0, 1);
  Eigen::Quaterniond q{g(rng), g(rng), g(rng), g(rng)};
  q.normalize();
  return q.cast<Real>();
}

}  // namespace elan::detail::oracle
