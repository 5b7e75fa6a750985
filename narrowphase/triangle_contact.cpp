// SPDX-License-Identifier: MIT
// Convex shape against one triangle (see triangle_contact.hpp).
//
// Internal edges: Jolt's active edges rather than Box2D's smooth segments or Bullet's
// btAdjustInternalEdgeContacts. Box2D's ghost vertices are the 2D case of the same idea (a
// segment knows its neighbours); in 3D it becomes a flag per edge, built once from the
// neighbours (mesh_triangle.hpp). Bullet corrects each finished contact's normal afterwards from
// an edge-angle map, and keeps the depth measured along the old normal; deciding on the flag
// before the points are made lets the separation be measured along the normal the solver gets,
// so a box resting across a shared edge sits at the face's height.
//
// The normal of a box, hull, cylinder or capsule: GJK between the cores when apart, EPA when they
// overlap, rather than a SAT over the triangle's normal, A's faces and the edge pairs. One path
// serves every shape (a cylinder has no finite set of axes), its witness point on the triangle
// names the feature the active-edge rule needs, and most triangles under a resting body need
// neither (the two cases before the GJK).
#include "narrowphase/triangle_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/heightfield.hpp"
#include "narrowphase/closest_on_triangle.hpp"
#include "narrowphase/manifold_reduce.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase/supporting_feature.hpp"

namespace elan::detail {
namespace {

// A closest point within this barycentric weight of an edge is on it: witnesses of GJK and EPA
// sit on the edge to about the float epsilon times the triangle's size, far below this.
constexpr Real kOnEdgeWeight = Real(1e-4);
// A vertex contact's normal leans out past an inactive edge when its component along the edge's
// outward direction is above this (about 0.06 degree): rounding of a face normal stays below.
constexpr Real kLeanTolerance = Real(1e-3);

// `base` plus the size of the corners' coordinates (from A's centre) and of the triangle's edges,
// added in that order: the scale of the rounding margins of the distances measured to the
// triangle, each a part in 1e4 of it.
Real with_corner_scale(Real base, const Vec3 (&v)[3]) {
  return base + v[0].cwiseAbs().sum() + (v[1] - v[0]).cwiseAbs().sum() +
         (v[2] - v[0]).cwiseAbs().sum();
}

// Closest point of the triangle to the origin, and its feature.
Vec3 closest_on_triangle(const Vec3 (&v)[3], uint32_t& region) {
  const TriangleClosest<Vec3> closest = closest_on_triangle_to_origin(v[0], v[1], v[2]);
  region = closest.region;
  return closest.point;
}

// The feature of the triangle a witness point p on it lies on, from its barycentric weights.
uint32_t region_of(const Vec3 (&v)[3], const Vec3& p) {
  const Vec3 e0 = v[1] - v[0], e1 = v[2] - v[0], e2 = p - v[0];
  const Real d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const Real d20 = e2.dot(e0), d21 = e2.dot(e1);
  const Real den = d00 * d11 - d01 * d01;
  if (!(den > 0)) return kTriangleFace;
  const Real w1 = (d11 * d20 - d01 * d21) / den;
  const Real w2 = (d00 * d21 - d01 * d20) / den;
  const Real w0 = 1 - w1 - w2;
  const bool z0 = w0 < kOnEdgeWeight, z1 = w1 < kOnEdgeWeight, z2 = w2 < kOnEdgeWeight;
  if (z1 && z2) return kTriangleVertex + 0;
  if (z0 && z2) return kTriangleVertex + 1;
  if (z0 && z1) return kTriangleVertex + 2;
  if (z2) return kTriangleEdge + 0;  // no weight on v2: edge v0 v1
  if (z0) return kTriangleEdge + 1;
  if (z1) return kTriangleEdge + 2;
  return kTriangleFace;
}

// A triangle's active edges, read on first use: a heightfield's triangles come without them
// (TriangleQuery::field), and most contacts are decided before they are needed.
struct LazyEdges {
  const MeshTriangle& t;
  const HeightField* field;
  int value = -1;
  uint8_t get() {
    if (value < 0) value = field != nullptr ? field->active_edges_of(t) : t.active_edges;
    return uint8_t(value);
  }
};

// Whether the normal found at the triangle's feature `region` stands: the feature is an active
// edge, or a vertex with an active edge whose normal leans out past none of its inactive edges.
// `out_normal`: from the triangle towards A; `face`: the face normal toward A's side.
bool keeps_normal(uint32_t region, LazyEdges& lazy, const Vec3 (&v)[3], const Vec3& face,
                  const Vec3& out_normal) {
  if (region == kTriangleFace || out_normal.dot(face) < -kLeanTolerance) return false;
  const uint8_t active_edges = lazy.get();
  const auto active = [&](uint32_t k) { return ((active_edges >> k) & 1u) != 0; };
  if (region >= kTriangleEdge) return active(region - kTriangleEdge);
  const uint32_t k = region - kTriangleVertex;
  const uint32_t edges[2] = {k, (k + 2) % 3};  // the edges leaving and reaching vertex k
  if (!active(edges[0]) && !active(edges[1])) return false;
  const Vec3 centroid = (v[0] + v[1] + v[2]) / 3;
  for (const uint32_t e : edges) {
    if (active(e)) continue;
    const Vec3& p = v[e];
    Vec3 outward = (v[(e + 1) % 3] - p).cross(face);
    if (outward.dot(centroid - p) > 0) outward = -outward;
    if (out_normal.dot(outward) > kLeanTolerance * outward.norm()) return false;
  }
  return true;
}

// Whether A, sunk to `depth` below the face's plane with its lowest point's foot F on the face
// (from_foot: the corners from F), is pushed out along the face's normal n by less than along any
// direction GJK/EPA could keep. Along u = cos(a) n + sin(a) w (w in the plane), A must move by
// d(u) = max over the triangle of p.u - min over A of q.u to clear it, and d(n) = depth. The
// triangle holds F + delta w (delta: F's distance to the nearest edge line) and A its lowest
// point F - depth n, so d(u) >= depth cos(a) + delta sin(a): above depth for every a in
// (0, pi / 2] once delta > depth, and on while cos(a) > -kLeanTolerance with the margin below.
// A direction leaning further down is one keeps_normal rejects. So the least push is along n, at
// the foot: the face's contact, which EPA would only approximate.
bool sunk_within_face(const Vec3 (&v)[3], const Vec3 (&from_foot)[3], Real depth,
                      Real bounding_radius) {
  // The margin covers the rounding of the foot's distances (as reach_triangle's margins).
  const Real need =
      depth * (1 + 2 * kLeanTolerance) + Real(1e-4) * with_corner_scale(bounding_radius, v);
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = v[k < 2 ? k + 1 : 0] - v[k];
    // |e x (v[k] - F)| is |e| times F's distance to the edge's line (both lie in the plane).
    if (!(e.cross(from_foot[k]).squaredNorm() > need * need * e.squaredNorm())) return false;
  }
  return true;
}

void add(TriangleContact& out, const Vec3& p, Real s, uint32_t id) {
  out.points[out.count] = p;
  out.separation[out.count] = s;
  out.feature[out.count] = id;
  ++out.count;
}

// The sphere's closed form: its centre (the origin) against the closest point of the triangle.
bool sphere_triangle(Real r, LazyEdges& edges, const Vec3 (&v)[3], const Vec3& face,
                     Real speculative, TriangleContact& out) {
  uint32_t region = kTriangleFace;
  const Vec3 q = closest_on_triangle(v, region);
  const Real dist = q.norm();
  if (dist - r > speculative) return false;
  const Real scale = std::max(r, (v[1] - v[0]).norm());
  if (dist > 16 * kEps * scale && keeps_normal(region, edges, v, face, -q / dist)) {
    const Vec3 n = q / dist;
    add(out, Real(0.5) * (r * n + q), dist - r, region);
  } else {
    const Real height = -face.dot(v[0]);  // the centre above the face's plane
    const Real s = height - r;
    if (s > speculative) return false;
    out.normal = -face;
    add(out, Real(-0.5) * (r + height) * face, s, region);
    return true;
  }
  out.normal = q / dist;
  return true;
}

}  // namespace

TriangleQuery make_triangle_query(const Shape& a, const Transform& xa, Real speculative_distance) {
  TriangleQuery q;
  q.shape = &a;
  q.position = xa.position;
  q.at_origin = Transform{Vec3::Zero(), xa.rotation};
  q.full = place(a, q.at_origin, true);
  q.radius = core_radius(a);
  q.core = q.radius > 0 ? place(a, q.at_origin, false) : q.full;
  q.speculative = speculative_distance;
  return q;
}

bool reach_triangle(const TriangleQuery& q, const Vec3& a, const Vec3& b, const Vec3& c,
                    bool two_sided, TriangleReach& r) {
  // Working frame: the surface's axes, origin at A's centre, so coordinates stay small.
  // perf: the corners are worked on as locals and only written to r: read back from r, GCC loaded
  // two floats at once that it had just stored one at a time (a failed store forwarding).
  const Vec3 v[3] = {a - q.position, b - q.position, c - q.position};
  for (int k = 0; k < 3; ++k) r.v[k] = v[k];
  Vec3 geometric = (v[1] - v[0]).cross(v[2] - v[0]);
  const Real area2 = geometric.norm();
  if (!(area2 > 0)) return false;
  geometric /= area2;
  const Real centre_height = -geometric.dot(v[0]);
  // A one-sided triangle collides from the front only: a body whose centre is behind it has
  // passed through (the continuous stage exists to prevent that) and must not be pushed down.
  if (!two_sided && centre_height < 0) return false;
  r.geometric = geometric;
  r.face = centre_height >= 0 ? geometric : Vec3(-geometric);
  // Only the motion toward the plane can close the gap to it within the step.
  r.speculative = q.speculative + std::max(Real(0), -r.face.dot(q.motion));
  if (q.shape->type == ShapeType::Sphere) {
    // The sphere's closed form rejects on its centre's distance to the triangle, which its
    // height above the plane bounds from below; the margin covers that distance's rounding
    // (coordinates of a few metres round to about 1e-6 m), so nothing it keeps is lost.
    const Real margin = Real(1e-4) * (q.shape->radius + r.speculative + v[0].cwiseAbs().sum());
    return !(std::abs(centre_height) - q.shape->radius > r.speculative + margin);
  }
  // A lies within its bounding radius R of its centre, so every point of A that a contact reports
  // (one over the triangle, or within the speculative distance of it) projects onto the plane
  // within R of the centre's projection, and the triangle must come that near: a triangle that
  // lies beyond one of its edges' lines by more than R plus the speculative distance, measured in
  // its plane, gives nothing. perf: the box of a body grown by its motion over the step holds
  // many such triangles beside it, each of which would cost a support, a supporting feature and
  // a clip to reject. The test on edge k, e = v[k+1] - v[k], whose outward normal in the plane is
  // e x g: -(e x g).v[k] > reach |e| (squared, with its sign, so that no root is taken).
  const Real lateral =
      q.shape->bounding_radius + r.speculative +
      Real(1e-4) * (q.shape->bounding_radius + r.speculative + v[0].cwiseAbs().sum());
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = v[(k + 1) % 3] - v[k];
    const Real beyond = -e.cross(geometric).dot(v[k]);
    if (beyond > 0 && beyond * beyond > lateral * lateral * e.squaredNorm()) return false;
  }
  // A lies on its centre's side of the plane down to its lowest point: when that is above the
  // plane by more than the speculative distance, the triangle is farther still. perf: one
  // support rejects most of the triangles under a body's box.
  r.lowest = support_world(q.full, -r.face);
  r.plane_gap = r.face.dot(r.lowest - v[0]);
  if (r.plane_gap > r.speculative) return false;
  // A's distance to the triangle is at least its gap along the direction u from A's centre to the
  // triangle's closest point c: no point of the triangle is nearer than |c| along u (c is the
  // closest), and no point of A is farther than its support along u. When that gap is beyond the
  // speculative distance, so is every contact: the closest features' distance (the GJK path),
  // and A's points the face path reports, over the triangle or under it at any depth, L = F - d n
  // (F on the triangle, n the face normal, d >= 0): u points from A's centre, on n's side, to the
  // triangle, so u.n <= 0 and u.L >= u.F >= |c|, and such a point would be in the gap. (The
  // cell's test, clear_of_box, has no such u and checks u.n.) The margin covers the rounding of the
  // gap and of the contact's own tests (as `lateral`'s). perf: a body resting on a smooth surface
  // is within the speculative distance of the planes of most triangles around it, which the tests
  // above keep, and a tilted body is above most of them by far more.
  uint32_t region = kTriangleFace;
  r.closest = closest_on_triangle(v, region);
  const Vec3& closest = r.closest;
  const Real dist2 = closest.squaredNorm();
  if (dist2 > 0) {
    const Real dist = std::sqrt(dist2);
    const Vec3 u = closest / dist;
    // A's support along u reaches at least as far as any point of A (its lowest, the last
    // support taken): a gap to such a point within the speculative distance keeps the triangle
    // without the support (the support's gap is no larger, to its rounding, which the margin
    // below far exceeds). perf: under a resting body u is near -face, where the lowest point is
    // the support, and beside it near the last triangle's direction.
    if (dist - std::max(u.dot(r.lowest), u.dot(q.recent)) <= r.speculative) return true;
    q.recent = support_world(q.full, u);
    const Real gap = dist - u.dot(q.recent);
    const Real margin = Real(1e-4) * with_corner_scale(q.shape->bounding_radius + r.speculative, v);
    if (gap > r.speculative + margin) return false;
  }
  return true;
}

bool clear_of_box(const TriangleQuery& q, const Vec3& lo, const Vec3& hi, Real speculative,
                  std::span<const MeshTriangle> in_box) {
  // Nothing of the box is nearer than |c| along u = c / |c| (c the box's closest point to A's
  // centre), and nothing of A is farther than its support along u: their distance is at least
  // the gap between the two, which bounds every triangle's in the box from below (as
  // reach_triangle's distance test, whose margin this one keeps for the box's corners).
  // That bounds the GJK path's contacts. The face path also reports A's points under a triangle,
  // L = F - d n (F on the triangle, n its face normal toward A's centre, d >= 0), at any depth;
  // u.L = u.F - d u.n >= |c| holds for them only when u.n <= 0, which reach_triangle's own u (to
  // the triangle's closest point) always has, and the box's u need not: a thin piece reaching
  // under a steep cell from its upper side. So a triangle that faces along u keeps the cell.
  const Vec3 c = q.position.cwiseMax(lo).cwiseMin(hi) - q.position;
  const Real dist2 = c.squaredNorm();
  if (!(dist2 > 0)) return false;
  const Real dist = std::sqrt(dist2);
  const Vec3 u = c / dist;
  // A's support along u reaches at least as far as any point of A (q.down, q.recent): a gap to
  // such a point within the speculative distance keeps the box without the support (the
  // support's gap is no larger, to its rounding, which the margin below far exceeds). perf: the
  // cells under A.
  if (dist - std::max(u.dot(q.down), u.dot(q.recent)) <= speculative) return false;
  for (const MeshTriangle& t : in_box) {
    const Vec3 geometric = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
    const Vec3 face = geometric.dot(q.position - t.v[0]) >= 0 ? geometric : Vec3(-geometric);
    if (!(u.dot(face) <= 0)) return false;
  }
  const Real margin = Real(1e-4) * (q.shape->bounding_radius + speculative +
                                    q.position.cwiseAbs().sum() + 2 * (hi - lo).cwiseAbs().sum());
  q.recent = support_world(q.full, u);
  return dist - u.dot(q.recent) > speculative + margin;
}

bool collide_triangle(const Shape& a, const Transform& xa, const MeshTriangle& t,
                      Real speculative_distance, TriangleContact& out) {
  out.count = 0;
  const TriangleQuery q = make_triangle_query(a, xa, speculative_distance);
  TriangleReach r;
  if (!reach_triangle(q, t, r)) return false;
  return collide_reached_triangle(q, t, r, out);
}

bool collide_reached_triangle(const TriangleQuery& q, const MeshTriangle& t, const TriangleReach& r,
                              TriangleContact& out) {
  out.count = 0;
  const Shape& a = *q.shape;
  const Real speculative_distance = r.speculative;
  const Vec3(&v)[3] = r.v;
  const Vec3& geometric = r.geometric;
  const Vec3& face = r.face;
  LazyEdges edges{t, q.field};
  if (a.type == ShapeType::Sphere) {
    return sphere_triangle(a.radius, edges, v, face, speculative_distance, out);
  }
  const Transform& at_origin = q.at_origin;
  const PlacedShape& full = q.full;
  const Vec3& lowest = r.lowest;
  const Real plane_gap_of_a = r.plane_gap;
  const Real radius = q.radius;
  Vec3 n, on_a, on_b;  // A to the triangle; closest (or deepest) points
  Real sep;
  uint32_t region = kTriangleFace;
  // Three cases need no GJK. A whose lowest point is above the plane with its foot on the face:
  // that foot is the closest point of the triangle (nothing of it is nearer than its plane), so
  // the contact is the face's. A sunk into the face less deep than its foot is from the edges:
  // the face's contact too (sunk_within_face). And a triangle with no active edge (inside a
  // smooth surface) gives the face's normal wherever A touches it; A's points over it come from
  // the clipping below, and when none is over it, its neighbour's triangle reports them. perf:
  // most triangles under a body resting on a mesh or a heightfield are one of these.
  const Vec3 foot = lowest - plane_gap_of_a * face;
  const Vec3 from_foot[3] = {v[0] - foot, v[1] - foot, v[2] - foot};
  uint32_t foot_region = kTriangleFace;
  closest_on_triangle(from_foot, foot_region);
  const bool foot_on_face = foot_region == kTriangleFace;
  const bool done =
      (foot_on_face && (plane_gap_of_a >= 0 ||
                        sunk_within_face(v, from_foot, -plane_gap_of_a, a.bounding_radius))) ||
      edges.get() == 0;
  // Whether the contact takes the face's normal: then it is the face's contact, made only of A's
  // points over the face (see below).
  bool face_normal = done;
  // The deepest point GJK/EPA found when the face's normal replaced theirs, and its separation.
  Vec3 witness = Vec3::Zero();
  Real witness_sep = 0;
  if (done) {
    n = -face;
    sep = plane_gap_of_a;
    on_a = lowest;
    on_b = foot;
  }
  if (!done) {
    Simplex simplex;
    // GJK may stop once the core is shown farther than the speculative distance plus the radius
    // (the rejection below); the margin covers the distance's rounding, so that GJK run to the
    // end would reject those triangles too.
    const Real reject = speculative_distance + radius +
                        Real(1e-4) * with_corner_scale(a.bounding_radius + speculative_distance, v);
    // GJK starts toward the triangle's closest point to A's centre (reach_triangle's), which
    // for a triangle beside A is nearer the closest features' direction than the face's normal:
    // fewer iterations, the same result to the search's precision, a contact's: one that ends in
    // overlap is the full search, which EPA goes on from.
    const GjkResult g = gjk_triangle_contact(q.core, v, r.closest, simplex, reject);
    if (g.beyond) return false;
    if (!g.overlap && g.distance > Real(1e-6) * a.bounding_radius) {
      sep = g.distance - radius;
      // The distance to the triangle bounds the separation along its face normal from above
      // only where A is over the face; beyond it the neighbour's triangle reports the contact.
      if (sep > speculative_distance) return false;
      n = (g.point_b - g.point_a) / g.distance;
      on_a = g.point_a + radius * n;
      on_b = g.point_b;
    } else {
      Simplex full_simplex = simplex;
      if (radius > 0) gjk_triangle(full, v, Vec3(-face), full_simplex);
      const EpaResult e = epa_triangle(full, v, full_simplex);
      n = e.normal;
      sep = -e.depth;
      on_a = e.point_a;
      on_b = e.point_b;
      if (!e.ok || !n.allFinite() || n.squaredNorm() < Real(0.5)) n = -face, on_b = on_a;
    }
    region = region_of(v, on_b);
  }
  if (!keeps_normal(region, edges, v, face, -n)) {
    // The face's normal; the separation is A's lowest point's height above the face's plane.
    face_normal = true;
    witness = Real(0.5) * (on_a + on_b);
    witness_sep = done ? Real(0) : sep;
    n = -face;
    on_a = lowest;
    sep = plane_gap_of_a;
    on_b = on_a + sep * n;
  }
  out.normal = n;

  // The points: A's supporting feature along n against the triangle, the better aligned face the
  // reference (the triangle on a tie: its plane is the one the normal was measured to).
  Feature fa, fb;
  supporting_feature(a, at_origin, n, Vec3::Zero(), fa, &q.kept_face);
  fb.count = 3;
  for (int k = 0; k < 3; ++k) fb.points[k] = v[k];
  fb.id = 0;
  const Real triangle_align = std::abs(geometric.dot(n));
  Real a_align = -1;
  if (fa.count >= 3) {
    const Vec3 fn = (fa.points[1] - fa.points[0]).cross(fa.points[2] - fa.points[0]);
    a_align = std::abs(fn.dot(n)) / fn.norm();
  }
  const Feature* ref = nullptr;
  if (a_align > triangle_align && a_align >= kFaceCos) {
    ref = &fa;
  } else if (triangle_align >= kFaceCos) {
    ref = &fb;
  }
  // A feature of at most kMaxFeature points clipped by three planes, or the triangle by as many.
  constexpr int kMaxPoints = kMaxFeature + 3;
  Vec3 points[kMaxPoints];
  Real seps[kMaxPoints];
  uint32_t ids[kMaxPoints];
  int count = 0;
  const uint32_t base = (region << 22) | ((fa.id & 0x7F) << 14);
  if (ref != nullptr) {
    const bool ref_is_a = ref == &fa;
    TriangleClip clipped;
    clip_against(*ref, ref_is_a ? fb : fa, clipped);
    const RefPlane plane = ref_plane(*ref, n, ref_is_a);
    for (int k = 0; k < std::min(clipped.count, kMaxPoints); ++k) {
      const Vec3& p = clipped.points[k];
      const Real s = plane.gap(p);
      if (s > speculative_distance) continue;
      points[count] = ref_is_a ? Vec3(p - Real(0.5) * s * n) : Vec3(p + Real(0.5) * s * n);
      seps[count] = s;
      ids[count] = base | (ref_is_a ? 1u << 21 : 0u) | clip_vertex_id(clipped, k);
      ++count;
    }
  }
  if (count == 0 && face_normal && !foot_on_face) {
    // A face contact is A's points over the face. When none is (A's lowest point along the
    // face's normal is beyond the triangle), the plane's gap to that point measures nothing of
    // this triangle: on a curved surface the plane runs above the neighbours' surface, so the
    // gap would be a penetration that is not there, at a point the triangle does not reach. The
    // triangle A is over reports the contact there. Only A overlapping the triangle itself
    // keeps one point: the deepest GJK/EPA found, at its depth along their normal, the least
    // push along any direction that separates them, so never more than the overlap.
    if (!(witness_sep < 0)) return false;
    points[0] = witness;
    seps[0] = witness_sep;
    ids[0] = base | 0x3FFFu;
    count = 1;
  }
  if (count == 0) {
    points[0] = Real(0.5) * (on_a + on_b);
    seps[0] = sep;
    ids[0] = base | 0x3FFFu;
    count = 1;
  }
  int keep[kMaxManifoldPoints];
  const int kept = reduce_to_four(std::span<const Vec3>(points, std::size_t(count)),
                                  std::span<const Real>(seps, std::size_t(count)), n, keep);
  for (int k = 0; k < kept; ++k) add(out, points[keep[k]], seps[keep[k]], ids[keep[k]]);
  return out.count > 0;
}

}  // namespace elan::detail
