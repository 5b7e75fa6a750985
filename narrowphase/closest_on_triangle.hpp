// SPDX-License-Identifier: MIT
// The closest point of a triangle to the origin, with its feature and barycentric weights
// (Ericson, Real-Time Collision Detection 5.1.5, the query point at the origin), by Voronoi
// regions, which stay right on a sliver where signed areas round wrong. A template over the
// vector type: the triangle contact works in Real, GJK's fallback for slivers in double.
#pragma once

#include <cstdint>

namespace elan::detail {

// The triangle's features: its face, vertex k, or edge k (v[k] to v[k + 1]).
inline constexpr uint32_t kTriangleFace = 0;
inline constexpr uint32_t kTriangleVertex = 1;  // + k
inline constexpr uint32_t kTriangleEdge = 4;    // + k

template <class V>
struct TriangleClosest {
  V point;
  typename V::Scalar weight[3];  // of a, b, c: point = sum weight[k] corner[k]
  uint32_t region;
};

template <class V>
[[gnu::always_inline]] inline TriangleClosest<V> closest_on_triangle_to_origin(const V& a,
                                                                               const V& b,
                                                                               const V& c) {
  using S = typename V::Scalar;
  const auto done = [](const V& p, S wa, S wb, S wc, uint32_t region) {
    return TriangleClosest<V>{p, {wa, wb, wc}, region};
  };
  const V ab = b - a, ac = c - a, ap = -a;
  const S d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return done(a, 1, 0, 0, kTriangleVertex + 0);
  const V bp = -b;
  const S d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return done(b, 0, 1, 0, kTriangleVertex + 1);
  const S vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const S t = d1 / (d1 - d3);
    return done(a + ab * t, 1 - t, t, 0, kTriangleEdge + 0);
  }
  const V cp = -c;
  const S d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return done(c, 0, 0, 1, kTriangleVertex + 2);
  const S vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const S t = d2 / (d2 - d6);
    return done(a + ac * t, 1 - t, 0, t, kTriangleEdge + 2);  // c to a
  }
  const S va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const S t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return done(b + (c - b) * t, 0, 1 - t, t, kTriangleEdge + 1);
  }
  const S denom = S(1) / (va + vb + vc);
  const S v = vb * denom, w = vc * denom;
  return done(a + ab * v + ac * w, 1 - v - w, v, w, kTriangleFace);
}

}  // namespace elan::detail
