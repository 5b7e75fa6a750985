// SPDX-License-Identifier: MIT
// collide_segment_polyhedron() and its parts: a capsule against a polyhedron (see
// capsule_polyhedron.hpp).
#include "narrowphase/capsule_polyhedron.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "narrowphase/sat_common.hpp"

namespace elan::detail {

namespace {

// A separated capsule whose closest-point normal is within ~2.5 degrees of a face normal lies
// on that face: clip its segment to the face for two points instead of one.
constexpr Real kFaceAlignCos = Real(0.999);

// Capsule core (segment) against face f of b: the segment clipped to the face's side planes,
// one point per surviving end (Box2D-style capsule manifold).
bool segment_face_contact(const Vec3& s0, const Vec3& s1, Real radius, const Polyhedron& b, int f,
                          Real speculative_distance, Manifold& out) {
  const Vec3 u = s1 - s0;
  // Clip the segment's parameter range against the face's side planes; remember which plane
  // cut each end for the feature ids.
  const Vec3& n = b.normals[f];
  Real t0 = 0, t1 = 1;
  uint32_t l0 = 0, l1 = 1;
  const uint32_t first = b.face_first[f], cnt = b.face_count_of[f];
  for (uint32_t k = 0; k < cnt && t0 <= t1; ++k) {
    const Vec3& v0 = b.vertices[b.face_vertices[first + k]];
    const Vec3& v1 = b.vertices[b.face_vertices[first + (k + 1) % cnt]];
    const Vec3 side = (v1 - v0).cross(n);
    const Real d0 = side.dot(s0 - v0), du = side.dot(u);
    if (std::abs(du) <= std::numeric_limits<Real>::epsilon() * std::abs(d0)) {
      if (d0 > 0) t0 = Real(2);
      continue;
    }
    const Real t = -d0 / du;
    if (du > 0) {
      if (t < t1) {
        t1 = t;
        l1 = 2 + k;
      }
    } else if (t > t0) {
      t0 = t;
      l0 = 2 + k;
    }
  }
  const Vec3 normal = -n;
  out.normal = normal;
  const uint32_t base = kFeatureSegment | ((uint32_t(f) & 0xFFFF) << 12);
  Vec3 points[2];
  Real seps[2];
  uint32_t ids[2];
  int count = 0;
  if (t0 > t1) {
    // The segment misses the face sideways: one point at the deeper end.
    const bool first_deeper = n.dot(s0) <= n.dot(s1);
    t0 = t1 = first_deeper ? Real(0) : Real(1);
    l0 = l1 = first_deeper ? 0u : 1u;
  }
  const Real ts[2] = {t0, t1};
  const uint32_t ls[2] = {l0, l1};
  for (int k = 0; k < (t0 == t1 ? 1 : 2); ++k) {
    const Vec3 p = s0 + ts[k] * u;
    const Real depth_plane = n.dot(p) - b.offsets[f];
    const Real s = depth_plane - radius;
    if (s > speculative_distance) continue;
    // Midpoint between the capsule surface point (p - radius n) and the face point.
    points[count] = p - (Real(0.5) * (depth_plane + radius)) * n;
    seps[count] = s;
    ids[count] = base | (ls[k] & 0xFFF);
    ++count;
  }
  return emit_points(points, seps, ids, count, normal, out);
}

}  // namespace

SegmentFaceQuery query_segment_faces(const Vec3& s0, const Vec3& s1, const Polyhedron& b) {
  SegmentFaceQuery q;
  for (int f = 0; f < b.face_count; ++f) {
    const Vec3& n = b.normals[f];
    const Real h0 = n.dot(s0), h1 = n.dot(s1);
    const Real s = std::min(h0, h1) - b.offsets[f];
    if (s > q.separation) {
      q.separation = s;
      q.face = f;
      q.nearest = h0 <= h1 ? s0 : s1;
    }
  }
  if (q.face >= 0) {
    q.foot_on_face = foot_on_face(b.vertices, b.face_vertices + b.face_first[q.face],
                                  b.face_count_of[q.face], b.normals[q.face], q.nearest);
  }
  return q;
}

bool collide_segment_polyhedron(const Vec3& s0, const Vec3& s1, Real radius, const Polyhedron& b,
                                Real speculative_distance, Manifold& out) {
  out.point_count = 0;
  const Vec3 u = s1 - s0;
  const SegmentFaceQuery sq = query_segment_faces(s0, s1, b);
  FaceQuery fq;
  fq.face = sq.face;
  fq.separation = sq.separation - radius;
  if (fq.separation > speculative_distance) return false;

  // The segment's Gauss map is the great circle normal to u; it crosses the arc of B's edge
  // (between the outward normals c and d) when they lie on opposite sides of it.
  EdgeQuery eq;
  const Real u_len2 = u.squaredNorm();
  for (int e = 0; e < b.edge_count; ++e) {
    const Vec3& c = b.normals[b.edge_faces[e][0]];
    const Vec3& d = b.normals[b.edge_faces[e][1]];
    if (c.dot(u) * d.dot(u) >= 0) continue;
    const Vec3& pb = b.vertices[b.edges[e][0]];
    const Vec3 ub = b.vertices[b.edges[e][1]] - pb;
    Vec3 axis = u.cross(ub);
    const Real len = axis.norm();
    if (len <= kParallelSine * std::sqrt(u_len2 * ub.squaredNorm())) continue;
    axis /= len;
    if (axis.dot(pb - b.centre) < 0) axis = -axis;  // out of B at its edge
    const Real s = axis.dot(s0 - pb) - radius;
    if (s > eq.separation) {
      eq.separation = s;
      eq.edge_a = e;
      eq.normal = -axis;
    }
  }
  if (eq.separation > speculative_distance) return false;

  if (eq.edge_a >= 0 && beats(eq.separation, fq.separation, kEdgeRelTol)) {
    const Vec3& pb = b.vertices[b.edges[eq.edge_a][0]];
    Vec3 ca, cb;
    closest_points_segments(s0, u, pb, b.vertices[b.edges[eq.edge_a][1]] - pb, ca, cb);
    out.normal = eq.normal;
    // Midpoint between the capsule surface (ca + radius n) and the edge point.
    set_point(out, 0, Real(0.5) * (ca + eq.normal * radius + cb), eq.separation,
              kFeatureSegment | (1u << 29) | (uint32_t(eq.edge_a) & 0xFFFF));
    out.point_count = 1;
    return true;
  }

  // Non-finite input compares false everywhere and picks no face: no contact, not face -1.
  if (fq.face < 0) return false;
  return segment_face_contact(s0, s1, radius, b, fq.face, speculative_distance, out);
}

bool collide_segment_polyhedron_separated(const Vec3& s0, const Vec3& s1, Real radius,
                                          const Polyhedron& b, const Vec3& normal,
                                          const Vec3& point_a, const Vec3& point_b,
                                          Real speculative_distance, Manifold& out) {
  out.point_count = 0;
  int face = 0;
  Real most = std::numeric_limits<Real>::max();
  for (int f = 0; f < b.face_count; ++f) {
    const Real d = b.normals[f].dot(normal);
    if (d < most) {
      most = d;
      face = f;
    }
  }
  if (-most >= kFaceAlignCos) {
    return segment_face_contact(s0, s1, radius, b, face, speculative_distance, out);
  }
  const Real sep = normal.dot(point_b - point_a) - radius;
  if (sep > speculative_distance) return false;
  out.normal = normal;
  set_point(out, 0, Real(0.5) * (point_a + normal * radius + point_b), sep,
            kFeatureSegment | (1u << 28) | (uint32_t(face) & 0xFFFF));
  out.point_count = 1;
  return true;
}

}  // namespace elan::detail
