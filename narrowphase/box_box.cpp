// SPDX-License-Identifier: MIT
// Box-box contact (box_box.hpp). The 15 axes from one rotation between the boxes, in A's frame
// (Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996); the contact by the polyhedron SAT's rules
// (sat.cpp: its hysteresis between axes, reference/incident face clipping after Gregorius, GDC
// 2015, and its feature ids), with the reference face's side planes those of a box in its own
// frame, each one coordinate against a half extent.
// perf: no polyhedra are built. The faces take three products a box instead of a rotated box's
// corners, the edges nine axes from the rotation's entries, and the clipping one coordinate a
// plane instead of a dot product.
#include "narrowphase/box_box.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "narrowphase/box_topology.hpp"
#include "narrowphase/clip.hpp"
#include "narrowphase/sat.hpp"
#include "narrowphase/sat_common.hpp"

namespace elan::detail {
namespace {

// One box placed in another's frame: column j of r is its axis j, t its centre.
struct BoxPlacement {
  Real r[3][3];
  Real t[3];
};

// B in A's frame: R = A^T B and T = A^T (B's centre - A's), from the relative rotation.
BoxPlacement place_b_in_a(const Transform& xa, const Transform& xb) {
  const Quat to_a = xa.rotation.conjugate();
  const Mat3 r = (to_a * xb.rotation).toRotationMatrix();
  const Vec3 t = to_a * (xb.position - xa.position);
  BoxPlacement p;
  for (int i = 0; i < 3; ++i) {
    p.t[i] = t[i];
    for (int j = 0; j < 3; ++j) p.r[i][j] = r(i, j);
  }
  return p;
}

// The separation of the boxes along L = a_i x b_j, oriented from A to B, or the lowest Real when
// the two directions are nearly parallel; `along` is T.L, whose sign orients L. In A's frame
// L[i] = 0, L[i1] = -R[i2][j] and L[i2] = R[i1][j] (i1, i2 and j1, j2: the other two axes in
// cyclic order); A's extent along it is ea[i1] |L[i1]| + ea[i2] |L[i2]|, and B's, as
// L.b_j1 = R[i][j2] and L.b_j2 = -R[i][j1], eb[j1] |R[i][j2]| + eb[j2] |R[i][j1]|.
inline Real edge_axis_separation(const BoxPlacement& p, const Vec3& ea, const Vec3& eb, int i,
                                 int j, Real& along) {
  const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
  const Real l1 = -p.r[i2][j], l2 = p.r[i1][j];
  const Real len = std::sqrt(l1 * l1 + l2 * l2);
  along = p.t[i1] * l1 + p.t[i2] * l2;
  if (len <= kParallelSine) return kLowest;
  const Real extents = (ea[i1] * std::abs(l1) + ea[i2] * std::abs(l2)) +
                       (eb[j1] * std::abs(p.r[i][j2]) + eb[j2] * std::abs(p.r[i][j1]));
  return (std::abs(along) - extents) / len;
}

struct EdgeAxis {
  int i = -1, j = -1;  // A's direction, B's
  Real separation = kLowest;
  Real along = 0;
};

// The axis of `e` (unit, A's frame, from A to B) and the two edges extreme along it: A's along
// it, B's against it, numbered as box_topology.hpp does.
void box_edge_features(const BoxPlacement& p, const EdgeAxis& e, Vec3& d, int& edge_a,
                       int& edge_b) {
  const int i1 = (e.i + 1) % 3, i2 = (e.i + 2) % 3;
  d = Vec3::Zero();
  d[i1] = -p.r[i2][e.j];
  d[i2] = p.r[i1][e.j];
  d /= d.norm();
  if (e.along < 0) d = -d;
  edge_a = box_edge(e.i, d[i1] > 0, d[i2] > 0);
  const auto against_b = [&](int m) {
    return -(d[0] * p.r[0][m] + d[1] * p.r[1][m] + d[2] * p.r[2][m]) > 0;
  };
  edge_b = box_edge(e.j, against_b((e.j + 1) % 3), against_b((e.j + 2) % 3));
}

// Vertex v of a box of half extents h (box_topology.hpp's signs), in its frame.
Vec3 box_corner(const Vec3& h, uint32_t v) {
  return Vec3((v & 1) ? h.x() : -h.x(), (v & 2) ? h.y() : -h.y(), (v & 4) ? h.z() : -h.z());
}

// Vertex v of the box of half extents g placed by p, in the frame it is placed in.
Vec3 placed_box_corner(const BoxPlacement& p, const Vec3& g, uint32_t v) {
  const Vec3 c = box_corner(g, v);
  Vec3 x;
  for (int row = 0; row < 3; ++row) {
    x[row] = p.t[row] + (p.r[row][0] * c.x() + p.r[row][1] * c.y() + p.r[row][2] * c.z());
  }
  return x;
}

// One point between the two edges of `e`: the midpoint of their closest points, world.
bool box_edge_contact(const BoxPlacement& p, const Vec3& ea, const Vec3& eb, const EdgeAxis& e,
                      const Transform& xa, Manifold& out) {
  Vec3 d;
  int edge_a, edge_b;
  box_edge_features(p, e, d, edge_a, edge_b);
  const Vec3 pa = box_corner(ea, kBoxEdges[edge_a][0]);
  Vec3 da = Vec3::Zero();
  da[e.i] = 2 * ea[e.i];
  const Vec3 pb = placed_box_corner(p, eb, kBoxEdges[edge_b][0]);
  const Vec3 db = Vec3(p.r[0][e.j], p.r[1][e.j], p.r[2][e.j]) * (2 * eb[e.j]);
  Vec3 ca, cb;
  closest_points_segments(pa, da, pb, db, ca, cb);
  const Mat3 ra = xa.rotation.toRotationMatrix();
  out.normal = ra * d;
  set_point(out, 0, ra * (Real(0.5) * (ca + cb)), e.separation,
            kFeatureEdges | (uint32_t(edge_a) << 15) | uint32_t(edge_b));
  out.point_count = 1;
  return true;
}

// A quadrilateral clipped by four lines has at most eight vertices; the room beyond them bounds
// what rounding could add.
constexpr int kBoxClipVertices = 16;
using BoxClip = ClipBuffer<kBoxClipVertices>;

// The face contact with face rf of the reference box (half extents h) against the incident box
// (half extents g, placed by `inc` in the reference box's frame), in that frame: the incident
// face most anti-parallel to rf clipped against rf's side planes, each point kept within the
// speculative distance and moved half its separation towards the other surface. Writes the
// points, their separations and ids (all but the reference face's bits); returns their count.
int clip_incident_face(const Vec3& h, int rf, const BoxPlacement& inc, const Vec3& g,
                       Real speculative_distance, Vec3* points, Real* seps, uint32_t* ids) {
  const int k = rf / 2;
  const Real sign = (rf & 1) ? Real(-1) : Real(1);
  int inf = 0;
  Real most = std::numeric_limits<Real>::max();
  for (int f = 0; f < 6; ++f) {
    const Real d = (f & 1) ? -(sign * inc.r[k][f / 2]) : sign * inc.r[k][f / 2];
    if (d < most) {
      most = d;
      inf = f;
    }
  }
  BoxClip poly[2];
  for (int q = 0; q < 4; ++q) {
    poly[0].points[q] = placed_box_corner(inc, g, kBoxLoops[4 * inf + q]);
    poly[0].out_label[q] = uint8_t(q);
  }
  poly[0].count = 4;
  int cur = 0;
  for (int q = 0; q < 4 && poly[cur].count > 0; ++q) {
    // The loop's edge from v0 to v1 runs along the axis where they differ; its side plane faces
    // along the third axis, out to the side both lie on.
    const uint32_t v0 = kBoxLoops[4 * rf + q], v1 = kBoxLoops[4 * rf + (q + 1) % 4];
    const int side = 3 - k - std::countr_zero(v0 ^ v1);
    const Real out_sign = ((v0 >> side) & 1) ? Real(1) : Real(-1);
    // The side plane out_sign x[side] <= h[side], one coordinate against a half extent.
    const auto beyond = [&](const Vec3& x) { return out_sign * x[side] - h[side]; };
    clip_by(poly[cur], beyond, uint8_t(kSidePlaneLabel + q), poly[1 - cur]);
    cur = 1 - cur;
  }
  const BoxClip& clipped = poly[cur];
  const uint32_t face_bits = uint32_t(inf) << 14;
  int count = 0;
  for (int q = 0; q < clipped.count; ++q) {
    const Vec3& p = clipped.points[q];
    const Real s = sign * p[k] - h[k];
    if (s > speculative_distance) continue;
    points[count] = p;
    points[count][k] -= (Real(0.5) * s) * sign;
    seps[count] = s;
    ids[count] = face_bits | clip_vertex_id(clipped, q);
    ++count;
  }
  if (count == 0) {
    // No clipped point within the speculative distance: the incident box's deepest vertex, when
    // the faces do not overlap sideways (a speculative contact still exists) or when that vertex,
    // clipped away, is below the reference face (the boxes overlap), as sat.cpp's face_contact.
    Real bs = std::numeric_limits<Real>::max();
    Vec3 deepest = Vec3::Zero();
    for (uint32_t v = 0; v < 8; ++v) {
      const Vec3 x = placed_box_corner(inc, g, v);
      const Real s = sign * x[k];
      if (s < bs) {
        bs = s;
        deepest = x;
      }
    }
    const Real s = bs - h[k];
    if (s > speculative_distance || (clipped.count > 0 && !(s < 0))) return 0;
    points[0] = deepest;
    points[0][k] -= (Real(0.5) * s) * sign;
    seps[0] = s;
    ids[0] = face_bits | 0x3FFFu;
    count = 1;
  }
  return count;
}

// Faces 2k and 2k + 1 of a box, whose separations are `plus` and `minus`, into the query: the
// first largest of all faces in order.
void take_deeper_faces(FaceQuery& q, int k, Real plus, Real minus) {
  if (plus > q.separation) q.separation = plus, q.face = 2 * k;
  if (minus > q.separation) q.separation = minus, q.face = 2 * k + 1;
}

// The face contact on face rf of A (ref_is_a) or of B, stored in `out` in the world.
bool box_face_contact(const BoxPlacement& b_in_a, const Real (&u)[3], const Vec3& ea,
                      const Vec3& eb, int rf, bool ref_is_a, const Transform& xa,
                      const Transform& xb, Real speculative_distance, Manifold& out) {
  BoxPlacement inc = b_in_a;
  if (!ref_is_a) {
    // A in B's frame: R^T, and A's centre -R^T T.
    for (int i = 0; i < 3; ++i) {
      inc.t[i] = -u[i];
      for (int j = 0; j < 3; ++j) inc.r[i][j] = b_in_a.r[j][i];
    }
  }
  Vec3 points[kBoxClipVertices];
  Real seps[kBoxClipVertices];
  uint32_t ids[kBoxClipVertices];
  const int count = clip_incident_face(ref_is_a ? ea : eb, rf, inc, ref_is_a ? eb : ea,
                                       speculative_distance, points, seps, ids);
  if (count == 0) return false;
  const Mat3 rot = (ref_is_a ? xa.rotation : xb.rotation).toRotationMatrix();
  const Vec3 origin = ref_is_a ? Vec3::Zero() : Vec3(xb.position - xa.position);
  const Vec3 face_normal = rot.col(rf / 2) * ((rf & 1) ? Real(-1) : Real(1));
  const Vec3 normal = ref_is_a ? face_normal : Vec3(-face_normal);
  const uint32_t base = (ref_is_a ? kFeatureFaceA : kFeatureFaceB) | (uint32_t(rf) << 22);
  for (int q = 0; q < count; ++q) {
    points[q] = rot * points[q] + origin;
    ids[q] |= base;
  }
  out.normal = normal;
  return emit_points(points, seps, ids, count, normal, out);
}

}  // namespace

bool collide_box_box(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                     Real speculative_distance, Manifold& out, Separation* separation) {
  out.point_count = 0;
  const BoxPlacement p = place_b_in_a(xa, xb);
  const Vec3& ea = a.half_extents;
  const Vec3& eb = b.half_extents;
  // A's faces 2k and 2k + 1: B's centre is T[k] and -T[k] along their normals, B reaches back
  // sum_j eb[j] |R[k][j]| and A out ea[k].
  FaceQuery fa;
  for (int k = 0; k < 3; ++k) {
    const Real reach =
        (eb[0] * std::abs(p.r[k][0]) + eb[1] * std::abs(p.r[k][1]) + eb[2] * std::abs(p.r[k][2])) +
        ea[k];
    take_deeper_faces(fa, k, p.t[k] - reach, -p.t[k] - reach);
  }
  if (fa.separation > speculative_distance) {
    report_separation(separation, Separation::Kind::FaceOfA, fa.separation);
    return false;
  }
  // B's faces 2k and 2k + 1: A's centre is -U[k] and U[k] along their normals (U = R^T T).
  Real u[3];
  FaceQuery fb;
  for (int k = 0; k < 3; ++k) {
    u[k] = p.r[0][k] * p.t[0] + p.r[1][k] * p.t[1] + p.r[2][k] * p.t[2];
    const Real reach =
        (ea[0] * std::abs(p.r[0][k]) + ea[1] * std::abs(p.r[1][k]) + ea[2] * std::abs(p.r[2][k])) +
        eb[k];
    take_deeper_faces(fb, k, -u[k] - reach, u[k] - reach);
  }
  if (fb.separation > speculative_distance) {
    report_separation(separation, Separation::Kind::FaceOfB, fb.separation);
    return false;
  }
  // The nine direction pairs of the edges, the first largest in the order 3 i + j.
  EdgeAxis edge;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      Real along;
      const Real s = edge_axis_separation(p, ea, eb, i, j, along);
      if (s > edge.separation) edge = {i, j, s, along};
    }
  }
  if (edge.separation > speculative_distance) {
    if (separation != nullptr) {
      Vec3 d;
      int edge_a, edge_b;
      box_edge_features(p, edge, d, edge_a, edge_b);
      *separation = {Separation::Kind::EdgePair, edge.separation, edge_a, edge_b};
    }
    return false;
  }
  // Non-finite input compares false everywhere, so no face is picked: no contact.
  if (fa.face < 0 || fb.face < 0) return false;
  const bool use_b = beats(fb.separation, fa.separation, kFaceRelTol);
  const Real face_separation = use_b ? fb.separation : fa.separation;
  if (edge.i >= 0 && beats(edge.separation, face_separation, kEdgeRelTol)) {
    return box_edge_contact(p, ea, eb, edge, xa, out);
  }
  return box_face_contact(p, u, ea, eb, use_b ? fb.face : fa.face, !use_b, xa, xb,
                          speculative_distance, out);
}

Real box_edge_pair_separation(const Shape& a, const Transform& xa, const Shape& b,
                              const Transform& xb, int edge_a, int edge_b) {
  if (edge_a < 0 || edge_a >= 12 || edge_b < 0 || edge_b >= 12) return kLowest;
  Real along;
  return edge_axis_separation(place_b_in_a(xa, xb), a.half_extents, b.half_extents, edge_a / 4,
                              edge_b / 4, along);
}

}  // namespace elan::detail
