// SPDX-License-Identifier: MIT
// Closed-form manifolds for spheres and capsules, sphere against box or any convex shape, and any
// shape against a plane. Contact points sit midway between the two surfaces.
#include "narrowphase/round_pairs.hpp"

#include <cmath>
#include <limits>

#include "narrowphase/any_perpendicular.hpp"
#include "narrowphase/manifold_reduce.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase/polyhedron.hpp"

namespace elan::detail {
namespace {

// Segments within this sine of parallel get the two-point manifold (about 0.57 degrees).
constexpr Real kParallelSegmentsSine = Real(0.01);
// perf: stack buffer of plane-contact candidates; beyond it the shallowest is replaced.
constexpr int kMaxPlaneCandidates = 64;

// Unit d, or `fallback` when d is too short to carry a direction (coincident features).
Vec3 direction_or(const Vec3& d, Real scale, const Vec3& fallback) {
  const Real len = d.norm();
  return len > 16 * kEps * scale ? Vec3(d / len) : fallback;
}

void begin(Manifold& m, const Vec3& normal) {
  m.normal = normal;
  m.point_count = 0;
}

// Contact at the midpoint of the two surface points; impulses stay for the warm-start merge.
void add_point(Manifold& m, const Vec3& surface_a, const Vec3& surface_b, Real separation,
               uint32_t id, const Vec3& ca) {
  ContactPoint& c = m.points[m.point_count++];
  const Vec3 p = Real(0.5) * (surface_a + surface_b);
  c.anchor_a = p - ca;
  c.separation = separation;
  c.feature_id = id;
}

Vec3 capsule_axis(const Shape& s, const Transform& x) {
  return x.rotation * Vec3(0, s.half_height, 0);
}

// Closest point to p on segment [c - h, c + h].
Vec3 closest_on_segment(const Vec3& c, const Vec3& h, const Vec3& p) {
  const Real hh = h.squaredNorm();
  if (!(hh > 0)) return c;
  const Real t = std::clamp(h.dot(p - c) / hh, Real(-1), Real(1));
  return c + t * h;
}

// Two balls (centre, radius) with ball A's body centre `ca_body`: the sphere-sphere closed form,
// normal along the centre line (fallback when the centres coincide).
bool collide_balls(const Vec3& ca, Real ra, const Vec3& ca_body, const Vec3& cb, Real rb,
                   const Vec3& fallback, Real speculative, uint32_t id, Manifold& out,
                   Separation* separation) {
  const Vec3 d = cb - ca;
  const Real dist = d.norm();
  const Real sep = dist - ra - rb;
  begin(out, fallback);
  if (sep > speculative) {
    report_separation(separation, Separation::Kind::Distance, sep);
    return false;
  }
  const Vec3 n = direction_or(d, ra + rb + dist, fallback);
  out.normal = n;
  add_point(out, ca + ra * n, cb - rb * n, sep, id, ca_body);
  return true;
}

// Closest points of segments p1 + s d1 and p2 + t d2, s, t in [0, 1] (Ericson, Real-Time
// Collision Detection 5.1.9).
void closest_segments(const Vec3& p1, const Vec3& d1, const Vec3& p2, const Vec3& d2, Real& s,
                      Real& t) {
  const Vec3 r = p1 - p2;
  const Real a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const Real c = d1.dot(r), b = d1.dot(d2);
  const Real denom = a * e - b * b;
  s = denom > 0 ? std::clamp((b * f - c * e) / denom, Real(0), Real(1)) : Real(0);
  t = e > 0 ? (b * s + f) / e : Real(0);
  if (t < 0) {
    t = 0;
    s = a > 0 ? std::clamp(-c / a, Real(0), Real(1)) : Real(0);
  } else if (t > 1) {
    t = 1;
    s = a > 0 ? std::clamp((b - c) / a, Real(0), Real(1)) : Real(0);
  }
}

struct Candidate {
  Vec3 point;  // world, on A's surface
  Real separation;
  uint32_t id;
};

}  // namespace

// |cb - ca| - ra - rb along the centre line.
bool collide_sphere_sphere(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                           Real speculative_distance, Manifold& out, Separation* separation) {
  return collide_balls(xa.position, a.radius, xa.position, xb.position, b.radius, Vec3::UnitY(),
                       speculative_distance, 0, out, separation);
}

// Sphere against the ball at the closest point of the capsule's segment.
bool collide_sphere_capsule(const Shape& a, const Transform& xa, const Shape& b,
                            const Transform& xb, Real speculative_distance, Manifold& out,
                            Separation* separation) {
  const Vec3 h = capsule_axis(b, xb);
  const Vec3 q = closest_on_segment(xb.position, h, xa.position);
  const Vec3 fallback = h.squaredNorm() > 0 ? any_perpendicular(h) : Vec3::UnitY();
  return collide_balls(xa.position, a.radius, xa.position, q, b.radius, fallback,
                       speculative_distance, 0, out, separation);
}

// Segment-segment closest points; near-parallel segments clip the overlap of B's projection on
// A's segment and report its two ends, each with its own separation along the common normal.
bool collide_capsule_capsule(const Shape& a, const Transform& xa, const Shape& b,
                             const Transform& xb, Real speculative_distance, Manifold& out,
                             Separation* separation) {
  const Vec3 ha = capsule_axis(a, xa), hb = capsule_axis(b, xb);
  const Vec3 a0 = xa.position - ha, b0 = xb.position - hb;
  const Vec3 d1 = 2 * ha, d2 = 2 * hb;
  const Real len1 = d1.squaredNorm(), len2 = d2.squaredNorm();
  const Real radii = a.radius + b.radius;
  const Real cross = d1.cross(d2).squaredNorm();
  begin(out, Vec3::UnitY());
  if (len1 > 0 && len2 > 0 &&
      cross <= kParallelSegmentsSine * kParallelSegmentsSine * len1 * len2) {
    // B's ends in A's segment parameter; the overlap [lo, hi] of that interval and [0, 1].
    const Real t0 = d1.dot(b0 - a0) / len1, t1 = d1.dot(b0 + d2 - a0) / len1;
    const int b_lo = t0 <= t1 ? 0 : 1;
    const Real lo = std::max(Real(0), std::min(t0, t1));
    const Real hi = std::min(Real(1), std::max(t0, t1));
    if (hi - lo > Real(1e-3)) {
      const Vec3 pa[2] = {a0 + lo * d1, a0 + hi * d1};
      const Vec3 pb[2] = {closest_on_segment(xb.position, hb, pa[0]),
                          closest_on_segment(xb.position, hb, pa[1])};
      const Vec3 mid_a = Real(0.5) * (pa[0] + pa[1]), mid_b = Real(0.5) * (pb[0] + pb[1]);
      Vec3 gap = mid_b - mid_a;
      gap -= d1 * (d1.dot(gap) / len1);
      const Vec3 n = direction_or(gap, radii + gap.norm(), any_perpendicular(d1));
      const uint32_t ids[2] = {lo > 0 ? uint32_t(2 + b_lo) : 0u, hi < 1 ? uint32_t(3 - b_lo) : 1u};
      out.normal = n;
      for (int k = 0; k < 2; ++k) {
        const Real sep = n.dot(pb[k] - pa[k]) - radii;
        if (sep > speculative_distance) continue;
        add_point(out, pa[k] + a.radius * n, pb[k] - b.radius * n, sep, ids[k], xa.position);
      }
      return out.point_count > 0;
    }
  }
  Real s, t;
  closest_segments(a0, d1, b0, d2, s, t);
  const Vec3 ca = a0 + s * d1, cb = b0 + t * d2;
  Vec3 fallback = d1.cross(d2);
  fallback = fallback.squaredNorm() > 0 ? Vec3(fallback.normalized())
             : len1 > 0                 ? any_perpendicular(d1)
                                        : Vec3::UnitY();
  return collide_balls(ca, a.radius, xa.position, cb, b.radius, fallback, speculative_distance, 4,
                       out, separation);
}

// Closest point on the box (clamp the centre in box coordinates); a centre inside the box is
// pushed out through the face of least penetration.
bool collide_sphere_box(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                        Real speculative_distance, Manifold& out, Separation* separation) {
  const Mat3 rb = xb.rotation.toRotationMatrix();
  const Vec3 c = rb.transpose() * (xa.position - xb.position);
  const Vec3& he = b.half_extents;
  const Vec3 q = c.cwiseMax(-he).cwiseMin(he);
  const Vec3 d = c - q;
  const Real dist = d.norm();
  begin(out, Vec3::UnitY());
  if (dist > 16 * kEps * he.maxCoeff()) {
    const Real sep = dist - a.radius;
    if (sep > speculative_distance) {
      report_separation(separation, Separation::Kind::Distance, sep);
      return false;
    }
    const Vec3 n = rb * (-d / dist);
    uint32_t region = 0;
    for (int i = 2; i >= 0; --i) region = region * 3 + (c[i] < -he[i] ? 0 : c[i] > he[i] ? 2 : 1);
    out.normal = n;
    add_point(out, xa.position + a.radius * n, xb.position + rb * q, sep, region, xa.position);
    return true;
  }
  int axis = 0;
  Real pen = he[0] - std::abs(c[0]);
  for (int i = 1; i < 3; ++i) {
    const Real p = he[i] - std::abs(c[i]);
    if (p < pen) pen = p, axis = i;
  }
  const Real sign = c[axis] >= 0 ? Real(1) : Real(-1);
  Vec3 surface = c;
  surface[axis] = sign * he[axis];
  const Vec3 n = -sign * rb.col(axis);
  out.normal = n;
  add_point(out, xa.position + a.radius * n, xb.position + rb * surface, -pen - a.radius,
            27 + 2 * axis + (sign < 0 ? 1 : 0), xa.position);
  return true;
}

// The sphere's centre against B's core: a hull's face when the centre stands over it or is
// inside the hull, otherwise GJK, and EPA when the centre is inside another shape (a cylinder).
// Radii are added to the core result (exact for rounded shapes).
bool collide_sphere_convex(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                           Real speculative_distance, Manifold& out, Separation* separation) {
  // In B's frame (see gjk_core_in_frame_of_b); the results are turned back to the world.
  const Vec3 centre = xb.rotation.conjugate() * (xa.position - xb.position);
  const Real radii = a.radius + core_radius(b);
  begin(out, Vec3::UnitY());
  Vec3 n, point_b;  // in B's frame
  Real sep;
  // A hull lies behind each of its face planes: the largest height of the centre above one
  // bounds its distance from below, and is the distance when the centre's foot is on that face,
  // or (negative) the depth when the centre is inside. perf: most spheres of a pile rest on a
  // face; those take neither GJK nor EPA.
  int face = -1;
  Real height = std::numeric_limits<Real>::lowest();
  if (b.type == ShapeType::ConvexHull) {
    const ConvexHull& h = *b.hull;
    for (int f = 0; f < int(h.faces.size()); ++f) {
      const Real s = h.faces[f].normal.dot(centre) - h.faces[f].offset;
      if (s > height) height = s, face = f;
    }
    if (height - radii > speculative_distance) {
      report_separation(separation, Separation::Kind::FaceOfB, height - radii);
      return false;
    }
    const HullFace& f = h.faces[face];
    if (!(height <= 0 ||
          foot_on_face(h.vertices, h.face_vertices.data() + f.first, f.count, f.normal, centre))) {
      face = -1;
    }
  }
  if (face >= 0) {
    const Vec3& normal = b.hull->faces[face].normal;
    n = -normal;
    sep = height - radii;
    point_b = centre - height * normal;
  } else {
    Simplex s;
    const GjkResult g = gjk_core_in_frame_of_b(std::span<const Vec3>(&centre, 1), b, s);
    if (!g.overlap && g.distance > 16 * kEps * b.bounding_radius) {
      sep = g.distance - radii;
      if (sep > speculative_distance) {
        report_separation(separation, Separation::Kind::Distance, g.lower_bound - radii);
        return false;
      }
      n = (g.point_b - g.point_a) / g.distance;
      point_b = g.point_b;
    } else {
      const Transform in_b{Vec3::Zero(), Quat::Identity()};
      const EpaResult e =
          epa_placed(place(a, {centre, Quat::Identity()}, false), place(b, in_b, false), s);
      n = e.normal;
      sep = -e.depth - radii;
      point_b = e.point_b;
    }
  }
  n = xb.rotation * n;
  out.normal = n;
  add_point(out, xa.position + a.radius * n,
            xb.rotation * point_b + xb.position - core_radius(b) * n, sep, 0, xa.position);
  return true;
}

// Signed distance of each candidate point of A to the plane dot(n, x) = offset (world); the
// candidates are A's deepest features: sphere bottom, capsule ends, box corners, hull vertices
// (reduced to four with reduce_to_four), the cylinder's deepest rim points.
bool collide_convex_plane(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                          Real speculative_distance, Manifold& out, Separation* separation) {
  const Vec3 n = xb.rotation * b.plane_normal;
  const Real offset = b.plane_offset + n.dot(xb.position);
  const Mat3 ra = xa.rotation.toRotationMatrix();
  const Vec3 nl = ra.transpose() * n;  // plane normal in A's principal frame
  const Real centre_height = n.dot(xa.position) - offset;
  begin(out, -n);
  Candidate cand[kMaxPlaneCandidates];
  int count = 0;
  Real lowest = std::numeric_limits<Real>::max();  // A's support below the plane is a candidate
  // A local point's height above the plane, rounded by r (sphere, capsule) on the way down.
  auto consider = [&](const Vec3& local, Real r, uint32_t id) {
    const Real s = nl.dot(local) + centre_height - r;
    lowest = std::min(lowest, s);
    if (s > speculative_distance) return;
    push_keeping_deepest(cand, count, kMaxPlaneCandidates,
                         Candidate{xa.position + ra * local - r * n, s, id});
  };
  switch (a.type) {
    case ShapeType::Sphere:
      consider(Vec3::Zero(), a.radius, 0);
      break;
    case ShapeType::Capsule:
      consider(Vec3(0, -a.half_height, 0), a.radius, 0);
      consider(Vec3(0, a.half_height, 0), a.radius, 1);
      break;
    case ShapeType::Box:
      for (uint32_t k = 0; k < 8; ++k) {
        const Vec3& h = a.half_extents;
        consider(Vec3(k & 1 ? h.x() : -h.x(), k & 2 ? h.y() : -h.y(), k & 4 ? h.z() : -h.z()), 0,
                 k);
      }
      break;
    case ShapeType::ConvexHull: {
      const std::vector<Vec3>& v = a.hull->vertices;
      for (size_t k = 0; k < v.size(); ++k) consider(v[k], 0, uint32_t(k));
      break;
    }
    case ShapeType::Cylinder: {
      // The rim point deepest along -n lies in the direction u of -n's part across the axis;
      // the lower cap contributes it and the rim points at 90, 180, 270 degrees (a cap resting
      // flat gives a square), the upper cap its deepest point (a cylinder on its side: a line).
      Vec3 u = -Vec3(nl.x(), 0, nl.z());
      u = u.squaredNorm() > kEps * kEps ? Vec3(u.normalized()) : Vec3::UnitX();
      const Vec3 w = Vec3::UnitY().cross(u);
      const Real low = nl.y() >= 0 ? -a.half_height : a.half_height;
      const Vec3 rim[4] = {u, w, -u, -w};
      for (uint32_t k = 0; k < 4; ++k) {
        consider(Vec3(0, low, 0) + a.radius * rim[k], 0, kFeatureRim + k);
      }
      consider(Vec3(0, -low, 0) + a.radius * u, 0, kFeatureRim + 4);
      break;
    }
    case ShapeType::Plane:
    default:
      return false;
  }
  // The half-space is B's one face: A's points move in B's frame.
  if (count == 0) report_separation(separation, Separation::Kind::FaceOfB, lowest);
  Vec3 pos[kMaxPlaneCandidates];
  Real sep[kMaxPlaneCandidates];
  for (int i = 0; i < count; ++i) pos[i] = cand[i].point, sep[i] = cand[i].separation;
  int keep[kMaxManifoldPoints];
  const int kept =
      reduce_to_four(std::span<const Vec3>(pos, count), std::span<const Real>(sep, count), n, keep);
  for (int i = 0; i < kept; ++i) {
    const Candidate& c = cand[keep[i]];
    add_point(out, c.point, c.point - c.separation * n, c.separation, c.id, xa.position);
  }
  return out.point_count > 0;
}

}  // namespace elan::detail
