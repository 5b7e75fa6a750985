// SPDX-License-Identifier: MIT
// SAT over face normals and Gauss-map-pruned edge pairs, then reference/incident face clipping
// (Gregorius GDC 2013/2015) or one point at the closest points of two edges. The capsule against a
// polyhedron is in capsule_polyhedron.cpp.
#include "narrowphase/sat.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>

#include "narrowphase/clip.hpp"
#include "narrowphase/edge_query.hpp"
#include "narrowphase/manifold_reduce.hpp"
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

// Faces of box `a` against box `b`, as query_faces. A box's faces come in opposite pairs,
// normals[2k + 1] = -normals[2k], and b's least projection along -n is -(n.c) less the same
// extents: negation is exact, so one set of products gives both faces' separations, the same bits
// as min_projection's.
FaceQuery query_box_faces(const Polyhedron& a, const Polyhedron& b) {
  FaceQuery q;
  for (int k = 0; k < 3; ++k) {
    const Vec3& n = a.normals[2 * k];
    const Real centre = n.dot(b.centre);
    const Real extents = std::abs(n.dot(b.half_axes[0])) + std::abs(n.dot(b.half_axes[1])) +
                         std::abs(n.dot(b.half_axes[2]));
    const Real s[2] = {(centre - extents) - a.offsets[2 * k],
                       (-centre - extents) - a.offsets[2 * k + 1]};
    for (int side = 0; side < 2; ++side) {
      if (s[side] > q.separation) {
        q.separation = s[side];
        q.face = 2 * k + side;
      }
    }
  }
  return q;
}

// Faces of `a` as axes: separation = how far b's deepest vertex is outside the face plane.
FaceQuery query_faces(const Polyhedron& a, const Polyhedron& b) {
  if (a.is_box && b.is_box) return query_box_faces(a, b);
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

// The edge of box p along direction i (0, 1, 2: edges 0-3, 4-7, 8-11 of the unit box) that is
// extreme along d: the other two directions' signs pick it.
int extreme_box_edge(const Polyhedron& p, int i, const Vec3& d) {
  const int j = (i + 1) % 3, k = (i + 2) % 3;
  const int bit_j = d.dot(p.half_axes[j]) > 0 ? 1 : 0;
  const int bit_k = d.dot(p.half_axes[k]) > 0 ? 1 : 0;
  // Within a direction's four edges the lower of the other two axes is the low bit.
  return 4 * i + (j < k ? bit_j + 2 * bit_k : bit_k + 2 * bit_j);
}

// The separation of boxes a and b along A's edge direction i x B's direction j, oriented from A
// to B (`d`), or the lowest Real when the two are nearly parallel.
Real box_edge_axis_separation(const Polyhedron& a, const Polyhedron& b, int i, int j, Vec3& d) {
  const Vec3 t = b.centre - a.centre;
  const Vec3& ua = a.normals[2 * i];  // unit: the box's +x, +y, +z face normals
  d = ua.cross(b.normals[2 * j]);
  const Real len = d.norm();
  if (len <= kParallelSine) return kLowest;
  d /= len;
  if (t.dot(d) < 0) d = -d;
  const Real extents = std::abs(d.dot(a.half_axes[0])) + std::abs(d.dot(a.half_axes[1])) +
                       std::abs(d.dot(a.half_axes[2])) + std::abs(d.dot(b.half_axes[0])) +
                       std::abs(d.dot(b.half_axes[1])) + std::abs(d.dot(b.half_axes[2]));
  return t.dot(d) - extents;
}

// The slack of box_edge_axes_above's bound, per metre of the pair's size (|T| and the half
// extents): the bound and box_edge_axis_separation compute one value by two formulas, each in a
// few dozen roundings of terms no larger than that size, divided by the axis's length; 1e-5 is
// about 84 float epsilons.
constexpr Real kEdgeBoundSlack = Real(1e-5);

// The nine direction pairs (i, j) of two boxes whose separation may exceed `threshold`, as bit
// 3 i + j. Gottschalk's OBB test in A's frame (Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH
// 1996): with R = A^T B and T = A^T (B's centre - A's), the axis L = a_i x b_j has
// T.L = T[i2] R[i1][j] - T[i1] R[i2][j], extents ea[i1] |R[i2][j]| + ea[i2] |R[i1][j]| and
// eb[j1] |R[i][j2]| + eb[j2] |R[i][j1]|, and length sqrt(R[i1][j]^2 + R[i2][j]^2) (i1, i2: the
// other two of A's directions, j1, j2 of B's). The separation is (|T.L| - extents) / |L|; a pair
// is left out when that, plus the slack over both formulas' rounding, is at most the threshold.
// perf: the nine dot products of R and three of T are shared by all nine axes, instead of a cross
// product, a norm and seven dot products per axis.
uint32_t box_edge_axes_above(const Polyhedron& a, const Polyhedron& b, Real threshold) {
  const Vec3 t = b.centre - a.centre;
  Real r[3][3], ta[3];
  for (int i = 0; i < 3; ++i) {
    ta[i] = t.dot(a.normals[2 * i]);
    for (int j = 0; j < 3; ++j) r[i][j] = a.normals[2 * i].dot(b.normals[2 * j]);
  }
  const Vec3& ea = a.half_extents;
  const Vec3& eb = b.half_extents;
  const Real scale = std::abs(ta[0]) + std::abs(ta[1]) + std::abs(ta[2]) + ea.sum() + eb.sum();
  const Real slack = kEdgeBoundSlack * scale;
  uint32_t axes = 0;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const Real centres = std::abs(ta[i2] * r[i1][j] - ta[i1] * r[i2][j]);
      const Real extents = ea[i1] * std::abs(r[i2][j]) + ea[i2] * std::abs(r[i1][j]) +
                           eb[j1] * std::abs(r[i][j2]) + eb[j2] * std::abs(r[i][j1]);
      const Real len = std::sqrt(r[i1][j] * r[i1][j] + r[i2][j] * r[i2][j]);
      // Non-finite input compares false: the axis is kept and the exact test decides, as before.
      const bool below = centres - extents + slack <= threshold * len;
      axes |= uint32_t(!below) << (3 * i + j);
    }
  }
  return axes;
}

// Two boxes: each has edges along three directions only, so the edge-edge faces of A - B are the
// nine direction pairs, each facing both ways. Along the unit d = ua x ub oriented from A to B
// the separation is T.d - ra - rb (T: B's centre from A's; ra, rb: the boxes' extents along d;
// Gottschalk's OBB test), the value the Gauss-map query finds for the two edges extreme along d
// and -d. perf: nine axes instead of the 144 edge pairs.
//
// Only the direction pairs in `axes` (bit 3 i + j) are measured. When the first largest of all
// nine exceeds a threshold it is among those box_edge_axes_above keeps for that threshold (an
// axis left out is at most the threshold, so it can neither beat nor tie it): the same query,
// bit for bit. Otherwise the result is at most the threshold, or empty.
EdgeQuery query_box_edges(const Polyhedron& a, const Polyhedron& b, uint32_t axes) {
  EdgeQuery q;
  for (; axes != 0; axes &= axes - 1) {
    const int k = std::countr_zero(axes);
    const int i = k / 3, j = k % 3;
    Vec3 d;
    const Real separation = box_edge_axis_separation(a, b, i, j, d);
    if (separation > q.separation) {
      q.separation = separation;
      q.normal = d;
      q.edge_a = extreme_box_edge(a, i, d);
      q.edge_b = extreme_box_edge(b, j, Vec3(-d));
    }
  }
  return q;
}

// The deepest edge axis when it exceeds `threshold` (kLowest: always): the nine direction pairs
// of two boxes (those that may exceed it), else the Gauss-map query of edge_query.hpp (its
// path's kernel). Below the threshold the result may be any axis at most the threshold, or none.
EdgeQuery query_edges(const Polyhedron& a, const Polyhedron& b, Real threshold) {
  if (a.is_box && b.is_box) return query_box_edges_above(a, b, threshold);
  return query_hull_edges(a, b);
}

// One edge pair of query_edges: the arcs' crossing (crossing_arcs) and then the separation
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
  if (count == 0 && clipped.count == 0) {
    // The faces do not overlap sideways (separated shapes, or round-off): keep the incident
    // polyhedron's deepest vertex so a speculative contact still exists.
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
    if (s > speculative_distance) return false;
    points[0] = inc.vertices[best] - (Real(0.5) * s) * n;
    seps[0] = s;
    ids[0] = base | 0x3FFFu;
    count = 1;
  }
  return emit_points(points, seps, ids, count, normal, out);
}

}  // namespace

EdgeQuery query_box_edges_above(const Polyhedron& a, const Polyhedron& b, Real threshold) {
  constexpr uint32_t kAllNine = 0x1FF;
  return query_box_edges(a, b,
                         threshold == kLowest ? kAllNine : box_edge_axes_above(a, b, threshold));
}

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
  // The edge query decides the outcome only when its separation exceeds the speculative distance
  // (a rejection) or beats the face the contact would take (an edge contact); an axis at most both
  // changes nothing, so the box query measures only the axes that may exceed them. Non-finite
  // faces (below) take every axis, as before.
  Real edge_threshold = kLowest;
  if (fa.face >= 0 && fb.face >= 0) {
    const Real face =
        beats(fb.separation, fa.separation, kFaceRelTol) ? fb.separation : fa.separation;
    edge_threshold = std::min(speculative_distance, face + kEdgeRelTol * std::abs(face) + kAbsTol);
  }
  EdgeQuery ee = query_edges(a, b, edge_threshold);
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
    ee = EdgeQuery{};
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
  if (a.is_box && b.is_box) {
    Vec3 d;
    return box_edge_axis_separation(a, b, edge_a / 4, edge_b / 4, d);
  }
  return gauss_edge_pair_separation(a, b, edge_a, edge_b);
}

}  // namespace elan::detail
