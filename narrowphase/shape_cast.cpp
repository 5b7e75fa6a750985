// SPDX-License-Identifier: MIT
// Shape cast by conservative advancement (toi.cpp) or, against a plane, in closed form; the
// contact at the time of impact and exact overlap from the collide routines.
#include "narrowphase/shape_cast.hpp"

#include <algorithm>
#include <cmath>

#include "core/base/compound.hpp"
#include "core/base/contact.hpp"
#include "narrowphase/collide.hpp"
#include "narrowphase/gjk.hpp"

namespace elan::detail {

namespace {

// A's farthest point along world direction d (A convex or compound), world.
Vec3 farthest_along(const Shape& a, const Transform& xa, const Vec3& d) {
  if (a.type == ShapeType::Compound) {
    Vec3 best = xa.position;
    Real best_h = -std::numeric_limits<Real>::infinity();
    for (const CompoundPart& part : a.compound->parts) {
      const Transform x{xa.rotation * part.pose.position + xa.position,
                        xa.rotation * part.pose.rotation};
      const Vec3 p = farthest_along(part.shape, x, d);
      if (p.dot(d) > best_h) {
        best_h = p.dot(d);
        best = p;
      }
    }
    return best;
  }
  return xa.position + xa.rotation * support(a, xa.rotation.conjugate() * d);
}

// Against the half-space n.x <= level: A's lowest point s along n is at height h = n.s - level,
// which falls at the rate -n.translation, so A comes within target at
// t = (h - target) / (-n.translation): exact for a pure translation.
bool plane_cast(const Shape& a, const Transform& xa, const Vec3& translation, const Shape& b,
                const Transform& xb, Real target, CastContact& out) {
  const Vec3 n = (xb.rotation * b.plane_normal).normalized();
  const Real level = n.dot(xb.position) + b.plane_offset;
  const Vec3 s = farthest_along(a, xa, -n);
  const Real h = n.dot(s) - level;
  Real t = 0;
  if (h > target) {
    const Real closing = -n.dot(translation);
    if (!(closing > 0) || h - target > closing) return false;
    t = (h - target) / closing;
  }
  out.fraction = t;
  out.normal = n;
  const Vec3 at = s + t * translation;
  out.point = at - (n.dot(at) - level) * n;
  return true;
}

}  // namespace

bool contact_normal(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                    Real gap, Vec3& normal, Vec3& point) {
  Manifold m;
  if (collide(a, xa, b, xb, gap, m) && m.point_count > 0) {
    uint32_t deepest = 0;
    for (uint32_t k = 1; k < m.point_count; ++k) {
      if (m.points[k].separation < m.points[deepest].separation) deepest = k;
    }
    normal = -m.normal;
    // The manifold's point is A's; B's surface lies `separation` along the normal (A to B).
    point = xa.position + m.points[deepest].anchor_a + m.points[deepest].separation * m.normal;
    return true;
  }
  if (is_convex(a) && is_convex(b)) {
    const GjkResult g = gjk_distance(a, xa, b, xb);
    if (g.overlap || !(g.distance <= gap) || !(g.distance > 0)) return false;
    normal = (g.point_a - g.point_b) / g.distance;
    point = g.point_b;
    return true;
  }
  return false;
}

bool shape_cast(const Shape& a, const Transform& xa, const Vec3& translation, const Shape& b,
                const Transform& xb, Real target, CastContact& out) {
  if (b.type == ShapeType::Plane) return plane_cast(a, xa, translation, b, xb, target, out);
  const Transform xa1{xa.position + translation, xa.rotation};
  const Real t = time_of_impact(a, xa, xa1, b, xb, xb, target);
  if (!(t < 1)) return false;
  out.fraction = t;
  const Transform at{xa.position + t * translation, xa.rotation};
  // The advancement stops within max(target / 4, 1e-4 r) of the target: look that far and more.
  const Real r = std::max(a.bounding_radius, b.bounding_radius);
  const Real gap = target * Real(1.5) + Real(2e-4) * r + Real(1e-4);
  if (!contact_normal(a, at, b, xb, gap, out.normal, out.point)) {
    // Only when the advancement's tolerance and the contact routines disagree at the very edge
    // of the gap: the direction of travel is the best estimate of the surface's.
    const Real len = translation.norm();
    out.normal = len > 0 ? Vec3(-translation / len) : Vec3::UnitY();
    out.point = farthest_along(a, at, -out.normal);
  }
  return true;
}

bool shapes_overlap(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  if (is_convex(a) && is_convex(b)) {
    const GjkResult g = gjk_distance(a, xa, b, xb);
    return g.overlap || g.distance <= 0;
  }
  Manifold m;
  if (!collide(a, xa, b, xb, 0, m)) return false;
  for (uint32_t k = 0; k < m.point_count; ++k) {
    if (m.points[k].separation <= 0) return true;
  }
  return false;
}

}  // namespace elan::detail
