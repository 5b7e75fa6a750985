// Substep integration of the solver packets.
#include "solver/integrate.hpp"

#include <cmath>

namespace elan::detail {

Quat rotation_from_angular_velocity(const Vec3& w, Real h) {
  const Real angle = w.norm() * h;
  if (angle < Real(1e-6)) {
    // Second-order series of the exponential map, normalised: avoids 0/0 for tiny rotations.
    Quat q(1, Real(0.5) * h * w.x(), Real(0.5) * h * w.y(), Real(0.5) * h * w.z());
    q.normalize();
    return q;
  }
  const Vec3 axis = w / w.norm();
  const Real s = std::sin(Real(0.5) * angle);
  return Quat(std::cos(Real(0.5) * angle), s * axis.x(), s * axis.y(), s * axis.z());
}

void integrate_velocities(std::span<SolverBody> packets, std::span<const SolverBodyParams> params,
                          Real h, uint32_t begin, uint32_t end) {
  for (uint32_t i = begin; i < end; ++i) {
    const SolverBodyParams& p = params[i];
    if (p.inv_mass == 0) continue;  // kinematic: moves with its given velocities
    SolverBody& b = packets[i];
    b.v = (b.v + h * p.delta_v_per_s) / (1 + h * p.linear_damping);
    b.w = (b.w + h * p.delta_w_per_s) / (1 + h * p.angular_damping);
  }
}

void integrate_positions(std::span<SolverBody> packets, std::span<SolverBodyParams> params,
                         const BodyStore& bodies, Real h, uint32_t begin, uint32_t end) {
  for (uint32_t i = begin; i < end; ++i) {
    SolverBody& b = packets[i];
    SolverBodyParams& p = params[i];
    b.dp += h * b.v;
    b.dtheta += h * b.w;
    if (!p.gyroscopic) {
      b.dq = (rotation_from_angular_velocity(b.w, h) * b.dq).normalized();
      continue;
    }
    // Midpoint rule on the rotation group with L fixed (second order and symmetric, so the
    // energy error stays bounded instead of drifting as with a first-order update):
    //   L = I(q) w,  q_mid = exp(h/2 w) q,  w_mid = I(q_mid)^-1 L,  q' = exp(h w_mid) q,
    //   w' = I(q')^-1 L.
    const Quat q0 = bodies.orientation(p.body);
    const Quat before = b.dq * q0;
    const Vec3& d = p.inertia;
    const Vec3 l_world = before * d.cwiseProduct(before.conjugate() * b.w);
    const Quat mid = (rotation_from_angular_velocity(b.w, Real(0.5) * h) * before).normalized();
    const Vec3 w_mid = mid * (mid.conjugate() * l_world).cwiseQuotient(d);
    b.dq = (rotation_from_angular_velocity(w_mid, h) * b.dq).normalized();
    const Quat after = b.dq * q0;
    b.w = after * (after.conjugate() * l_world).cwiseQuotient(d);
    // Impulses from here on change w through the inertia of the current orientation, so that
    // the L read back above next substep grows by exactly r x P.
    p.inv_inertia = rotate_diagonal(after, d.cwiseInverse());
  }
}

}  // namespace elan::detail
