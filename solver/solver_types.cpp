// SPDX-License-Identifier: MIT
// The solver's shared closed forms (solver_types.hpp). Outside the per-level units
// (core/base/isa.hpp): every path and the joint solver share this one copy.
#include "solver/solver_types.hpp"

#include <cmath>

namespace elan::detail {

SymMat3 rotate_diagonal(const Quat& q, const Vec3& d) {
  const Mat3 r = q.toRotationMatrix();
  SymMat3 m;
  // (R D R^T)_ij = sum_k R_ik d_k R_jk
  m.xx = r(0, 0) * d.x() * r(0, 0) + r(0, 1) * d.y() * r(0, 1) + r(0, 2) * d.z() * r(0, 2);
  m.yy = r(1, 0) * d.x() * r(1, 0) + r(1, 1) * d.y() * r(1, 1) + r(1, 2) * d.z() * r(1, 2);
  m.zz = r(2, 0) * d.x() * r(2, 0) + r(2, 1) * d.y() * r(2, 1) + r(2, 2) * d.z() * r(2, 2);
  m.xy = r(0, 0) * d.x() * r(1, 0) + r(0, 1) * d.y() * r(1, 1) + r(0, 2) * d.z() * r(1, 2);
  m.xz = r(0, 0) * d.x() * r(2, 0) + r(0, 1) * d.y() * r(2, 1) + r(0, 2) * d.z() * r(2, 2);
  m.yz = r(1, 0) * d.x() * r(2, 0) + r(1, 1) * d.y() * r(2, 1) + r(1, 2) * d.z() * r(2, 2);
  return m;
}

Softness make_softness(Real hertz, Real damping_ratio, Real h) {
  if (hertz == 0) return {0, 1, 0};
  // Catto, "Solver2D" (2024): a damped spring of angular frequency omega integrated implicitly
  // over h becomes bias_rate = omega / (2 zeta + h omega), mass_scale = a2 / (1 + a2),
  // impulse_scale = 1 / (1 + a2) with a2 = h omega (2 zeta + h omega).
  const Real omega = Real(2 * M_PI) * hertz;
  const Real a1 = 2 * damping_ratio + h * omega;
  const Real a2 = h * omega * a1;
  const Real a3 = 1 / (1 + a2);
  return {omega / a1, a2 * a3, a3};
}

}  // namespace elan::detail
