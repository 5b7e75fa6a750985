// SPDX-License-Identifier: MIT
// SAT over face normals and Gauss-map-pruned edge pairs, then reference/incident face clipping
// (Gregorius GDC 2013/2015) or one point at the closest points of two edges. The capsule against a
// polyhedron is in capsule_polyhedron.cpp, two boxes in box_box.cpp.
#include "narrowphase/sat.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

#include "narrowphase/clip.hpp"
#include "narrowphase/edge_query.hpp"
#include "narrowphase/manifold_reduce.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase/sat_common.hpp"

namespace elan::detail {

void closest_points_segments(const Vec3& p1, const Vec3& d1, const Vec3& p2, const Vec3& d2,
                             Vec3& c1, Vec3& c2) {
  const Vec3 r = p1 - p2;
  const Real a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const Real eps = std::numeric_limits<Real>::epsilon();
  Real s = 0, t = 0;
  if (a <= eps && e <= eps) {
  } else if (a <= eps) {
    t = std::clamp(f / e, Real(0), Real(1));
  } else {
    const Real c = d1.dot(r);
    if (e <= eps) {
      s = std::clamp(-c / a, Real(0), Real(1));
    } else {
      const Real b = d1.dot(d2), denom = a * e - b * b;
      s = denom > eps * a * e ? std::clamp((b * f - c * e) / denom, Real(0), Real(1)) : Real(0);
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, Real(0), Real(1));
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, Real(0), Real(1));
      }
    }
  }
  c1 = p1 + s * d1;
  c2 = p2 + t * d2;
}

bool emit_points(const Vec3* points, const Real* separations, const uint32_t* ids, int count,
                 const Vec3& normal, Manifold& out) {
  if (count <= kMaxManifoldPoints) {
    for (int k = 0; k < count; ++k) set_point(out, k, points[k], separations[k], ids[k]);
    out.point_count = count;
  } else {
    int keep[kMaxManifoldPoints];
    const int n =
        reduce_to_four(std::span<const Vec3>(points, std::size_t(count)),
                       std::span<const Real>(separations, std::size_t(count)), normal, keep);
    for (int k = 0; k < n; ++k) {
      set_point(out, k, points[keep[k]], separations[keep[k]], ids[keep[k]]);
    }
    out.point_count = n;
  }
  return out.point_count > 0;
}

namespace {

// The least of n . x over p's vertices. perf: a box's is its centre's less the extents along n,
// three products instead of eight vertices.
Real min_projection(const Polyhedron& p, const Vec3& n) {
  if (p.is_box) {
    return n.dot(p.centre) - (std::abs(n.dot(p.half_axes[0])) + std::abs(n.dot(p.half_axes[1])) +
                              std::abs(n.dot(p.half_axes[2])));
  }
  Real m = std::numeric_limits<Real>::max();
  for (int i = 0; i < p.vertex_count; ++i) m = std::min(m, n.dot(p.vertices[i]));
  return m;
}

// Faces of `a` as axes: separation = how far b's deepest vertex is outside the face plane.
FaceQuery query_faces(const Polyhedron& a, const Polyhedron& b) {
  FaceQuery q;
  for (int f = 0; f < a.face_count; ++f) {
    const Real s = min_projection(b, a.normals[f]) - a.offsets[f];
    if (s > q.separation) {
      q.separation = s;
      q.face = f;
    }
  }
  return q;
}

// One edge pair of query_hull_edges: the arcs' crossing (crossing_arcs) and then the separation
// (candidate_separations, edge_query.cpp), the same operations in the same order, so the same bits.
Real gauss_edge_pair_separation(const Polyhedron& a, const Polyhedron& b, int ea, int eb) {
  const Vec3& na = a.normals[a.edge_faces[ea][0]];
  const Vec3& nb = a.normals[a.edge_faces[ea][1]];
  const Vec3 bxa = nb.cross(na);
  const Vec3 c = -b.normals[b.edge_faces[eb][0]];
  const Vec3 d = -b.normals[b.edge_faces[eb][1]];
  const Vec3 dxc = d.cross(c);
  const Real cba = c.x() * bxa.x() + c.y() * bxa.y() + c.z() * bxa.z();
  const Real dba = d.x() * bxa.x() + d.y() * bxa.y() + d.z() * bxa.z();
  const Real adc = na.x() * dxc.x() + na.y() * dxc.y() + na.z() * dxc.z();
  const Real bdc = nb.x() * dxc.x() + nb.y() * dxc.y() + nb.z() * dxc.z();
  if (!((cba * dba < 0) & (adc * bdc < 0) & (cba * bdc > 0))) return kLowest;
  const Vec3& pa = a.vertices[a.edges[ea][0]];
  const Vec3 ua = a.vertices[a.edges[ea][1]] - pa;
  const Vec3 oa = pa - a.centre;
  const Vec3& pb = b.vertices[b.edges[eb][0]];
  const Vec3 ub = b.vertices[b.edges[eb][1]] - pb;
  const Real va_len2 = ua.squaredNorm(), vb_len2 = ub.squaredNorm();
  Real nx = ua.y() * ub.z() - ua.z() * ub.y();
  Real ny = ua.z() * ub.x() - ua.x() * ub.z();
  Real nz = ua.x() * ub.y() - ua.y() * ub.x();
  const Real len = std::sqrt(nx * nx + (ny * ny + nz * nz));
  if (len <= kParallelSine * std::sqrt(va_len2 * vb_len2)) return kLowest;
  nx /= len;
  ny /= len;
  nz /= len;
  const Real sep = nx * (pb.x() - pa.x()) + (ny * (pb.y() - pa.y()) + nz * (pb.z() - pa.z()));
  const Real out = nx * oa.x() + (ny * oa.y() + nz * oa.z());
  return out < 0 ? -sep : sep;
}

// The edge pairs of a and b that build a face of the Minkowski difference (their Gauss-map arcs
// cross), each measured by the supports along its axis (turned away from A's centre, as the edge
// query turns it): the pair of the largest gap. The distance of two polyhedra is the largest such
// gap over their face normals and these axes. perf: every pair against both polyhedra's vertices,
// so only the fallback for an edge query whose best pair the supports contradict
// (collide_polyhedra).
EdgeQuery edge_query_by_supports(const Polyhedron& a, const Polyhedron& b) {
  EdgeQuery best;
  for (int ea = 0; ea < a.edge_count; ++ea) {
    const Vec3& pa = a.vertices[a.edges[ea][0]];
    const Vec3 ua = a.vertices[a.edges[ea][1]] - pa;
    for (int eb = 0; eb < b.edge_count; ++eb) {
      if (gauss_edge_pair_separation(a, b, ea, eb) == kLowest) continue;
      const Vec3 axis = ua.cross(b.vertices[b.edges[eb][1]] - b.vertices[b.edges[eb][0]]);
      const Real length = axis.norm();
      if (!(length > 0)) continue;
      const Vec3 n = axis.dot(pa - a.centre) < 0 ? Vec3(-axis / length) : Vec3(axis / length);
      const Real gap = min_projection(b, n) + min_projection(a, -n);
      if (gap > best.separation) best = {ea, eb, gap, n};
    }
  }
  return best;
}

// Whether the polyhedra are farther apart than `distance`, by GJK over their vertices. For the
// two separations the SAT measures along an axis where the shapes need not be closest, which
// bound their distance only from below: an edge pair whose segments' nearest points are not
// those of their lines, and the incident vertex off the reference face. Such a bound within the
// speculative distance gave a contact to shapes beyond it (docs/fuzzing.md). perf: asked only
// when no pair of points the SAT found lies within the distance, which would settle it: rare.
bool farther_than(const Polyhedron& a, const Polyhedron& b, Real distance) {
  const GjkResult g =
      gjk_point_sets(std::span<const Vec3>(a.vertices.data(), std::size_t(a.vertex_count)),
                     std::span<const Vec3>(b.vertices.data(), std::size_t(b.vertex_count)),
                     b.centre - a.centre, distance);
  return g.beyond || (!g.overlap && g.distance > distance);
}

// Clips the incident face of `inc` (the face most anti-parallel to the reference normal) against
// the side planes of `ref`'s face `rf`. `ref_is_a` orients the normal and tags the ids.
bool face_contact(const Polyhedron& ref, int rf, const Polyhedron& inc, bool ref_is_a,
                  Real speculative_distance, Manifold& out) {
  const Vec3 n = ref.normals[rf];
  int inf = 0;
  Real most = std::numeric_limits<Real>::max();
  for (int f = 0; f < inc.face_count; ++f) {
    const Real d = inc.normals[f].dot(n);
    if (d < most) {
      most = d;
      inf = f;
    }
  }
  ClipPolygon poly[2];
  {
    const uint32_t first = inc.face_first[inf], cnt = inc.face_count_of[inf];
    const int m = int(std::min<uint32_t>(cnt, kMaxClipVertices / 2));
    for (int k = 0; k < m; ++k) {
      poly[0].points[k] = inc.vertices[inc.face_vertices[first + k]];
      poly[0].out_label[k] = uint8_t(k & 63);
    }
    poly[0].count = m;
  }
  int cur = 0;
  const uint32_t rfirst = ref.face_first[rf], rcnt = ref.face_count_of[rf];
  for (uint32_t k = 0; k < rcnt && poly[cur].count > 0; ++k) {
    const Vec3& v0 = ref.vertices[ref.face_vertices[rfirst + k]];
    const Vec3& v1 = ref.vertices[ref.face_vertices[rfirst + (k + 1) % rcnt]];
    // Loop is counter-clockwise seen along -n, so (v1 - v0) x n points out of the face.
    clip_polygon(poly[cur], (v1 - v0).cross(n), v0, uint8_t(kSidePlaneLabel + (k & 63)),
                 poly[1 - cur]);
    cur = 1 - cur;
  }
  const ClipPolygon& clipped = poly[cur];
  const Vec3 normal = ref_is_a ? n : Vec3(-n);
  out.normal = normal;
  const uint32_t base = (ref_is_a ? kFeatureFaceA : kFeatureFaceB) | ((uint32_t(rf) & 0xFF) << 22) |
                        ((uint32_t(inf) & 0xFF) << 14);
  const Real offset = ref.offsets[rf];

  Vec3 points[kMaxClipVertices];
  Real seps[kMaxClipVertices];
  uint32_t ids[kMaxClipVertices];
  int count = 0;
  for (int k = 0; k < clipped.count; ++k) {
    const Vec3& p = clipped.points[k];
    const Real s = n.dot(p) - offset;
    if (s > speculative_distance) continue;
    points[count] = p - (Real(0.5) * s) * n;
    seps[count] = s;
    ids[count] = base | clip_vertex_id(clipped, k);
    ++count;
  }
  if (count == 0) {
    // No clipped point within the speculative distance. Either the faces do not overlap sideways
    // (separated shapes, or round-off): keep the incident polyhedron's deepest vertex so that a
    // speculative contact still exists. Or the clipped face lies beyond that distance while the
    // deepest vertex, off it, is below the reference face: the shapes overlap (every axis's
    // separation is at most the face's, below zero), so that vertex is a contact: a hull whose
    // most anti-parallel face does not hold its deepest vertex (docs/fuzzing.md).
    int best = 0;
    Real bs = std::numeric_limits<Real>::max();
    for (int i = 0; i < inc.vertex_count; ++i) {
      const Real s = n.dot(inc.vertices[i]);
      if (s < bs) {
        bs = s;
        best = i;
      }
    }
    const Real s = bs - offset;
    if (s > speculative_distance || (clipped.count > 0 && !(s < 0))) return false;
    // A vertex whose foot is on the face is s from it; off the face, s only bounds the distance.
    const Vec3& deepest = inc.vertices[best];
    if (s > 0 && !foot_on_face(ref.vertices, ref.face_vertices + rfirst, rcnt, n, deepest) &&
        (ref_is_a ? farther_than(ref, inc, speculative_distance)
                  : farther_than(inc, ref, speculative_distance))) {
      return false;
    }
    points[0] = inc.vertices[best] - (Real(0.5) * s) * n;
    seps[0] = s;
    ids[0] = base | 0x3FFFu;
    count = 1;
  }
  return emit_points(points, seps, ids, count, normal, out);
}

}  // namespace

bool collide_polyhedra(const Polyhedron& a, const Polyhedron& b, Real speculative_distance,
                       Manifold& out, Separation* separation) {
  out.point_count = 0;
  const FaceQuery fa = query_faces(a, b);
  if (fa.separation > speculative_distance) {
    report_separation(separation, Separation::Kind::FaceOfA, fa.separation);
    return false;
  }
  const FaceQuery fb = query_faces(b, a);
  if (fb.separation > speculative_distance) {
    report_separation(separation, Separation::Kind::FaceOfB, fb.separation);
    return false;
  }
  EdgeQuery ee = query_hull_edges(a, b);
  if (ee.separation > speculative_distance) {
    // Checked by the supports along the pair's own axis before it is believed: a hull's edges
    // once gave an axis whose gap, measured from the two edges, was 1.29 m for shapes 0.34 m into
    // each other (found by fuzz_narrowphase). An axis along which the shapes' extents overlap
    // separates nothing; the faces then decide. The gap along n, from A towards B, is
    // min over B of n.x - max over A of n.x.
    const Real gap = min_projection(b, ee.normal) + min_projection(a, -ee.normal);
    if (gap > speculative_distance) {
      if (separation != nullptr) {
        *separation = {Separation::Kind::EdgePair, ee.separation, ee.edge_a, ee.edge_b};
      }
      return false;
    }
    // The best pair's gap was wrong, and so may its rank have been: another pair, whose gap the
    // query measured smaller, may be the one that separates the shapes (found by
    // fuzz_narrowphase: docs/fuzzing.md). Every pair is measured again by the supports. A
    // rejection on it reports no separation, which the separation cache could not re-check from
    // the two edges.
    ee = edge_query_by_supports(a, b);
    if (ee.separation > speculative_distance) return false;
  }

  // Non-finite input (a pose far past the supported range overflows) compares false everywhere,
  // so no face is picked: no contact, rather than reading face -1.
  if (fa.face < 0 || fb.face < 0) return false;
  const bool use_b = beats(fb.separation, fa.separation, kFaceRelTol);
  const Real face_sep = use_b ? fb.separation : fa.separation;
  if (ee.edge_a >= 0 && beats(ee.separation, face_sep, kEdgeRelTol)) {
    const Vec3& pa = a.vertices[a.edges[ee.edge_a][0]];
    const Vec3& pb = b.vertices[b.edges[ee.edge_b][0]];
    Vec3 ca, cb;
    closest_points_segments(pa, a.vertices[a.edges[ee.edge_a][1]] - pa, pb,
                            b.vertices[b.edges[ee.edge_b][1]] - pb, ca, cb);
    // The shapes are no farther apart than ca and cb. When those are beyond the speculative
    // distance, the segments' nearest points are not their lines' and the separation, within
    // it, only bounds the distance from below.
    if (ee.separation > 0 &&
        (cb - ca).squaredNorm() > speculative_distance * speculative_distance &&
        farther_than(a, b, speculative_distance)) {
      return false;
    }
    out.normal = ee.normal;
    set_point(
        out, 0, Real(0.5) * (ca + cb), ee.separation,
        kFeatureEdges | ((uint32_t(ee.edge_a) & 0x7FFF) << 15) | (uint32_t(ee.edge_b) & 0x7FFF));
    out.point_count = 1;
    return true;
  }
  if (use_b) return face_contact(b, fb.face, a, false, speculative_distance, out);
  return face_contact(a, fa.face, b, true, speculative_distance, out);
}

Real edge_pair_separation(const Polyhedron& a, const Polyhedron& b, int edge_a, int edge_b) {
  if (edge_a < 0 || edge_a >= a.edge_count || edge_b < 0 || edge_b >= b.edge_count) return kLowest;
  return gauss_edge_pair_separation(a, b, edge_a, edge_b);
}

}  // namespace elan::detail
