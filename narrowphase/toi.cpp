// SPDX-License-Identifier: MIT
// Time of impact by conservative advancement (Mirtich 1996, "Impulse-based dynamic simulation of
// rigid body systems", 4.3): step time forward by distance / (bound on the approach speed);
// against a mesh, heightfield or compound, the earliest over its triangles and parts.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/compound.hpp"
#include "core/base/fixed_math.hpp"
#include "core/base/fixed_slerp.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/triangle_mesh.hpp"
#include "narrowphase/collide.hpp"
#include "narrowphase/composite.hpp"
#include "narrowphase/minkowski.hpp"

namespace elan::detail {
namespace {

constexpr int kMaxIterations = 64;

// The pose at t of the motion from x0 to x1: the position along the line, the rotation along
// the arc (slerp, in the engine's own trigonometry: the same bits on every CPU).
Transform pose_at(const Transform& x0, const Transform& x1, const SlerpArc& arc, Real t) {
  Transform x;
  x.position = x0.position + t * (x1.position - x0.position);
  x.rotation = slerp_at(arc, t);
  return x;
}

// Rotation angle from q0 to q1 along the shorter arc: |omega| over the unit interval.
Real rotation_angle(const Quat& q0, const Quat& q1) {
  const Real c = std::min(std::abs(q0.dot(q1)), Real(1));
  return 2 * Real(fixed_acos(c));
}

Transform compose(const Transform& outer, const Transform& inner) {
  return {outer.rotation * inner.position + outer.position, outer.rotation * inner.rotation};
}

// Conservative advancement from t = 0 on the distance at time t (distance(t, dir, bound), dir
// the last normal as GJK's warm start): `delta` is the relative linear motion over the unit
// interval, `spin` the bound on the rotational speed of any surface point. Returns 1 if they do
// not meet before `until` (at most 1): t only grows, so a caller taking the earliest of several
// impacts stops each search at the earliest found so far, with the same minimum.
// The distance may stop early (result.beyond) when its lower bound shows the gap staying above
// `bound.reach` over the rest of the interval, [t, until]: the stop below (distance <= target +
// tolerance) is then never met, so the answer is 1 as the full search would find. `margin` is
// added to the stop distance in that bound for the rounding of the distances (GJK's relative
// tolerance and coordinates far from the origin).
template <class Distance>
Real advance(const Distance& distance, const Vec3& delta, Real spin, Real target, Real tolerance,
             Real margin, Vec3 dir, Real until = 1) {
  Real t = 0;
  for (int iter = 0; iter < kMaxIterations; ++iter) {
    const Real rest = until - t;
    const SweepBound bound{rest * delta, rest * spin, target + tolerance + margin};
    const GjkResult g = distance(t, dir, bound);
    if (g.beyond) return 1;
    if (g.overlap || g.distance <= target + tolerance) return t;
    const Vec3 n = (g.point_b - g.point_a) / g.distance;
    // Along the fixed axis n the gap closes no faster than the relative velocity's component
    // plus the rotational bound, so advancing by (distance - target) / speed cannot overshoot.
    const Real speed = delta.dot(n) + spin;
    if (!(speed > 0)) return 1;
    t += (g.distance - target) / speed;
    if (t >= until) return 1;
    dir = n;
  }
  return t;
}

// Two convex shapes.
Real convex_time_of_impact(const Shape& a, const Transform& xa0, const Transform& xa1,
                           const Shape& b, const Transform& xb0, const Transform& xb1,
                           Real target) {
  // Stop within this of the target distance; a floor relative to size keeps target 0 finite.
  const Real tolerance =
      std::max(Real(0.25) * target, Real(1e-4) * std::max(a.bounding_radius, b.bounding_radius));
  const Vec3 delta = (xa1.position - xa0.position) - (xb1.position - xb0.position);
  // A point at distance <= bounding_radius from the centre moves at most |omega| r by rotation.
  const Real spin = rotation_angle(xa0.rotation, xa1.rotation) * a.bounding_radius +
                    rotation_angle(xb0.rotation, xb1.rotation) * b.bounding_radius;
  const SlerpArc arc_a = make_slerp_arc(xa0.rotation, xa1.rotation);
  const SlerpArc arc_b = make_slerp_arc(xb0.rotation, xb1.rotation);
  const auto distance = [&](Real t, const Vec3& dir, const SweepBound& bound) {
    const Transform xa = pose_at(xa0, xa1, arc_a, t), xb = pose_at(xb0, xb1, arc_b, t);
    Simplex s;
    return gjk_placed(place(a, xa, true), place(b, xb, true), dir, s, bound);
  };
  // GJK's relative tolerance on the sizes and motion, and the rounding of world coordinates.
  const Real margin =
      Real(1e-4) * (a.bounding_radius + b.bounding_radius + target + delta.cwiseAbs().sum()) +
      Real(1e-6) * (xa0.position.cwiseAbs().sum() + xb0.position.cwiseAbs().sum());
  return advance(distance, delta, spin, target, tolerance, margin,
                 Vec3(xb0.position - xa0.position));
}

Transform relative_to(const Transform& frame, const Transform& x) {
  const Quat to_frame = frame.rotation.conjugate();
  return {to_frame * (x.position - frame.position), to_frame * x.rotation};
}

// Whether two convex pieces of bounding radii ra and rb, whose origins move on the lines a0 -> a1
// and b0 -> b1 (as pose_at moves them), stay farther apart than `target` plus
// convex_time_of_impact's tolerance over the whole interval: each piece lies within its bounding
// sphere about its origin whatever it turns, so the distance is at least the closest approach of
// the two centres, min over t of |c0 + t d| (c0 the offset at t = 0, d its change), less the two
// radii. perf: a compound's parts are mostly far from the other body's parts; this spares their
// conservative advancement, whose answer for such a pair is no impact. `widen` scales the reach.
bool pieces_stay_apart(Real ra, const Vec3& a0, const Vec3& a1, Real rb, const Vec3& b0,
                       const Vec3& b1, Real target, Real widen = 1) {
  const Real tolerance = std::max(Real(0.25) * target, Real(1e-4) * std::max(ra, rb));
  const Vec3 c0 = b0 - a0;
  const Vec3 d = (b1 - a1) - c0;
  const Real dd = d.squaredNorm();
  const Real t = dd > 0 ? std::clamp(-c0.dot(d) / dd, Real(0), Real(1)) : Real(0);
  // A margin of a part in a thousand of the reach for the rounding of the closest approach, and
  // one that grows with the coordinates for the advancement's own, which works in world
  // coordinates (far from the origin a millimetre is a few ulps).
  const Real reach =
      widen * ((ra + rb + target + tolerance) * Real(1.001) +
               Real(1e-6) * (a0.cwiseAbs().sum() + b0.cwiseAbs().sum() + d.cwiseAbs().sum()));
  return (c0 + t * d).squaredNorm() > reach * reach;
}

// Convex A against the triangles of surface B (mesh or heightfield) under A's swept box, in B's
// frame: the earliest impact, or 1.
Real surface_time_of_impact(const Shape& a, const Transform& xa0, const Transform& xa1,
                            const Shape& b, const Transform& xb0, const Transform& xb1,
                            Real target) {
  const Transform p0 = relative_to(xb0, xa0), p1 = relative_to(xb1, xa1);
  const Real tolerance = std::max(Real(0.25) * target, Real(1e-4) * a.bounding_radius);
  const Vec3 delta = p1.position - p0.position;
  // B's own turn moves A's points in B's frame by at most its angle times their distance from
  // B's origin, which is no more than A's centre's farthest distance plus A's radius.
  const Real reach = std::max(p0.position.norm(), p1.position.norm()) + a.bounding_radius;
  const Real spin = rotation_angle(p0.rotation, p1.rotation) * a.bounding_radius +
                    rotation_angle(xb0.rotation, xb1.rotation) * reach;
  const Vec3 grow = Vec3::Constant(a.bounding_radius + target);
  const Vec3 lo = p0.position.cwiseMin(p1.position) - grow;
  const Vec3 hi = p0.position.cwiseMax(p1.position) + grow;
  // A's points stay within its bounding radius of its centre, which runs along the segment p0 p1
  // at every pose advance() tries; a triangle farther than this from that segment is never within
  // the target. The relative margin covers the rounding of the distances below (coordinates of a
  // few hundred metres round to about 1e-5 m), so that nothing the advancement would stop at is
  // passed over.
  const Real margin = Real(1e-4) * (a.bounding_radius + target + delta.cwiseAbs().sum() +
                                    p0.position.cwiseAbs().sum());
  const Real clear = a.bounding_radius + target + tolerance + margin;
  // perf: every triangle's advancement starts at t = 0, where A's pose and placement are the
  // same for all: made once (the same computation, so the same bits).
  const SlerpArc arc = make_slerp_arc(p0.rotation, p1.rotation);
  const Transform start = pose_at(p0, p1, arc, 0);
  const PlacedShape placed_start = place(a, {Vec3::Zero(), start.rotation}, true);
  Real best = 1;
  const auto visit = [&](const MeshTriangle& tri) {
    // A one-sided triangle stops only what comes from its front.
    const Vec3 n = tri.normal();
    if (!tri.two_sided && n.dot(p0.position - tri.v[0]) < 0) return;
    // perf: the swept box holds many triangles the segment passes far from. Two tests bound the
    // segment's distance to the triangle from below: both ends on one side of its plane and
    // farther than `clear` from it, or both beyond the plane through one edge along the normal
    // (the triangle lies on the other side of it) by more than `clear`.
    // Only the path up to the earliest impact found so far can give an earlier one.
    const Vec3 ahead = best * delta;
    const Vec3 w0 = tri.v[0] - p0.position;
    const Real h0 = -n.dot(w0), h1 = n.dot(ahead) + h0;
    if ((h0 > clear && h1 > clear) || (h0 < -clear && h1 < -clear)) return;
    for (int k = 0; k < 3; ++k) {
      const Vec3 from = tri.v[k] - p0.position;
      const Vec3 out = (tri.v[(k + 1) % 3] - tri.v[k]).cross(n);  // outward for v's winding
      const Real reach = clear * out.norm();
      const Real b0 = -out.dot(from), b1 = out.dot(ahead) + b0;
      if (b0 > reach && b1 > reach) return;
    }
    const auto distance = [&](Real t, const Vec3& dir, const SweepBound& bound) {
      Simplex s;
      if (t == 0) {
        const Vec3 v[3] = {tri.v[0] - start.position, tri.v[1] - start.position,
                           tri.v[2] - start.position};
        return gjk_triangle(placed_start, v, dir, s, bound);
      }
      const Transform x = pose_at(p0, p1, arc, t);
      const Vec3 v[3] = {tri.v[0] - x.position, tri.v[1] - x.position, tri.v[2] - x.position};
      return gjk_triangle(place(a, {Vec3::Zero(), x.rotation}, true), v, dir, s, bound);
    };
    const Vec3 towards = (tri.v[0] + tri.v[1] + tri.v[2]) / 3 - p0.position;
    best = std::min(best, advance(distance, delta, spin, target, tolerance, margin, towards, best));
  };
  if (b.type == ShapeType::Mesh) {
    for_each_triangle(*b.mesh, lo, hi, visit);
  } else {
    // perf: the advancement reads a triangle's corners, not its active edges.
    const HeightField& field = *b.heightfield;
    for_each_triangle_index(field, lo, hi, [&](uint32_t t) { visit(field.corners(t)); });
  }
  return best;
}

// Convex A against B of any kind but a plane.
Real piece_time_of_impact(const Shape& a, const Transform& xa0, const Transform& xa1,
                          const Shape& b, const Transform& xb0, const Transform& xb1, Real target) {
  if (is_surface(b)) return surface_time_of_impact(a, xa0, xa1, b, xb0, xb1, target);
  if (b.type != ShapeType::Compound) {
    return convex_time_of_impact(a, xa0, xa1, b, xb0, xb1, target);
  }
  // perf: a compound's parts are mostly far from a part of the other body. At every pose the
  // advancement tries, each part's origin (on the line between its poses at the ends) is within
  // |its offset| of B's origin (on B's line), by the triangle inequality, and B's bounding radius
  // holds the offset and the part's radius: so the whole compound's test bounds every part's
  // from below. Widened by a part in a hundred, far beyond the rounding of either, it skips only
  // parts whose own test would skip them too: the same impacts.
  if (pieces_stay_apart(a.bounding_radius, xa0.position, xa1.position, b.bounding_radius,
                        xb0.position, xb1.position, target, Real(1.01))) {
    return 1;
  }
  Real best = 1;
  // determinism: every part in the compound's order; the minimum does not depend on it anyway.
  for (const CompoundPart& part : b.compound->parts) {
    const Transform p0 = compose(xb0, part.pose), p1 = compose(xb1, part.pose);
    if (pieces_stay_apart(a.bounding_radius, xa0.position, xa1.position, part.shape.bounding_radius,
                          p0.position, p1.position, target)) {
      continue;
    }
    best = std::min(best, convex_time_of_impact(a, xa0, xa1, part.shape, p0, p1, target));
  }
  return best;
}

}  // namespace

Real time_of_impact(const Shape& a, const Transform& xa0, const Transform& xa1, const Shape& b,
                    const Transform& xb0, const Transform& xb1, Real target) {
  if (is_convex(a) && is_convex(b)) {
    return convex_time_of_impact(a, xa0, xa1, b, xb0, xb1, target);
  }
  // Two static shapes, or a half-space (whose contact exists wherever the body ends): no impact.
  if ((is_surface(a) && is_surface(b)) || a.type == ShapeType::Plane ||
      b.type == ShapeType::Plane) {
    return 1;
  }
  // Time of impact is symmetric: the surface or the compound goes second.
  if (is_surface(a) || (a.type == ShapeType::Compound && is_convex(b))) {
    return time_of_impact(b, xb0, xb1, a, xa0, xa1, target);
  }
  if (a.type != ShapeType::Compound) {
    return piece_time_of_impact(a, xa0, xa1, b, xb0, xb1, target);
  }
  // A compound: each part's path is the line between its poses at the ends.
  Real best = 1;
  for (const CompoundPart& part : a.compound->parts) {
    const Transform p0 = compose(xa0, part.pose), p1 = compose(xa1, part.pose);
    best = std::min(best, piece_time_of_impact(part.shape, p0, p1, b, xb0, xb1, target));
  }
  return best;
}

}  // namespace elan::detail
