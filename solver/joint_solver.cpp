// SPDX-License-Identifier: MIT
// Joint rows: preparation, warm start, the soft solve and relax, and the impulses' storage.
#include "solver/joint_solver.hpp"

#include <algorithm>
#include <cmath>

#include "core/base/fixed_math.hpp"
#include "core/base/grow.hpp"
#include "core/base/parallel.hpp"
#include "solver/direct_solve.hpp"

namespace elan::detail {

namespace {

constexpr Real kPi = Real(3.14159265358979323846);

// Joints are stiffer than contacts by default, as in Box2D v3 (twice the contact stiffness): a
// chain or a ragdoll sags less, and a joint has no speculative margin to hide a soft response in.
constexpr Real kJointHertzScale = 2;

constexpr std::size_t kPrepareGrain = kJointPrepareGrain;

Real wrap_angle(Real a) {
  if (a > kPi) return a - 2 * kPi;
  if (a <= -kPi) return a + 2 * kPi;
  return a;
}

// rel = A's joint frame seen in B's.
Quat relative_frame(const Quat& frame_a, const Quat& frame_b) {
  return frame_b.conjugate() * frame_a;
}

// The twist of rel about x (the hinge angle, the cone's twist), rad in (-pi, pi].
Real twist_angle(const Quat& rel) {
  return wrap_angle(2 * Real(fixed_atan2(rel.x(), rel.w())));
}

Mat3 to_mat(const SymMat3& m) {
  Mat3 r;
  r << m.xx, m.xy, m.xz, m.xy, m.yy, m.yz, m.xz, m.yz, m.zz;
  return r;
}

// The inverse of a symmetric positive semi-definite 3x3 matrix, or zero when singular (a joint
// between two bodies that cannot move along those rows).
Mat3 inverse_or_zero(const Mat3& k) {
  const Real det = k.determinant();
  if (!(std::abs(det) > Real(1e-30))) return Mat3::Zero();
  return k.inverse();
}

Real inverse_or_zero(Real k) {
  return k > Real(1e-30) ? 1 / k : 0;
}

// A body's side of a joint for one pass: its velocities (copied, written back only if the
// packet is written), mass and inverse inertia.
struct Side {
  Vec3 v, w;
  Real m;
  SymMat3 i;
};

SymMat3 operator+(const SymMat3& a, const SymMat3& b) {
  return {a.xx + b.xx, a.yy + b.yy, a.zz + b.zz, a.xy + b.xy, a.xz + b.xz, a.yz + b.yz};
}

// The soft coefficients of a position row: Box2D v3's, off in the relax pass.
struct Soft {
  Real bias_rate = 0, mass_scale = 1, impulse_scale = 0;
};

Soft soft_of(const JointRow& j, bool use_bias) {
  return use_bias ? Soft{j.softness.bias_rate, j.softness.mass_scale, j.softness.impulse_scale}
                  : Soft{};
}

using Pose = JointPose;

Pose pose_of(const JointRow& j, const SolverBody& a, const SolverBody& b) {
  Pose p;
  p.r_a = a.dq * j.r_a;
  p.r_b = b.dq * j.r_b;
  // perf: ball and distance joints read no frame (a joint grid is all ball joints).
  if (j.type != JointType::Ball && j.type != JointType::Distance) {
    p.frame_a = a.dq * j.frame_a;
    p.frame_b = b.dq * j.frame_b;
  }
  p.separation = (b.dp - a.dp) + (p.r_b - p.r_a) + j.delta_center;
  return p;
}

// The point rows' mass matrix at the current arms, inverted: K = (m_a + m_b) E + P(r_a, I_a^-1)
// + P(r_b, I_b^-1), with P(r, I) = [r]x I [r]x^T, whose column j is r x (I (e_j x r)). perf:
// written out on the symmetric entries (a joint grid refreshes every joint once a substep).
SymMat3 arm_term(const Vec3& r, const SymMat3& i) {
  const Vec3 c0 = r.cross(i * Vec3(0, -r.z(), r.y()));
  const Vec3 c1 = r.cross(i * Vec3(r.z(), 0, -r.x()));
  const Vec3 c2 = r.cross(i * Vec3(-r.y(), r.x(), 0));
  return {c0.x(), c1.y(), c2.z(), c1.x(), c2.x(), c2.y()};
}

// perf: the same for an isotropic inverse inertia k E (a sphere, a cube; 0 for the world and
// kinematic bodies), the joint grid's: k [r]x [r]x^T = k (|r|^2 E - r r^T).
SymMat3 arm_term(const Vec3& r, Real k) {
  const Real r2 = r.squaredNorm();
  return {k * (r2 - r.x() * r.x()), k * (r2 - r.y() * r.y()), k * (r2 - r.z() * r.z()),
          -k * r.x() * r.y(),       -k * r.x() * r.z(),       -k * r.y() * r.z()};
}

SymMat3 point_mass_of(const JointRow& j, const SolverBodyMass& a, const SolverBodyMass& b) {
  const Pose& p = j.pose;
  const SymMat3 ta =
      j.isotropic_a >= 0 ? arm_term(p.r_a, j.isotropic_a) : arm_term(p.r_a, a.inv_inertia);
  const SymMat3 tb =
      j.isotropic_b >= 0 ? arm_term(p.r_b, j.isotropic_b) : arm_term(p.r_b, b.inv_inertia);
  const Real m = a.inv_mass + b.inv_mass;
  const Real xx = m + ta.xx + tb.xx, yy = m + ta.yy + tb.yy, zz = m + ta.zz + tb.zz;
  const Real xy = ta.xy + tb.xy, xz = ta.xz + tb.xz, yz = ta.yz + tb.yz;
  // The inverse by cofactors.
  const Real c00 = yy * zz - yz * yz, c01 = xz * yz - xy * zz, c02 = xy * yz - xz * yy;
  const Real det = xx * c00 + xy * c01 + xz * c02;
  if (!(std::abs(det) > Real(1e-30))) return {};
  const Real inv = 1 / det;
  return {c00 * inv, (xx * zz - xz * xz) * inv, (xx * yy - xy * xy) * inv, c01 * inv,
          c02 * inv, (xy * xz - xx * yz) * inv};
}

bool has_point_rows(JointType type) {
  return type != JointType::Slider && type != JointType::Distance;
}

// The geometry at the current poses, and the point rows' mass matrix there. Kept fresh every
// substep: a mass matrix from the step's start, on a body turning fast about a distant anchor,
// points its correction the wrong way and the joint blows up (tests/determinism/soak.cpp).
void refresh_row(JointRow& j, std::span<const SolverBody> packets,
                 std::span<const SolverBodyMass> masses) {
  j.pose = pose_of(j, packets[j.packet_a], packets[j.packet_b]);
  if (has_point_rows(j.type)) {
    j.point_mass = point_mass_of(j, masses[j.packet_a], masses[j.packet_b]);
  }
}

// A row that turns A about `axis` (unit, world) against B: rate = axis . (w_a - w_b).
struct AngularRow {
  Vec3 axis;
  Real mass;  // kg m^2
};
AngularRow angular_row(const Side& a, const Side& b, const Vec3& axis) {
  return {axis, inverse_or_zero(axis.dot((a.i + b.i) * axis))};
}
Real rate_of(const AngularRow& r, const Side& a, const Side& b) {
  return r.axis.dot(a.w - b.w);
}
void apply(const AngularRow& r, Side& a, Side& b, Real impulse) {
  a.w += a.i * (r.axis * impulse);
  b.w -= b.i * (r.axis * impulse);
}

// A row along `e` (unit, world) of A's anchor relative to B's: rate = e . (v_a + w_a x r_a -
// v_b - w_b x r_b'), with r_b' the arm from B's centre to A's anchor (so the row's torque on B is
// taken where the force acts: the slider's rows).
struct LinearRow {
  Vec3 e, ra_e, rb_e;  // e, r_a x e, r_b' x e
  Real mass;
};
LinearRow linear_row(const Side& a, const Side& b, const Vec3& e, const Vec3& r_a,
                     const Vec3& r_b) {
  LinearRow r{e, r_a.cross(e), r_b.cross(e), 0};
  r.mass = inverse_or_zero(a.m + b.m + r.ra_e.dot(a.i * r.ra_e) + r.rb_e.dot(b.i * r.rb_e));
  return r;
}
Real rate_of(const LinearRow& r, const Side& a, const Side& b) {
  return r.e.dot(a.v - b.v) + r.ra_e.dot(a.w) - r.rb_e.dot(b.w);
}
void apply(const LinearRow& r, Side& a, Side& b, Real impulse) {
  a.v += r.e * (a.m * impulse);
  a.w += a.i * (r.ra_e * impulse);
  b.v -= r.e * (b.m * impulse);
  b.w -= b.i * (r.rb_e * impulse);
}

// Spring, motor and limits on one coordinate x whose rate is rate_of(row) (Box2D v3's revolute
// and prismatic joints, in their order: spring, motor, lower, upper).
template <class Row>
void solve_axis(const JointSolverContext& ctx, JointRow& j, const Row& row, Real x, Side& a,
                Side& b, bool use_bias) {
  if ((j.flags & kJointFriction) && (j.type == JointType::Hinge || j.type == JointType::Slider)) {
    const Real old = j.impulses.friction.x();
    const Real updated = std::clamp(old - row.mass * rate_of(row, a, b), -j.max_friction_impulse,
                                    j.max_friction_impulse);
    j.impulses.friction.x() = updated;
    apply(row, a, b, updated - old);
  }
  if (j.flags & kJointSpring) {
    const Real c = x - j.spring_target;
    const Real rate = rate_of(row, a, b);
    const Real impulse = -j.spring.mass_scale * row.mass * (rate + j.spring.bias_rate * c) -
                         j.spring.impulse_scale * j.impulses.spring;
    j.impulses.spring += impulse;
    apply(row, a, b, impulse);
  }
  if (j.flags & kJointMotor) {
    const Real rate = rate_of(row, a, b);
    const Real impulse = -row.mass * (rate - j.motor_speed);
    const Real old = j.impulses.motor;
    j.impulses.motor = std::clamp(old + impulse, -j.max_motor_impulse, j.max_motor_impulse);
    apply(row, a, b, j.impulses.motor - old);
  }
  if (j.flags & kJointLimit) {
    const Soft soft = soft_of(j, use_bias);
    // A limit not yet reached is speculative: it lets the coordinate close the gap in this
    // substep and no further (bias = gap / h, rigid).
    auto limit = [&](Real c, Real sign, Real& accumulated) {
      Real bias = 0, mass_scale = 1, impulse_scale = 0;
      if (c > 0) {
        bias = c * ctx.inv_h;
      } else if (use_bias) {
        bias = soft.bias_rate * c;
        mass_scale = soft.mass_scale;
        impulse_scale = soft.impulse_scale;
      }
      const Real rate = sign * rate_of(row, a, b);
      const Real impulse = -row.mass * mass_scale * (rate + bias) - impulse_scale * accumulated;
      const Real updated = std::max(accumulated + impulse, Real(0));
      apply(row, a, b, sign * (updated - accumulated));
      accumulated = updated;
    };
    limit(x - j.lower, 1, j.impulses.lower);
    limit(j.upper - x, -1, j.impulses.upper);
  }
}

// Joint friction about every axis (ball, cone): the relative angular velocity is stopped by an
// impulse whose accumulated length stays within the friction's (Jolt's friction torque).
void solve_angular_friction(JointRow& j, Side& a, Side& b) {
  const Vec3 old = j.impulses.friction;
  Vec3 updated = old - inverse_or_zero(to_mat(a.i + b.i)) * (a.w - b.w);
  const Real length = updated.norm();
  if (length > j.max_friction_impulse) updated *= j.max_friction_impulse / length;
  j.impulses.friction = updated;
  a.w += a.i * (updated - old);
  b.w -= b.i * (updated - old);
}

// The anchors coincide: three rows solved as one block.
void solve_point(JointRow& j, const Pose& p, Side& a, Side& b, bool use_bias) {
  const Soft soft = soft_of(j, use_bias);
  const Vec3 rate = b.v + b.w.cross(p.r_b) - a.v - a.w.cross(p.r_a);
  const Vec3 impulse = -soft.mass_scale * (j.point_mass * (rate + soft.bias_rate * p.separation)) -
                       soft.impulse_scale * j.point_impulse;
  j.point_impulse += impulse;
  a.v -= a.m * impulse;
  a.w -= a.i * p.r_a.cross(impulse);
  b.v += b.m * impulse;
  b.w += b.i * p.r_b.cross(impulse);
}

// The orientation error of A's joint frame against B's, world (rad, small-angle).
Vec3 orientation_error(const Pose& p) {
  Quat rel = relative_frame(p.frame_a, p.frame_b);
  if (rel.w() < 0) rel.coeffs() = -rel.coeffs();
  return p.frame_b * (2 * rel.vec());
}

// The relative orientation is locked: three rows, one block.
void solve_orientation(JointRow& j, const Pose& p, Side& a, Side& b, bool use_bias) {
  const Soft soft = soft_of(j, use_bias);
  const Vec3 rate = a.w - b.w;
  const Vec3 impulse = -soft.mass_scale * (inverse_or_zero(to_mat(a.i + b.i)) *
                                           (rate + soft.bias_rate * orientation_error(p))) -
                       soft.impulse_scale * j.impulses.angular;
  j.impulses.angular += impulse;
  a.w += a.i * impulse;
  b.w -= b.i * impulse;
}

// The hinge's axes stay aligned: A's axis a keeps a . b1 = a . b2 = 0 with B's two normals;
// rate_k = (a x b_k) . (w_a - w_b). Two rows, one block.
void solve_hinge_axes(JointRow& j, const Pose& p, Side& a, Side& b, bool use_bias) {
  const Soft soft = soft_of(j, use_bias);
  const Vec3 axis = p.frame_a * Vec3::UnitX();
  const Vec3 b1 = p.frame_b * Vec3::UnitY(), b2 = p.frame_b * Vec3::UnitZ();
  const Vec3 u1 = axis.cross(b1), u2 = axis.cross(b2);
  const SymMat3 inv_i = a.i + b.i;
  const Real k11 = u1.dot(inv_i * u1), k12 = u1.dot(inv_i * u2), k22 = u2.dot(inv_i * u2);
  const Real det = k11 * k22 - k12 * k12;
  const Real inv_det = std::abs(det) > Real(1e-30) ? 1 / det : 0;
  const Vec3 dw = a.w - b.w;
  const Real r1 = u1.dot(dw) + soft.bias_rate * axis.dot(b1);
  const Real r2 = u2.dot(dw) + soft.bias_rate * axis.dot(b2);
  const Real x1 = inv_det * (k22 * r1 - k12 * r2);
  const Real x2 = inv_det * (k11 * r2 - k12 * r1);
  const Real l1 = -soft.mass_scale * x1 - soft.impulse_scale * j.impulses.angular.x();
  const Real l2 = -soft.mass_scale * x2 - soft.impulse_scale * j.impulses.angular.y();
  j.impulses.angular.x() += l1;
  j.impulses.angular.y() += l2;
  const Vec3 torque = u1 * l1 + u2 * l2;
  a.w += a.i * torque;
  b.w -= b.i * torque;
}

// The slider's anchor stays on B's axis: two rows along B's normals, one block.
void solve_slider_line(JointRow& j, const Pose& p, Side& a, Side& b, bool use_bias) {
  const Soft soft = soft_of(j, use_bias);
  const Vec3 d = -p.separation;  // A's anchor minus B's
  const Vec3 r_b = p.r_b + d;    // B's centre to A's anchor
  const LinearRow row1 = linear_row(a, b, p.frame_b * Vec3::UnitY(), p.r_a, r_b);
  const LinearRow row2 = linear_row(a, b, p.frame_b * Vec3::UnitZ(), p.r_a, r_b);
  const Real k11 = a.m + b.m + row1.ra_e.dot(a.i * row1.ra_e) + row1.rb_e.dot(b.i * row1.rb_e);
  const Real k22 = a.m + b.m + row2.ra_e.dot(a.i * row2.ra_e) + row2.rb_e.dot(b.i * row2.rb_e);
  const Real k12 = row1.ra_e.dot(a.i * row2.ra_e) + row1.rb_e.dot(b.i * row2.rb_e);
  const Real det = k11 * k22 - k12 * k12;
  const Real inv_det = std::abs(det) > Real(1e-30) ? 1 / det : 0;
  const Real r1 = rate_of(row1, a, b) + soft.bias_rate * row1.e.dot(d);
  const Real r2 = rate_of(row2, a, b) + soft.bias_rate * row2.e.dot(d);
  const Real l1 = -soft.mass_scale * inv_det * (k22 * r1 - k12 * r2) -
                  soft.impulse_scale * j.impulses.linear.x();
  const Real l2 = -soft.mass_scale * inv_det * (k11 * r2 - k12 * r1) -
                  soft.impulse_scale * j.impulses.linear.y();
  j.impulses.linear.x() += l1;
  j.impulses.linear.y() += l2;
  apply(row1, a, b, l1);
  apply(row2, a, b, l2);
}

// The cone's swing: A's axis stays within swing_limit of B's. The row turns about the axis of
// the swing (B's axis x A's axis); none while the axes are (anti)parallel.
void solve_swing(const JointSolverContext& ctx, JointRow& j, const Pose& p, Side& a, Side& b,
                 bool use_bias) {
  const Vec3 axis_a = p.frame_a * Vec3::UnitX(), axis_b = p.frame_b * Vec3::UnitX();
  const Vec3 n = axis_b.cross(axis_a);
  const Real sin_swing = n.norm();
  if (!(sin_swing > Real(1e-6))) return;
  const Real swing = Real(fixed_atan2(sin_swing, axis_a.dot(axis_b)));
  const AngularRow row = angular_row(a, b, n / sin_swing);
  const Real c = j.swing_limit - swing;
  Real bias = 0, mass_scale = 1, impulse_scale = 0;
  if (c > 0) {
    bias = c * ctx.inv_h;
  } else if (use_bias) {
    bias = j.softness.bias_rate * c;
    mass_scale = j.softness.mass_scale;
    impulse_scale = j.softness.impulse_scale;
  }
  const Real rate = -rate_of(row, a, b);
  const Real impulse = -row.mass * mass_scale * (rate + bias) - impulse_scale * j.impulses.swing;
  const Real updated = std::max(j.impulses.swing + impulse, Real(0));
  apply(row, a, b, -(updated - j.impulses.swing));
  j.impulses.swing = updated;
}

// The distance rows along the anchors' line (B's anchor minus A's).
struct DistanceGeometry {
  LinearRow row;
  Real length;
};
DistanceGeometry distance_geometry(const Pose& p, const Side& a, const Side& b) {
  const Real length = p.separation.norm();
  const Vec3 e = length > Real(1e-9) ? Vec3(p.separation / length) : Vec3(Vec3::UnitY());
  // In the LinearRow convention (A relative to B) the row is along -e: its rate is that of the
  // length.
  return {linear_row(a, b, -e, p.r_a, p.r_b), length};
}

void solve_distance(const JointSolverContext& ctx, JointRow& j, const Pose& p, Side& a, Side& b,
                    bool use_bias) {
  const DistanceGeometry g = distance_geometry(p, a, b);
  const bool rigid = j.lower == j.upper && !(j.flags & kJointSpring);
  if (rigid) {
    const Soft soft = soft_of(j, use_bias);
    const Real c = g.length - j.lower;
    const Real impulse =
        -soft.mass_scale * g.row.mass * (rate_of(g.row, a, b) + soft.bias_rate * c) -
        soft.impulse_scale * j.impulses.axial;
    j.impulses.axial += impulse;
    apply(g.row, a, b, impulse);
    return;
  }
  solve_axis(ctx, j, g.row, g.length, a, b, use_bias);
}

// Applies the point impulse P (on B; -P on A) at the current arms.
void apply_point(const JointSolverContext& ctx, const JointRow& j, const Vec3& impulse) {
  if (written_packet(j.packet_a, ctx.written_end)) {
    SolverBody& pa = ctx.bodies[j.packet_a];
    const SolverBodyMass& ma = ctx.masses[j.packet_a];
    pa.v -= ma.inv_mass * impulse;
    pa.w -= ma.inv_inertia * j.pose.r_a.cross(impulse);
  }
  if (written_packet(j.packet_b, ctx.written_end)) {
    SolverBody& pb = ctx.bodies[j.packet_b];
    const SolverBodyMass& mb = ctx.masses[j.packet_b];
    pb.v += mb.inv_mass * impulse;
    pb.w += mb.inv_inertia * j.pose.r_b.cross(impulse);
  }
}

// A ball joint's passes, on the packets directly. perf: a joint grid is all ball joints, and
// the general path's copies of both sides cost as much as the rows.
void solve_ball(const JointSolverContext& ctx, JointRow& j, bool use_bias) {
  SolverBody& pa = ctx.bodies[j.packet_a];
  SolverBody& pb = ctx.bodies[j.packet_b];
  const Soft soft = soft_of(j, use_bias);
  const Pose& p = j.pose;
  const Vec3 rate = pb.v + pb.w.cross(p.r_b) - pa.v - pa.w.cross(p.r_a);
  const Vec3 impulse = -soft.mass_scale * (j.point_mass * (rate + soft.bias_rate * p.separation)) -
                       soft.impulse_scale * j.point_impulse;
  j.point_impulse += impulse;
  apply_point(ctx, j, impulse);
}

// The impulse along the joint's coordinate: spring, motor, limits and, for hinges and sliders,
// friction (N s, N m s).
Real axial_impulse(const JointRow& j) {
  const JointImpulses& im = j.impulses;
  const bool along_axis = j.type == JointType::Hinge || j.type == JointType::Slider;
  return im.spring + im.motor + im.lower - im.upper + (along_axis ? im.friction.x() : Real(0));
}

// The angular impulse the joint's rotational rows apply to A (B gets its opposite), world, at
// pose p: what the warm start applies again and what the joint's torque reports.
Vec3 angular_impulse(const JointRow& j, const Pose& p) {
  const JointImpulses& im = j.impulses;
  const Vec3 axis_a = p.frame_a * Vec3::UnitX();
  switch (j.type) {
    case JointType::Ball:
      return im.friction;
    case JointType::Fixed:
    case JointType::Slider:
      return im.angular;
    case JointType::Hinge:
      return axis_a.cross(p.frame_b * Vec3::UnitY()) * im.angular.x() +
             axis_a.cross(p.frame_b * Vec3::UnitZ()) * im.angular.y() + axis_a * axial_impulse(j);
    case JointType::Cone: {
      Vec3 torque = im.friction;
      const Vec3 axis_b = p.frame_b * Vec3::UnitX();
      const Vec3 twist = axis_a + axis_b;
      if (twist.squaredNorm() > Real(1e-12)) torque += twist.normalized() * axial_impulse(j);
      const Vec3 n = axis_b.cross(axis_a);
      if (n.norm() > Real(1e-6)) torque -= n.normalized() * im.swing;
      return torque;
    }
    case JointType::Distance:
      break;
  }
  return Vec3::Zero();
}

template <class F>
void for_joint(const JointSolverContext& ctx, JointRow& j, F&& f) {
  SolverBody& pa = ctx.bodies[j.packet_a];
  SolverBody& pb = ctx.bodies[j.packet_b];
  const SolverBodyMass& ma = ctx.masses[j.packet_a];
  const SolverBodyMass& mb = ctx.masses[j.packet_b];
  Side a{pa.v, pa.w, ma.inv_mass, ma.inv_inertia};
  Side b{pb.v, pb.w, mb.inv_mass, mb.inv_inertia};
  f(j.pose, a, b);
  // determinism: only the packets of awake dynamic bodies are written; the static dummy and
  // kinematic packets are read by both halves at once.
  if (written_packet(j.packet_a, ctx.written_end)) {
    pa.v = a.v;
    pa.w = a.w;
  }
  if (written_packet(j.packet_b, ctx.written_end)) {
    pb.v = b.v;
    pb.w = b.w;
  }
}

}  // namespace

void joint_links(const JointStore& joints, std::span<const uint32_t> slot_index,
                 std::vector<JointLink>& links) {
  links.resize(joints.size());
  for (std::size_t k = 0; k < joints.size(); ++k) {
    const Joint& j = joints.joints[k];
    links[k].a = j.slot_a == kWorldSlot ? UINT32_MAX : slot_index[j.slot_a];
    links[k].b = j.slot_b == kWorldSlot ? UINT32_MAX : slot_index[j.slot_b];
  }
}

JointSolverContext make_joint_context(const SolveSettings& settings, SolverState& state) {
  JointSolverContext ctx;
  ctx.bodies = state.packets;
  ctx.masses = state.masses;
  ctx.written_end = state.half_start[kHalves];
  ctx.h = settings.dt / Real(settings.substeps);
  ctx.inv_h = 1 / ctx.h;
  return ctx;
}

void prepare_joints(const BodyStore& bodies, const JointStore& joints,
                    std::span<const uint32_t> slot_index, const SolveSettings& settings,
                    SolverState& st) {
  const Real h = settings.dt / Real(settings.substeps);
  const Real default_hertz = kJointHertzScale * std::min(settings.contact_hertz, Real(0.25) / h);
  auto group_of = [&](uint32_t packet) -> int {
    if (packet == 0 || packet >= st.half_start[kHalves]) return -1;  // not written
    return packet < st.half_start[1] ? 0 : 1;
  };
  // Two passes: count per group, then place, so rows land group by group in joint order.
  uint32_t count[kGroups] = {};
  std::vector<uint8_t>& group = st.joint_group;
  group.resize(joints.size());
  for (std::size_t k = 0; k < joints.size(); ++k) {
    const Joint& j = joints.joints[k];
    const uint32_t pa = j.slot_a == kWorldSlot ? 0 : st.packet_of[slot_index[j.slot_a]];
    const uint32_t pb = j.slot_b == kWorldSlot ? 0 : st.packet_of[slot_index[j.slot_b]];
    const int ga = group_of(pa), gb = group_of(pb);
    uint8_t g = UINT8_MAX;  // asleep (or both sides read-only): not solved
    if (ga >= 0 || gb >= 0) {
      g = uint8_t(ga < 0 ? gb : gb < 0 ? ga : ga == gb ? ga : int(kCutGroup));
      ++count[g];
    }
    group[k] = g;
  }
  st.joint_group_start[0] = 0;
  for (uint32_t g = 0; g < kGroups; ++g) {
    st.joint_group_start[g + 1] = st.joint_group_start[g] + count[g];
  }
  st.joint_rows.resize(st.joint_group_start[kGroups]);
  auto prepare_row = [&](JointRow& r) {
    const Joint& j = joints.joints[r.joint];
    Vec3 c_a = Vec3::Zero(), c_b = Vec3::Zero();
    Quat q_a = Quat::Identity(), q_b = Quat::Identity();
    r.packet_a = r.packet_b = 0;
    // A side's inverse inertia when it is the same about every axis (then its world form is that
    // too), or -1. Read from the body's principal moments, exactly.
    auto isotropic = [&](uint32_t slot, uint32_t packet) -> Real {
      if (packet == 0 || packet >= st.half_start[kHalves]) return 0;  // no inertia in the solve
      const uint32_t i = slot_index[slot];
      const Real k = bodies.inv_ix[i];
      return k == bodies.inv_iy[i] && k == bodies.inv_iz[i] ? k : Real(-1);
    };
    if (j.slot_a != kWorldSlot) {
      const uint32_t i = slot_index[j.slot_a];
      c_a = bodies.position(i);
      q_a = bodies.orientation(i);
      r.packet_a = st.packet_of[i];
    }
    if (j.slot_b != kWorldSlot) {
      const uint32_t i = slot_index[j.slot_b];
      c_b = bodies.position(i);
      q_b = bodies.orientation(i);
      r.packet_b = st.packet_of[i];
    }
    r.isotropic_a = j.slot_a == kWorldSlot ? 0 : isotropic(j.slot_a, r.packet_a);
    r.isotropic_b = j.slot_b == kWorldSlot ? 0 : isotropic(j.slot_b, r.packet_b);
    r.type = j.def.type;
    r.r_a = q_a * j.anchor_a;
    r.r_b = q_b * j.anchor_b;
    r.frame_a = q_a * j.frame_a;
    r.frame_b = q_b * j.frame_b;
    r.delta_center = c_b - c_a;
    r.flags = 0;
    const JointDef& d = j.def;
    const bool axial = r.type == JointType::Hinge || r.type == JointType::Slider;
    if (r.type == JointType::Distance) {
      r.lower = j.min_length;
      r.upper = j.max_length;
      if (r.lower < r.upper) r.flags |= kJointLimit;
      if (d.spring.enabled) {
        r.flags |= kJointSpring | kJointLimit;
        r.spring_target = j.rest_length;
      }
    } else if ((axial || r.type == JointType::Cone) && d.limits.enabled) {
      r.flags |= kJointLimit;
      r.lower = d.limits.lower;
      r.upper = d.limits.upper;
    }
    if (axial && d.motor.enabled) {
      r.flags |= kJointMotor;
      r.motor_speed = d.motor.speed;
      r.max_motor_impulse = d.motor.max_force * h;
    }
    if (axial && d.spring.enabled) {
      r.flags |= kJointSpring;
      r.spring_target = d.spring.target;
    }
    r.softness = make_softness(d.constraint_hertz > 0 ? d.constraint_hertz : default_hertz,
                               d.constraint_damping_ratio, h);
    if (r.flags & kJointSpring)
      r.spring = make_softness(d.spring.frequency, d.spring.damping_ratio, h);
    if (r.type == JointType::Cone && d.swing_limit < kPi) {
      r.flags |= kJointSwing;
      r.swing_limit = d.swing_limit;
    }
    r.impulses = j.impulses;
    r.point_impulse = j.impulses.point;
    // A part switched off since the last step has nothing to warm start.
    if (!(r.flags & kJointSpring)) r.impulses.spring = 0;
    if (!(r.flags & kJointMotor)) r.impulses.motor = 0;
    if (!(r.flags & kJointLimit)) r.impulses.lower = r.impulses.upper = 0;
    if (!(r.flags & kJointSwing)) r.impulses.swing = 0;
    const bool frictional = r.type == JointType::Ball || r.type == JointType::Cone || axial;
    if (frictional && d.friction > 0) {
      r.flags |= kJointFriction;
      r.max_friction_impulse = d.friction * h;
    } else {
      r.impulses.friction.setZero();
    }
    refresh_row(r, st.packets, st.masses);
    // Loaded: the point rows' soft spring would give more than kDirectJointGive under last step's
    // impulse, lambda gamma / m_eff with m_eff the mean of the point mass's diagonal. A joint
    // made soft on purpose (its own constraint_hertz) keeps its softness.
    if (has_point_rows(r.type) && !(d.constraint_hertz > 0)) {
      const Real m_eff = (r.point_mass.xx + r.point_mass.yy + r.point_mass.zz) / 3;
      if (give_per_impulse(r.softness) * r.point_impulse.norm() > kDirectJointGive * m_eff) {
        r.flags |= kJointLoaded;
      }
    }
  };
  uint32_t next[kGroups];
  for (uint32_t g = 0; g < kGroups; ++g) next[g] = st.joint_group_start[g];
  for (std::size_t k = 0; k < joints.size(); ++k) {
    if (group[k] != UINT8_MAX) st.joint_rows[next[group[k]]++].joint = uint32_t(k);
  }
  // determinism: each row is written by its block alone, from its joint alone (rule 1).
  grow_fill(st.direct.loaded_joint_blocks, block_count(st.joint_rows.size(), kPrepareGrain),
            uint8_t(0));
  for_blocks(st.joint_rows.size(), kPrepareGrain,
             [&](std::size_t begin, std::size_t end, std::size_t block) {
               uint8_t loaded = 0;
               for (std::size_t row = begin; row < end; ++row) {
                 prepare_row(st.joint_rows[row]);
                 loaded |= st.joint_rows[row].flags & kJointLoaded;
               }
               st.direct.loaded_joint_blocks[block] = loaded != 0;
             });
}

void refresh_joints(const JointSolverContext& ctx, std::span<JointRow> rows) {
  for (JointRow& j : rows) refresh_row(j, ctx.bodies, ctx.masses);
}

void warm_start_joints(const JointSolverContext& ctx, std::span<JointRow> rows) {
  for (JointRow& j : rows) {
    if (j.type == JointType::Ball && !(j.flags & kJointFriction)) {
      apply_point(ctx, j, j.point_impulse);
      continue;
    }
    for_joint(ctx, j, [&](const Pose& p, Side& a, Side& b) {
      const JointImpulses& im = j.impulses;
      if (j.type != JointType::Slider && j.type != JointType::Distance) {
        const Vec3 P = j.point_impulse;
        a.v -= a.m * P;
        a.w -= a.i * p.r_a.cross(P);
        b.v += b.m * P;
        b.w += b.i * p.r_b.cross(P);
      }
      const Real axial = axial_impulse(j);
      if (j.type == JointType::Slider) {
        const Vec3 d = -p.separation;
        const Vec3 r_b = p.r_b + d;
        apply(linear_row(a, b, p.frame_b * Vec3::UnitY(), p.r_a, r_b), a, b, im.linear.x());
        apply(linear_row(a, b, p.frame_b * Vec3::UnitZ(), p.r_a, r_b), a, b, im.linear.y());
        apply(linear_row(a, b, p.frame_b * Vec3::UnitX(), p.r_a, r_b), a, b, axial);
      } else if (j.type == JointType::Distance) {
        apply(distance_geometry(p, a, b).row, a, b, im.axial + axial);
      }
      const Vec3 torque = angular_impulse(j, p);
      a.w += a.i * torque;
      b.w -= b.i * torque;
    });
  }
}

void solve_joints(const JointSolverContext& ctx, std::span<JointRow> rows, bool use_bias) {
  for (JointRow& j : rows) {
    if (j.type == JointType::Ball && !(j.flags & kJointFriction)) {
      solve_ball(ctx, j, use_bias);
      continue;
    }
    for_joint(ctx, j, [&](const Pose& p, Side& a, Side& b) {
      switch (j.type) {
        case JointType::Ball:
          if (j.flags & kJointFriction) solve_angular_friction(j, a, b);
          solve_point(j, p, a, b, use_bias);
          break;
        case JointType::Hinge: {
          const Quat rel = relative_frame(p.frame_a, p.frame_b);
          if (j.flags & (kJointSpring | kJointMotor | kJointLimit | kJointFriction)) {
            const AngularRow row = angular_row(a, b, p.frame_a * Vec3::UnitX());
            solve_axis(ctx, j, row, twist_angle(rel), a, b, use_bias);
          }
          solve_hinge_axes(j, p, a, b, use_bias);
          solve_point(j, p, a, b, use_bias);
          break;
        }
        case JointType::Slider: {
          if (j.flags & (kJointSpring | kJointMotor | kJointLimit | kJointFriction)) {
            const Vec3 d = -p.separation;
            const Vec3 axis = p.frame_b * Vec3::UnitX();
            const LinearRow row = linear_row(a, b, axis, p.r_a, p.r_b + d);
            solve_axis(ctx, j, row, axis.dot(d), a, b, use_bias);
          }
          solve_orientation(j, p, a, b, use_bias);
          solve_slider_line(j, p, a, b, use_bias);
          break;
        }
        case JointType::Fixed:
          solve_orientation(j, p, a, b, use_bias);
          solve_point(j, p, a, b, use_bias);
          break;
        case JointType::Distance:
          solve_distance(ctx, j, p, a, b, use_bias);
          break;
        case JointType::Cone: {
          if (j.flags & kJointFriction) solve_angular_friction(j, a, b);
          if (j.flags & kJointSwing) solve_swing(ctx, j, p, a, b, use_bias);
          if (j.flags & kJointLimit) {
            const Vec3 twist = p.frame_a * Vec3::UnitX() + p.frame_b * Vec3::UnitX();
            if (twist.squaredNorm() > Real(1e-12)) {
              const AngularRow row = angular_row(a, b, twist.normalized());
              solve_axis(ctx, j, row, twist_angle(relative_frame(p.frame_a, p.frame_b)), a, b,
                         use_bias);
            }
          }
          solve_point(j, p, a, b, use_bias);
          break;
        }
      }
    });
  }
}

void store_joint_impulses(std::span<const JointRow> rows, const JointSolverContext& ctx,
                          JointStore& store, std::vector<uint8_t>& broke,
                          std::vector<uint32_t>& broken) {
  broke.assign(rows.size(), 0);
  auto store_row = [&](std::size_t row) {
    const JointRow& r = rows[row];
    Joint& j = store.joints[r.joint];
    const JointImpulses& im = r.impulses;
    const bool finite =
        r.point_impulse.allFinite() && im.angular.allFinite() && im.linear.allFinite() &&
        im.friction.allFinite() &&
        std::isfinite(im.axial + im.spring + im.motor + im.lower + im.upper + im.swing);
    if (!finite) {
      // A body of the joint went non-finite and is quarantined by finalize_bodies: the joint
      // starts again from rest rather than warm starting its neighbours with NaN.
      j.impulses = JointImpulses{};
      j.force = j.torque = Vec3::Zero();
      return;
    }
    j.impulses = r.impulses;
    j.impulses.point = r.point_impulse;
    // The force and torque on A at the end of the step, from the last substep's impulses and the
    // final geometry (refreshed after the last position change).
    const Pose& p = r.pose;
    const Real axial = axial_impulse(r);
    Vec3 force = -r.point_impulse;
    if (r.type == JointType::Slider) {
      force = p.frame_b * Vec3(axial, im.linear.x(), im.linear.y());
    } else if (r.type == JointType::Distance) {
      const Real length = p.separation.norm();
      const Vec3 e = length > Real(1e-9) ? Vec3(p.separation / length) : Vec3(Vec3::UnitY());
      force = -e * (im.axial + axial);
    }
    const Vec3 torque = angular_impulse(r, p);
    j.force = force * ctx.inv_h;
    j.torque = torque * ctx.inv_h;
    broke[row] = j.force.norm() > j.def.break_force;
  };
  // determinism: each row writes its own joint and flag (rule 1); the broken joints are listed
  // serially in row order.
  for_blocks(rows.size(), kPrepareGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t row = begin; row < end; ++row) store_row(row);
  });
  for (std::size_t row = 0; row < rows.size(); ++row) {
    if (broke[row]) broken.push_back(rows[row].joint);
  }
}

Real joint_coordinate(const Joint& j, const Vec3& c_a, const Quat& q_a, const Vec3& c_b,
                      const Quat& q_b) {
  const Quat frame_a = q_a * j.frame_a, frame_b = q_b * j.frame_b;
  const Vec3 p_a = c_a + q_a * j.anchor_a, p_b = c_b + q_b * j.anchor_b;
  switch (j.def.type) {
    case JointType::Hinge:
    case JointType::Cone:
      return twist_angle(relative_frame(frame_a, frame_b));
    case JointType::Slider:
      return (frame_b * Vec3::UnitX()).dot(p_a - p_b);
    case JointType::Distance:
      return (p_b - p_a).norm();
    case JointType::Ball:
    case JointType::Fixed:
      break;
  }
  return 0;
}

}  // namespace elan::detail
