// SPDX-License-Identifier: MIT
// Spherical linear interpolation of unit quaternions through the engine's own trigonometry.
// determinism (rule 7): Eigen's Quaternion::slerp calls the C library's acos and sin, whose last
// bits change with the library and with the variant it picks at run time for the CPU (FMA or
// not). This is the same formula (Shoemake, "Animating rotation with quaternion curves", 1985)
// and the same short-arc and near-parallel cases as Eigen's, through fixed_acos and fixed_sin in
// double, so a time of impact's pose has the same bits on every build and CPU.
#pragma once

#include <elan/math.hpp>

#include <cmath>
#include <limits>

#include "core/base/fixed_math.hpp"

namespace elan::detail {

// q(t) = (sin((1 - t) theta) q0 + sin(t theta) q1') / sin theta, cos theta = |q0.q1|, where q1'
// is q1 or -q1, whichever is on q0's side (the shorter arc). Within Real's epsilon of parallel,
// where sin theta loses its digits, the straight line (1 - t) q0 + t q1' instead (the two agree
// there to that epsilon). The result is unit when q0 and q1 are (up to their rounding).
// The arc is made once for the many poses a time of impact tries along it.
struct SlerpArc {
  Quat q0, q1;       // q1 already on q0's side
  double theta = 0;  // the angle between them, 0 on the straight-line case
  double sin_theta = 0;
};

inline SlerpArc make_slerp_arc(const Quat& q0, const Quat& q1) {
  SlerpArc arc{q0, q1};
  const double d = double(q0.dot(q1));
  if (d < 0) arc.q1.coeffs() = -q1.coeffs();
  const double c = std::abs(d);
  if (c < 1 - double(std::numeric_limits<Real>::epsilon())) {
    arc.theta = fixed_acos(c);
    arc.sin_theta = fixed_sin(arc.theta);
  }
  return arc;
}

inline Quat slerp_at(const SlerpArc& arc, Real t) {
  const double u = double(t);
  double s0 = 1 - u, s1 = u;
  if (arc.theta > 0) {
    s0 = fixed_sin((1 - u) * arc.theta) / arc.sin_theta;
    s1 = fixed_sin(u * arc.theta) / arc.sin_theta;
  }
  return Quat(Real(s0) * arc.q0.coeffs() + Real(s1) * arc.q1.coeffs());
}

inline Quat fixed_slerp(const Quat& q0, Real t, const Quat& q1) {
  return slerp_at(make_slerp_arc(q0, q1), t);
}

}  // namespace elan::detail
