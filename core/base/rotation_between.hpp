// SPDX-License-Identifier: MIT
// The shortest rotation taking one direction to another, in the engine's own fixed operations.
#pragma once

#include <algorithm>
#include <cmath>

#include "elan/math.hpp"

namespace elan::detail {

// The unit quaternion turning direction `from` onto direction `to` by the smallest angle.
// q = (s/2, (a x b)/s) with s = sqrt(2 (1 + a.b)) for unit a, b: the half-angle formulas
// cos(t/2) = sqrt((1 + cos t)/2), sin(t/2) = sin t / (2 cos(t/2)). These are the operations of
// Eigen's Quaternion::FromTwoVectors in the same order, so results are unchanged where it took
// them. determinism (rule 7): near-opposite directions Eigen takes the axis from a JacobiSVD, whose
// Householder steps use fused multiply-add where the target has FMA, so the bits would depend on
// the build; here the turn is by pi about a fixed choice of axis normal to `from` (unitOrthogonal:
// plain products and one square root).
inline Quat rotation_between(const Vec3& from, const Vec3& to) {
  const Vec3 a = from.normalized(), b = to.normalized();
  Real c = b.dot(a);
  // Eigen's bound for "opposite" (1e-5 in float, 1e-12 in double), so its choices are kept.
  if (c < Real(-1) + Eigen::NumTraits<Real>::dummy_precision()) {
    c = std::max(c, Real(-1));
    const Vec3 axis = a.unitOrthogonal();
    const Real w2 = (1 + c) * Real(0.5);
    const Vec3 v = axis * std::sqrt(1 - w2);
    return Quat(std::sqrt(w2), v.x(), v.y(), v.z());
  }
  const Vec3 axis = a.cross(b);
  const Real s = std::sqrt((1 + c) * 2);
  const Real inv_s = 1 / s;
  const Vec3 v = axis * inv_s;
  return Quat(s * Real(0.5), v.x(), v.y(), v.z());
}

}  // namespace elan::detail
