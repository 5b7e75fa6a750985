// SPDX-License-Identifier: MIT
// Time of impact by conservative advancement (Mirtich 1996, "Impulse-based dynamic simulation of
// rigid body systems", 4.3): step time forward by distance / (bound on the approach speed).
#include <cmath>
#include <limits>

#include "narrowphase/collide.hpp"
#include "narrowphase/minkowski.hpp"

namespace elan::detail {
namespace {

constexpr int kMaxIterations = 64;

Transform pose_at(const Transform& x0, const Transform& x1, Real t) {
  Transform x;
  x.position = x0.position + t * (x1.position - x0.position);
  x.rotation = x0.rotation.slerp(t, x1.rotation);
  return x;
}

// Rotation angle from q0 to q1 along the shorter arc: |omega| over the unit interval.
Real rotation_angle(const Quat& q0, const Quat& q1) {
  const Real c = std::min(std::abs(q0.dot(q1)), Real(1));
  return 2 * std::acos(c);
}

}  // namespace

Real time_of_impact(const Shape& a, const Transform& xa0, const Transform& xa1, const Shape& b,
                    const Transform& xb0, const Transform& xb1, Real target) {
  // Stop within this of the target distance; a floor relative to size keeps target 0 finite.
  const Real tolerance =
      std::max(Real(0.25) * target, Real(1e-4) * std::max(a.bounding_radius, b.bounding_radius));
  const Vec3 delta = (xa1.position - xa0.position) - (xb1.position - xb0.position);
  // A point at distance <= bounding_radius from the centre moves at most |omega| r by rotation.
  const Real spin = rotation_angle(xa0.rotation, xa1.rotation) * a.bounding_radius +
                    rotation_angle(xb0.rotation, xb1.rotation) * b.bounding_radius;
  Real t = 0;
  Vec3 dir = xb0.position - xa0.position;
  for (int iter = 0; iter < kMaxIterations; ++iter) {
    const Transform xa = pose_at(xa0, xa1, t), xb = pose_at(xb0, xb1, t);
    const GjkResult g = gjk_distance(a, xa, b, xb, true, &dir);
    if (g.overlap || g.distance <= target + tolerance) return t;
    const Vec3 n = (g.point_b - g.point_a) / g.distance;
    // Along the fixed axis n the gap closes no faster than the relative velocity's component
    // plus the rotational bound, so advancing by (distance - target) / speed cannot overshoot.
    const Real speed = delta.dot(n) + spin;
    if (!(speed > 0)) return 1;
    t += (g.distance - target) / speed;
    if (t >= 1) return 1;
    dir = n;
  }
  return t;
}

}  // namespace elan::detail
