// Soft-step contact solver: non-penetration with soft position correction, Coulomb friction with
// a circular cone, restitution from the pre-solve approach speed.
#include "solver/contact_solver.hpp"

#include <algorithm>
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

namespace {

// Radius of the contact patch that a point contact stands for, m: the twist friction of a
// manifold is at least mu * kTorsionPatch * sum(lambda_n). An ideal point contact has no
// torsional friction, so a sphere pinched between two bodies would spin about the normal for
// ever and keep its island awake; real contacts have a patch (MuJoCo's default torsional
// friction length is the same 5 mm).
constexpr Real kTorsionPatch = Real(0.005);

// Below these relative motions since the step's start refresh_contacts keeps a constraint's
// arms (m, rad): the angular momentum error left is at most this distance times the impulse.
constexpr Real kRefreshDistance = Real(1e-4);
constexpr Real kRefreshAngle = Real(1e-4);

// Relative velocity of B against A along a row with Jacobian [-d, -ra_d, d, rb_d].
inline Real row_velocity(const SolverBody& a, const SolverBody& b, const Vec3& d, const Vec3& ra_d,
                         const Vec3& rb_d) {
  return d.dot(b.v - a.v) + rb_d.dot(b.w) - ra_d.dot(a.w);
}

// Applies impulse `lambda` along a row: linear part along d, angular parts precomputed as
// I^-1 (r x d). Static and kinematic sides are read-only.
inline void apply_row(const ContactConstraint& c, SolverBody& a, SolverBody& b, const Vec3& d,
                      const Vec3& ia_ra_d, const Vec3& ib_rb_d, Real lambda) {
  if (c.write_a) {
    a.v -= (c.inv_mass_a * lambda) * d;
    a.w -= lambda * ia_ra_d;
  }
  if (c.write_b) {
    b.v += (c.inv_mass_b * lambda) * d;
    b.w += lambda * ib_rb_d;
  }
}

// The tangent impulse (t0, t1) at the centre, applied as one combined update.
inline void apply_friction(const ContactConstraint& c, SolverBody& a, SolverBody& b, Real t0,
                           Real t1) {
  const Vec3 p = t0 * c.tangent[0] + t1 * c.tangent[1];
  if (c.write_a) {
    a.v -= c.inv_mass_a * p;
    a.w -= t0 * c.ia_ra_t[0] + t1 * c.ia_ra_t[1];
  }
  if (c.write_b) {
    b.v += c.inv_mass_b * p;
    b.w += t0 * c.ib_rb_t[0] + t1 * c.ib_rb_t[1];
  }
}

inline void apply_twist(const ContactConstraint& c, SolverBody& a, SolverBody& b, Real twist) {
  if (c.write_a) a.w -= twist * c.ia_n;
  if (c.write_b) b.w += twist * c.ib_n;
}

// The friction rows' Jacobians at the manifold centre and the inverse of their 2x2 mass matrix
// K = J M^-1 J^T, inverted in closed form.
void set_friction_rows(ContactConstraint& c, const Vec3& center_ra, const Vec3& center_rb,
                       const SymMat3& ia, const SymMat3& ib) {
  for (int t = 0; t < 2; ++t) {
    c.ra_t[t] = center_ra.cross(c.tangent[t]);
    c.rb_t[t] = center_rb.cross(c.tangent[t]);
    c.ia_ra_t[t] = ia * c.ra_t[t];
    c.ib_rb_t[t] = ib * c.rb_t[t];
  }
  const Real m_sum = c.inv_mass_a + c.inv_mass_b;
  const Real k00 = m_sum + c.ra_t[0].dot(c.ia_ra_t[0]) + c.rb_t[0].dot(c.ib_rb_t[0]);
  const Real k01 = c.ra_t[0].dot(c.ia_ra_t[1]) + c.rb_t[0].dot(c.ib_rb_t[1]);
  const Real k11 = m_sum + c.ra_t[1].dot(c.ia_ra_t[1]) + c.rb_t[1].dot(c.ib_rb_t[1]);
  const Real det = k00 * k11 - k01 * k01;
  const Real inv_det = det > 0 ? 1 / det : 0;
  c.tangent_inv_k[0] = k11 * inv_det;
  c.tangent_inv_k[1] = -k01 * inv_det;
  c.tangent_inv_k[2] = k00 * inv_det;
}

}  // namespace

void prepare_contact(const Manifold& m, uint32_t manifold_index, const BodyStore& bodies,
                     std::span<const uint32_t> packet_of, const ContactSolverContext& ctx,
                     ContactConstraint& c) {
  const uint32_t a = m.body_a, b = m.body_b;
  c.packet_a = packet_of[a];
  c.packet_b = packet_of[b];
  c.manifold = manifold_index;
  c.count = m.point_count;
  c.write_a = bodies.is_dynamic(a);
  c.write_b = bodies.is_dynamic(b);
  const SolverBodyParams& pa = ctx.params[c.packet_a];
  const SolverBodyParams& pb = ctx.params[c.packet_b];
  const Real ma = c.write_a ? pa.inv_mass : 0;
  const Real mb = c.write_b ? pb.inv_mass : 0;
  const SymMat3 ia = c.write_a ? pa.inv_inertia : SymMat3{};
  const SymMat3 ib = c.write_b ? pb.inv_inertia : SymMat3{};
  c.inv_mass_a = ma;
  c.inv_mass_b = mb;
  c.friction = std::sqrt(bodies.friction[a] * bodies.friction[b]);
  c.restitution = std::max(bodies.restitution[a], bodies.restitution[b]);
  c.softness = (c.write_a && c.write_b) ? ctx.contact_softness : ctx.static_softness;
  const Vec3 n = m.normal;
  c.normal = n;
  tangent_basis(n, c.tangent[0], c.tangent[1]);
  const SolverBody& sa = ctx.bodies[c.packet_a];
  const SolverBody& sb = ctx.bodies[c.packet_b];

  Vec3 center_ra = Vec3::Zero(), center_rb = Vec3::Zero();
  for (int i = 0; i < c.count; ++i) {
    const ContactPoint& mp = m.points[i];
    ConstraintPoint& cp = c.points[i];
    cp.ra_n = mp.anchor_a.cross(n);
    cp.rb_n = mp.anchor_b.cross(n);
    cp.ia_ra_n = ia * cp.ra_n;
    cp.ib_rb_n = ib * cp.rb_n;
    cp.separation = mp.separation;
    const Real k = ma + mb + cp.ra_n.dot(cp.ia_ra_n) + cp.rb_n.dot(cp.ib_rb_n);
    cp.normal_mass = k > 0 ? 1 / k : 0;
    cp.normal_impulse = mp.normal_impulse;
    cp.max_normal_impulse = 0;
    cp.relative_velocity = row_velocity(sa, sb, n, cp.ra_n, cp.rb_n);
    center_ra += mp.anchor_a;
    center_rb += mp.anchor_b;
  }
  const Real inv_count = c.count > 0 ? Real(1) / Real(c.count) : Real(0);
  center_ra *= inv_count;
  center_rb *= inv_count;
  for (int i = 0; i < c.count; ++i) {
    const Vec3 offset = m.points[i].anchor_a - center_ra;
    c.points[i].twist_lever = (offset - offset.dot(n) * n).norm();
  }
  set_friction_rows(c, center_ra, center_rb, ia, ib);
  c.ia_n = ia * n;
  c.ib_n = ib * n;
  const Real k_twist = n.dot(c.ia_n) + n.dot(c.ib_n);
  c.twist_mass = k_twist > 0 ? 1 / k_twist : 0;
  c.tangent_impulse[0] = m.tangent_impulse[0];
  c.tangent_impulse[1] = m.tangent_impulse[1];
  c.twist_impulse = m.twist_impulse;
}

void refresh_contacts(ContactSolverContext& ctx, const BodyStore& bodies,
                      std::span<const Manifold> manifolds, uint32_t begin, uint32_t end) {
  for (uint32_t i = begin; i < end; ++i) {
    ContactConstraint& c = ctx.constraints[i];
    // Against a static or kinematic body the impulse is external anyway: keep the arms.
    if (!(c.write_a && c.write_b)) continue;
    const Manifold& m = manifolds[c.manifold];
    const SolverBody& a = ctx.bodies[c.packet_a];
    const SolverBody& b = ctx.bodies[c.packet_b];
    // perf: resting contacts (most of a pile or stack) have barely moved since the step began;
    // their arms are then the step's own, within 0.1 mm, and re-deriving them buys nothing.
    if ((b.dp - a.dp).squaredNorm() < kRefreshDistance * kRefreshDistance &&
        a.dtheta.squaredNorm() + b.dtheta.squaredNorm() < kRefreshAngle * kRefreshAngle) {
      continue;
    }
    const SymMat3 ia = c.write_a ? ctx.params[c.packet_a].inv_inertia : SymMat3{};
    const SymMat3 ib = c.write_b ? ctx.params[c.packet_b].inv_inertia : SymMat3{};
    const Vec3& n = c.normal;
    // Centres now, relative to A's centre at the step's start (keeps the numbers small).
    const Vec3 xa = a.dp;
    const Vec3 xb = bodies.position(m.body_b) - bodies.position(m.body_a) + b.dp;
    const Real dp_n = n.dot(b.dp - a.dp);
    Vec3 center_ra = Vec3::Zero(), center_rb = Vec3::Zero();
    for (int k = 0; k < c.count; ++k) {
      ConstraintPoint& cp = c.points[k];
      const Real s = cp.separation + dp_n + cp.rb_n.dot(b.dtheta) - cp.ra_n.dot(a.dtheta);
      // The contact point of the step's start, carried by the mean translation of the two
      // bodies (not their rotation: a rolling sphere's contact stays under its centre).
      const Vec3 start_b = xb - b.dp;
      const Vec3 shared = Real(0.5) * (m.points[k].anchor_a + start_b + m.points[k].anchor_b) +
                          Real(0.5) * (a.dp + b.dp);
      const Vec3 ra = shared - xa, rb = shared - xb;
      cp.ra_n = ra.cross(n);
      cp.rb_n = rb.cross(n);
      cp.ia_ra_n = ia * cp.ra_n;
      cp.ib_rb_n = ib * cp.rb_n;
      const Real k_n =
          c.inv_mass_a + c.inv_mass_b + cp.ra_n.dot(cp.ia_ra_n) + cp.rb_n.dot(cp.ib_rb_n);
      cp.normal_mass = k_n > 0 ? 1 / k_n : 0;
      // Same separation as before, expressed with the new arms.
      cp.separation = s - (dp_n + cp.rb_n.dot(b.dtheta) - cp.ra_n.dot(a.dtheta));
      center_ra += ra;
      center_rb += rb;
    }
    const Real inv_count = c.count > 0 ? Real(1) / Real(c.count) : Real(0);
    center_ra *= inv_count;
    center_rb *= inv_count;
    set_friction_rows(c, center_ra, center_rb, ia, ib);
  }
}

void warm_start_contacts(ContactSolverContext& ctx, uint32_t begin, uint32_t end) {
  for (uint32_t i = begin; i < end; ++i) {
    const ContactConstraint& c = ctx.constraints[i];
    SolverBody& a = ctx.bodies[c.packet_a];
    SolverBody& b = ctx.bodies[c.packet_b];
    for (int k = 0; k < c.count; ++k) {
      const ConstraintPoint& cp = c.points[k];
      apply_row(c, a, b, c.normal, cp.ia_ra_n, cp.ib_rb_n, cp.normal_impulse);
    }
    apply_friction(c, a, b, c.tangent_impulse[0], c.tangent_impulse[1]);
    apply_twist(c, a, b, c.twist_impulse);
  }
}

void solve_contacts(ContactSolverContext& ctx, uint32_t begin, uint32_t end, bool use_bias) {
  for (uint32_t i = begin; i < end; ++i) {
    ContactConstraint& c = ctx.constraints[i];
    SolverBody& a = ctx.bodies[c.packet_a];
    SolverBody& b = ctx.bodies[c.packet_b];
    const Vec3 n = c.normal;
    {
      // Friction first, so the non-penetration rows, which carry the load, have the last word.
      // Coulomb limits from the accumulated normal impulses: the tangent impulse within
      // mu * sum(lambda_n), the twist within mu * sum(lever_k * lambda_n_k).
      Real total_normal = 0, twist_limit = 0;
      for (int k = 0; k < c.count; ++k) {
        total_normal += c.points[k].normal_impulse;
        twist_limit += c.points[k].twist_lever * c.points[k].normal_impulse;
      }
      const Real v0 = row_velocity(a, b, c.tangent[0], c.ra_t[0], c.rb_t[0]);
      const Real v1 = row_velocity(a, b, c.tangent[1], c.ra_t[1], c.rb_t[1]);
      Real t0 = c.tangent_impulse[0] - (c.tangent_inv_k[0] * v0 + c.tangent_inv_k[1] * v1);
      Real t1 = c.tangent_impulse[1] - (c.tangent_inv_k[1] * v0 + c.tangent_inv_k[2] * v1);
      const Real max_friction = c.friction * total_normal;
      const Real len2 = t0 * t0 + t1 * t1;
      if (len2 > max_friction * max_friction) {
        const Real scale = len2 > 0 ? max_friction / std::sqrt(len2) : 0;
        t0 *= scale;
        t1 *= scale;
      }
      apply_friction(c, a, b, t0 - c.tangent_impulse[0], t1 - c.tangent_impulse[1]);
      c.tangent_impulse[0] = t0;
      c.tangent_impulse[1] = t1;

      const Real spin = n.dot(b.w - a.w);
      const Real max_twist = c.friction * std::max(twist_limit, kTorsionPatch * total_normal);
      const Real twist = std::clamp(c.twist_impulse - c.twist_mass * spin, -max_twist, max_twist);
      apply_twist(c, a, b, twist - c.twist_impulse);
      c.twist_impulse = twist;
    }
    const Real dp_n = n.dot(b.dp - a.dp);
    for (int k = 0; k < c.count; ++k) {
      ConstraintPoint& cp = c.points[k];
      // Current separation from the pose change since the step began, linearised in the
      // rotation: s = s0 + n.(dp_b - dp_a) + (rb x n).dtheta_b - (ra x n).dtheta_a.
      const Real s = cp.separation + dp_n + cp.rb_n.dot(b.dtheta) - cp.ra_n.dot(a.dtheta);
      Real bias = 0, mass_scale = 1, impulse_scale = 0;
      if (s > 0) {
        bias = s * ctx.inv_h;  // speculative: allow closing the gap within this substep only
      } else if (use_bias) {
        bias = std::max(c.softness.bias_rate * s, -ctx.max_push_velocity);
        mass_scale = c.softness.mass_scale;
        impulse_scale = c.softness.impulse_scale;
      }
      const Real vn = row_velocity(a, b, n, cp.ra_n, cp.rb_n);
      Real impulse = -cp.normal_mass * mass_scale * (vn + bias) - impulse_scale * cp.normal_impulse;
      const Real updated = std::max(cp.normal_impulse + impulse, Real(0));
      impulse = updated - cp.normal_impulse;
      cp.normal_impulse = updated;
      cp.max_normal_impulse = std::max(cp.max_normal_impulse, impulse);
      apply_row(c, a, b, n, cp.ia_ra_n, cp.ib_rb_n, impulse);
    }
  }
}

void apply_restitution(ContactSolverContext& ctx, uint32_t begin, uint32_t end) {
  for (uint32_t i = begin; i < end; ++i) {
    ContactConstraint& c = ctx.constraints[i];
    if (c.restitution == 0) continue;
    SolverBody& a = ctx.bodies[c.packet_a];
    SolverBody& b = ctx.bodies[c.packet_b];
    for (int k = 0; k < c.count; ++k) {
      ConstraintPoint& cp = c.points[k];
      // Only points that approached faster than the threshold and actually pushed bounce.
      if (cp.relative_velocity > -ctx.restitution_threshold || cp.max_normal_impulse == 0) {
        continue;
      }
      const Real vn = row_velocity(a, b, c.normal, cp.ra_n, cp.rb_n);
      Real impulse = -cp.normal_mass * (vn + c.restitution * cp.relative_velocity);
      const Real updated = std::max(cp.normal_impulse + impulse, Real(0));
      impulse = updated - cp.normal_impulse;
      cp.normal_impulse = updated;
      cp.max_normal_impulse = std::max(cp.max_normal_impulse, impulse);
      apply_row(c, a, b, c.normal, cp.ia_ra_n, cp.ib_rb_n, impulse);
    }
  }
}

void store_impulses(const ContactSolverContext& ctx, uint32_t begin, uint32_t end,
                    std::span<Manifold> manifolds) {
  for (uint32_t i = begin; i < end; ++i) {
    const ContactConstraint& c = ctx.constraints[i];
    Manifold& m = manifolds[c.manifold];
    for (int k = 0; k < c.count; ++k) {
      m.points[k].normal_impulse = c.points[k].normal_impulse;
      m.points[k].max_normal_impulse = c.points[k].max_normal_impulse;
    }
    m.tangent_impulse[0] = c.tangent_impulse[0];
    m.tangent_impulse[1] = c.tangent_impulse[1];
    m.twist_impulse = c.twist_impulse;
  }
}

}  // namespace elan::detail
