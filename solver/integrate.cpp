// SPDX-License-Identifier: MIT
// Substep integration of the solver packets.
#include "solver/integrate.hpp"

#include <algorithm>
#include <cmath>

#include "core/base/fixed_math.hpp"
#include "solver/body_lanes.hpp"

namespace elan::detail {
ELAN_ISA_BEGIN

void integrate_velocities(std::span<SolverBody> packets, std::span<const SolverBodyMass> masses,
                          const BodyStore& bodies, const Vec3& gravity, Real h, uint32_t begin,
                          uint32_t end) {
  for (uint32_t k = begin; k < end; ++k) {
    const SolverBodyMass& m = masses[k];
    if (m.inv_mass == 0) continue;  // kinematic: moves with its given velocities
    const uint32_t i = m.body;
    const Vec3 force = bodies.force(i);
    const Vec3 torque = bodies.torque(i);
    const BodyTraits& traits = bodies.traits_of(i);
    // A gravity scale of 1 (the default) multiplies exactly: the same bits as gravity alone.
    const Vec3 delta_v_per_s = traits.gravity_scale * gravity + m.inv_mass * force;
    const Vec3 delta_w_per_s = m.inv_inertia * torque;
    SolverBody& b = packets[k];
    b.v = (b.v + h * delta_v_per_s) / (1 + h * traits.linear_damping);
    b.w = (b.w + h * delta_w_per_s) / (1 + h * traits.angular_damping);
  }
}

namespace {

// Quaternions across the lanes, with the operations the integrator needs (Hamilton product,
// rotation of a vector, normalisation). Each lane runs the same formulas in the same order
// whatever the lane width, so a body's bits do not depend on its lane.
struct WideQuat {
  Wide w{}, x{}, y{}, z{};
};

WideQuat operator*(const WideQuat& a, const WideQuat& b) {
  return {
      a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
      a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

WideQuat normalized(const WideQuat& q) {
  const Wide inv = 1 / wide_sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {q.w * inv, q.x * inv, q.y * inv, q.z * inv};
}

// q v q^-1 = v + 2 w (u x v) + 2 u x (u x v), u = vec(q); `sign` -1 rotates by q^-1.
WideVec3 rotate(const WideQuat& q, const WideVec3& v, Real sign = 1) {
  const WideVec3 u{sign * q.x, sign * q.y, sign * q.z};
  const WideVec3 t = splat(2) * cross(u, v);
  return v + q.w * t + cross(u, t);
}

WideVec3 cwise_product(const WideVec3& a, const WideVec3& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
WideVec3 cwise_quotient(const WideVec3& a, const WideVec3& b) {
  return {a.x / b.x, a.y / b.y, a.z / b.z};
}

// Per lane: a where the mask is set, else b.
WideQuat select(WideMask m, const WideQuat& a, const WideQuat& b) {
  return {m ? a.w : b.w, m ? a.x : b.x, m ? a.y : b.y, m ? a.z : b.z};
}

bool all_of(WideMask m, int count) {
  for (int l = 0; l < count; ++l) {
    if (!m[l]) return false;
  }
  return true;
}

// The rotation by angle |w| h about w, lane by lane: q = (cos x, sin(x)/x (h/2) w) with
// x = |w| h / 2. Both cos and sin(x)/x are even, so they are series in y = x^2 = |w|^2 h^2 / 4,
// here Taylor to y^4: for x <= 1/2 the first term left out is y^5 / 10! < 3e-10, far below float
// rounding. No square root, no division, no libm, and the same bits on every platform (libm's sin
// and cos are not). Lanes that turn faster (|w| > 1/h: 240 rad/s at 4 substeps of 60 Hz) take
// the engine's own sine and cosine (core/base/fixed_math.hpp), for the same reason.
WideQuat exp_map(const WideVec3& w, Real h) {
  const Wide y = Real(0.25) * h * h * dot(w, w);
  const Wide cos_x = 1 - y * (Real(1.0 / 2) -
                              y * (Real(1.0 / 24) - y * (Real(1.0 / 720) - y * Real(1.0 / 40320))));
  const Wide sinc_x =
      1 -
      y * (Real(1.0 / 6) - y * (Real(1.0 / 120) - y * (Real(1.0 / 5040) - y * Real(1.0 / 362880))));
  WideQuat q{cos_x, Wide{}, Wide{}, Wide{}};
  Wide k = Real(0.5) * h * sinc_x;
  const WideMask fast = y > Real(0.25);
  if (any_lane(fast)) {
    for (int l = 0; l < kLanes; ++l) {
      if (!fast[l]) continue;
      const Real x = std::sqrt(y[l]);
      const FixedSinCos sc = fixed_sin_cos(x);
      q.w[l] = Real(sc.cos);
      k[l] = Real(sc.sin) / x * Real(0.5) * h;
    }
  }
  q.x = k * w.x;
  q.y = k * w.y;
  q.z = k * w.z;
  return q;
}

// rotate_diagonal() across the lanes: R diag(d) R^T with R from the unit quaternion q.
WideSym3 rotate_diagonal(const WideQuat& q, const WideVec3& d) {
  const Wide tx = 2 * q.x, ty = 2 * q.y, tz = 2 * q.z;
  const Wide r00 = 1 - (ty * q.y + tz * q.z), r11 = 1 - (tx * q.x + tz * q.z);
  const Wide r22 = 1 - (tx * q.x + ty * q.y);
  const Wide r01 = tx * q.y - tz * q.w, r10 = tx * q.y + tz * q.w;
  const Wide r02 = tx * q.z + ty * q.w, r20 = tx * q.z - ty * q.w;
  const Wide r12 = ty * q.z - tx * q.w, r21 = ty * q.z + tx * q.w;
  // (R D R^T)_ij = sum_k R_ik d_k R_jk
  const WideVec3 row0{r00, r01, r02}, row1{r10, r11, r12}, row2{r20, r21, r22};
  const WideVec3 d0 = cwise_product(d, row0), d1 = cwise_product(d, row1);
  const WideVec3 d2 = cwise_product(d, row2);
  return {dot(d0, row0), dot(d1, row1), dot(d2, row2), dot(d0, row1), dot(d0, row2), dot(d1, row2)};
}

void set_lane(WideQuat& q, int l, const Quat& value) {
  q.w[l] = value.w();
  q.x[l] = value.x();
  q.y[l] = value.y();
  q.z[l] = value.z();
}
Quat lane(const WideQuat& q, int l) {
  return Quat(q.w[l], q.x[l], q.y[l], q.z[l]);
}

}  // namespace

Quat rotation_from_angular_velocity(const Vec3& w, Real h) {
  WideVec3 lanes;
  set_lane(lanes, 0, w);
  return lane(exp_map(lanes, h), 0);
}

namespace {

// The midpoint rule below is accurate while a body turns by a small angle per update; at a few
// radians per update (1,000 rad/s at 1/240 s turns 4.2 rad) its error is no longer small and the
// discrete map drives even a spin about the major axis towards the minor one, which with L held
// raises the energy L^2 / (2 I) by up to I_max / I_min. A faster body is integrated in pieces of
// at most this angle, and at most kMaxSpinPieces of them, so an absurd spin costs a bounded time.
constexpr Real kMaxTurnPerPiece = Real(0.25);  // rad
constexpr int kMaxSpinPieces = 256;

// One gyroscopic substep of a fast-spinning body by the same midpoint rule as the lanes, in
// pieces (see above); returns the new dq, and the new w and world inverse inertia through the
// references. determinism: per body, whichever lane or block it came in.
// Whatever the piece size, the torque-free energy E = w . L / 2 cannot grow: should the pieces
// still end at a higher energy (a spin too fast for kMaxSpinPieces), w is scaled back to the
// energy it started with. That shortens L along itself, by the same factor; the scene is then
// outside what the step resolves, and losing energy, never gaining it, is the safe side.
Quat spin_in_pieces(const Quat& dq, const Quat& q0, const Vec3& d, Real h, Vec3& w,
                    SymMat3& inv_inertia) {
  const Quat before = (dq * q0).normalized();
  const Vec3 l_world = before * d.cwiseProduct(before.conjugate() * w);
  const Real e_start = w.dot(l_world);
  // Compared as a Real first: an infinite or NaN turn (a body going non-finite, quarantined after
  // the step) takes the most pieces instead of an undefined conversion to int.
  const Real turn_pieces = std::ceil(w.norm() * h / kMaxTurnPerPiece);
  const int pieces =
      turn_pieces < Real(kMaxSpinPieces) ? std::max(1, int(turn_pieces)) : kMaxSpinPieces;
  const Real hp = h / Real(pieces);
  Quat turned = dq, after = before;
  Vec3 wc = w;
  for (int k = 0; k < pieces; ++k) {
    const Quat mid = (rotation_from_angular_velocity(wc, Real(0.5) * hp) * after).normalized();
    const Vec3 w_mid = mid * (mid.conjugate() * l_world).cwiseQuotient(d);
    turned = (rotation_from_angular_velocity(w_mid, hp) * turned).normalized();
    after = (turned * q0).normalized();
    wc = after * (after.conjugate() * l_world).cwiseQuotient(d);
  }
  const Real e_end = wc.dot(l_world);
  if (e_end > e_start && e_end > 0) wc *= std::sqrt(std::max(e_start, Real(0)) / e_end);
  w = wc;
  const Mat3 r = after.toRotationMatrix();
  const Mat3 m = r * d.cwiseInverse().asDiagonal() * r.transpose();
  inv_inertia = {m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(0, 2), m(1, 2)};
  return turned;
}

}  // namespace

// perf: kLanes packets at once: the gyroscopic update is two exponentials, six rotations and an
// inertia per body and substep.
void integrate_positions(std::span<SolverBody> packets, std::span<SolverBodyMass> masses,
                         const BodyStore& bodies, Real h, uint32_t begin, uint32_t end) {
  for (uint32_t first = begin; first < end; first += kLanes) {
    const int count = int(std::min<uint32_t>(kLanes, end - first));
    // Unused lanes repeat the last packet (gather_packets), with unit inertia and no gyroscopic
    // term; they are not stored.
    Wide cols[16];
    gather_packets(&packets[first], count, cols);
    const WideVec3 v{cols[0], cols[1], cols[2]};
    WideVec3 w{cols[3], cols[4], cols[5]}, dp{cols[6], cols[7], cols[8]};
    WideVec3 dtheta{cols[9], cols[10], cols[11]}, d{splat(1), splat(1), splat(1)};
    const WideQuat dq{cols[15], cols[12], cols[13], cols[14]};
    WideQuat q0{splat(1), Wide{}, Wide{}, Wide{}};
    Wide gyroscopic{};
    for (int l = 0; l < count; ++l) {
      const SolverBodyMass& m = masses[first + l];
      if (m.gyroscopic) {
        gyroscopic[l] = 1;
        set_lane(d, l, principal_moments(bodies, m.body));
        set_lane(q0, l, bodies.orientation(m.body));
      }
    }
    dp = dp + splat(h) * v;
    dtheta = dtheta + splat(h) * w;
    const WideMask gyro = gyroscopic != 0;
    WideQuat next = dq;
    if (!all_of(gyro, count)) next = normalized(exp_map(w, h) * dq);
    if (any_lane(gyro)) {
      // Midpoint rule on the rotation group with L fixed (second order and symmetric, so the
      // energy error stays bounded instead of drifting as with a first-order update):
      //   L = I(q) w,  q_mid = exp(h/2 w) q,  w_mid = I(q_mid)^-1 L,  q' = exp(h w_mid) q,
      //   w' = I(q')^-1 L.
      const WideQuat before = dq * q0;
      const WideVec3 l_world = rotate(before, cwise_product(d, rotate(before, w, -1)));
      const WideQuat mid = normalized(exp_map(w, Real(0.5) * h) * before);
      const WideVec3 w_mid = rotate(mid, cwise_quotient(rotate(mid, l_world, -1), d));
      const WideQuat turned = normalized(exp_map(w_mid, h) * dq);
      const WideQuat after = turned * q0;
      const WideVec3 w_after = rotate(after, cwise_quotient(rotate(after, l_world, -1), d));
      next = select(gyro, turned, next);
      w = select(gyro, w_after, w);
      // Impulses from here on change w through the inertia of the current orientation, so
      // that the L read back above next substep grows by exactly r x P.
      const WideSym3 inv_inertia = rotate_diagonal(after, {1 / d.x, 1 / d.y, 1 / d.z});
      for (int l = 0; l < count; ++l) {
        if (!gyro[l]) continue;
        SymMat3& m = masses[first + l].inv_inertia;
        const Vec3 w0 = packets[first + l].w;
        if (w0.squaredNorm() * h * h > kMaxTurnPerPiece * kMaxTurnPerPiece) {
          Vec3 w1 = w0;
          const Quat q = spin_in_pieces(packets[first + l].dq, lane(q0, l), lane(d, l), h, w1, m);
          set_lane(next, l, q);
          set_lane(w, l, w1);
          continue;
        }
        m = {inv_inertia.xx[l], inv_inertia.yy[l], inv_inertia.zz[l],
             inv_inertia.xy[l], inv_inertia.xz[l], inv_inertia.yz[l]};
      }
    }
    const Wide out[16] = {v.x,  v.y,      v.z,      w.x,      w.y,    w.z,    dp.x,   dp.y,
                          dp.z, dtheta.x, dtheta.y, dtheta.z, next.x, next.y, next.z, next.w};
    scatter_packets(&packets[first], count, out);
  }
}

ELAN_ISA_END
}  // namespace elan::detail
