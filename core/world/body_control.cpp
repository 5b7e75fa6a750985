// SPDX-License-Identifier: MIT
// Per-body control of the public API between steps: pose, velocities, forces and impulses,
// kinematic targets, sleep, material, mass and filter bits. All validated, all by id.
#include <Eigen/Geometry>

#include <cmath>

#include "core/base/fixed_math.hpp"
#include "core/base/range_checks.hpp"
#include "core/world/recorder_hooks.hpp"
#include "core/world/sensors.hpp"
#include "core/world/world_access.hpp"
#include "elan/world.hpp"

namespace elan {

using detail::check_arg;
using detail::index_of;
using detail::WorldState;

namespace {

void check_vec(const Vec3& v, const char* field) {
  check_arg(v.allFinite(), field, "must be finite");
}

void check_position(const Vec3& p, const char* field) {
  check_vec(p, field);
  detail::check_coordinates(p, limits::kMaxPosition, field, "m");
}

void check_linear_velocity(const Vec3& v, const char* field) {
  check_vec(v, field);
  detail::check_length(v, limits::kMaxLinearSpeed, field, "m/s");
}

void check_angular_velocity(const Vec3& w, const char* field) {
  check_vec(w, field);
  detail::check_length(w, limits::kMaxAngularSpeed, field, "rad/s");
}

Quat checked_rotation(const Quat& q, const char* field) {
  check_arg(q.coeffs().allFinite(), field, "must be finite");
  check_arg(q.norm() > Real(1e-12), field, "zero quaternion");
  return q.normalized();
}

// World inverse inertia applied to a vector: R diag(inv_i) R^T x, R the principal axes.
Vec3 apply_inv_inertia(const detail::BodyStore& b, std::size_t i, const Vec3& x) {
  const Quat q = b.orientation(i);
  const Vec3 local = q.conjugate() * x;
  return q * Vec3(b.inv_ix[i] * local.x(), b.inv_iy[i] * local.y(), b.inv_iz[i] * local.z());
}

// Stores a shape-frame pose as the principal-frame pose the store keeps.
void store_pose(WorldState& s, std::size_t i, const Vec3& position, const Quat& rotation) {
  const detail::Shape& shape = s.shapes[s.bodies.shape[i]];
  s.bodies.set_position(i, position + rotation * shape.frame_position);
  s.bodies.set_orientation(i, (rotation * shape.frame_rotation).normalized());
  if (s.bodies.is_dynamic(i)) {
    s.bodies.flags[i] |= detail::kPlaced;
    s.bodies_placed = true;
  }
  detail::wake_index(s, i);
  detail::wake_sensor_partners(s, uint32_t(i));
  detail::query_tree_update(s, uint32_t(i));
}

}  // namespace

Real World::friction(BodyId id) const {
  return state_->bodies.traits_of(index_of(*state_, id)).friction;
}
Real World::restitution(BodyId id) const {
  return state_->bodies.traits_of(index_of(*state_, id)).restitution;
}
uint32_t World::category_bits(BodyId id) const {
  return state_->bodies.traits_of(index_of(*state_, id)).category;
}
uint32_t World::mask_bits(BodyId id) const {
  return state_->bodies.traits_of(index_of(*state_, id)).mask;
}

void World::set_linear_velocity(BodyId id, const Vec3& v) {
  ELAN_RECORDED(SetLinearVelocity, set_linear_velocity(id, v), id, v);
  check_linear_velocity(v, "linear_velocity");
  const std::size_t i = index_of(*state_, id);
  if (state_->bodies.is_static(i)) return;
  state_->bodies.set_linear_velocity(i, v);
  detail::wake_index(*state_, i);
}

void World::set_angular_velocity(BodyId id, const Vec3& w) {
  ELAN_RECORDED(SetAngularVelocity, set_angular_velocity(id, w), id, w);
  check_angular_velocity(w, "angular_velocity");
  const std::size_t i = index_of(*state_, id);
  if (state_->bodies.is_static(i)) return;
  state_->bodies.set_angular_velocity(i, w);
  detail::wake_index(*state_, i);
}

void World::set_position(BodyId id, const Vec3& position) {
  ELAN_RECORDED(SetPosition, set_position(id, position), id, position);
  check_position(position, "position");
  const std::size_t i = index_of(*state_, id);
  store_pose(*state_, i, position, orientation(id));
}

void World::set_orientation(BodyId id, const Quat& orientation) {
  ELAN_RECORDED(SetOrientation, set_orientation(id, orientation), id, orientation);
  const Quat q = checked_rotation(orientation, "orientation");
  const std::size_t i = index_of(*state_, id);
  store_pose(*state_, i, position(id), q);
}

void World::set_transform(BodyId id, const Transform& pose) {
  ELAN_RECORDED(SetTransform, set_transform(id, pose), id, pose);
  check_position(pose.position, "position");
  const Quat q = checked_rotation(pose.rotation, "orientation");
  store_pose(*state_, index_of(*state_, id), pose.position, q);
}

void World::apply_force(BodyId id, const Vec3& force) {
  ELAN_RECORDED(ApplyForce, apply_force(id, force), id, force);
  check_vec(force, "force");
  detail::BodyStore& b = state_->bodies;
  const std::size_t i = index_of(*state_, id);
  if (!b.is_dynamic(i)) return;
  b.applied_force(i).force += force;
  detail::wake_index(*state_, i);
}

void World::apply_force_at(BodyId id, const Vec3& force, const Vec3& point) {
  ELAN_RECORDED(ApplyForceAt, apply_force_at(id, force, point), id, force, point);
  check_vec(force, "force");
  check_vec(point, "point");
  const std::size_t i = index_of(*state_, id);
  apply_force(id, force);
  apply_torque(id, (point - state_->bodies.position(i)).cross(force));
}

void World::apply_torque(BodyId id, const Vec3& torque) {
  ELAN_RECORDED(ApplyTorque, apply_torque(id, torque), id, torque);
  check_vec(torque, "torque");
  detail::BodyStore& b = state_->bodies;
  const std::size_t i = index_of(*state_, id);
  if (!b.is_dynamic(i)) return;
  b.applied_force(i).torque += torque;
  detail::wake_index(*state_, i);
}

void World::apply_impulse(BodyId id, const Vec3& impulse, const Vec3& point) {
  ELAN_RECORDED(ApplyImpulse, apply_impulse(id, impulse, point), id, impulse, point);
  check_vec(impulse, "impulse");
  check_vec(point, "point");
  const std::size_t i = index_of(*state_, id);
  const detail::BodyStore& b = state_->bodies;
  const Vec3 angular = (point - b.position(i)).cross(impulse);
  // Both halves checked before either is applied, so a refused impulse changes nothing.
  if (b.is_dynamic(i)) {
    check_angular_velocity(b.angular_velocity(i) + apply_inv_inertia(b, i, angular), "impulse");
  }
  apply_linear_impulse(id, impulse);
  apply_angular_impulse(id, angular);
}

void World::apply_linear_impulse(BodyId id, const Vec3& impulse) {
  ELAN_RECORDED(ApplyLinearImpulse, apply_linear_impulse(id, impulse), id, impulse);
  check_vec(impulse, "impulse");
  detail::BodyStore& b = state_->bodies;
  const std::size_t i = index_of(*state_, id);
  if (!b.is_dynamic(i)) return;
  const Vec3 v = b.linear_velocity(i) + b.inv_mass[i] * impulse;
  check_linear_velocity(v, "impulse");
  b.set_linear_velocity(i, v);
  detail::wake_index(*state_, i);
}

void World::apply_angular_impulse(BodyId id, const Vec3& impulse) {
  ELAN_RECORDED(ApplyAngularImpulse, apply_angular_impulse(id, impulse), id, impulse);
  check_vec(impulse, "angular_impulse");
  detail::BodyStore& b = state_->bodies;
  const std::size_t i = index_of(*state_, id);
  if (!b.is_dynamic(i)) return;
  const Vec3 w = b.angular_velocity(i) + apply_inv_inertia(b, i, impulse);
  check_angular_velocity(w, "angular_impulse");
  b.set_angular_velocity(i, w);
  detail::wake_index(*state_, i);
}

void World::move_kinematic(BodyId id, const Transform& target, Real dt) {
  ELAN_RECORDED(MoveKinematic, move_kinematic(id, target, dt), id, target, dt);
  check_position(target.position, "target.position");
  const Quat q_target = checked_rotation(target.rotation, "target.rotation");
  check_arg(std::isfinite(dt) && dt > 0, "dt", "must be finite and positive");
  WorldState& s = *state_;
  const std::size_t i = index_of(s, id);
  check_arg(s.bodies.motion[i] == uint8_t(MotionType::Kinematic), "body", "not kinematic");
  const detail::Shape& shape = s.shapes[s.bodies.shape[i]];
  // The centre of mass travels in a straight line and the principal frame turns about it, so
  // both must reach the target's: v = dx / dt, w = axis * angle / dt of dq = q1 q0^-1.
  const Vec3 com_target = target.position + q_target * shape.frame_position;
  const Quat q1 = (q_target * shape.frame_rotation).normalized();
  Quat dq = q1 * s.bodies.orientation(i).conjugate();
  if (dq.w() < 0) dq.coeffs() = -dq.coeffs();  // the shorter arc
  // angle = 2 atan2(|v|, w) of the unit dq = (w, v), axis v / |v|, as Eigen's AngleAxis reads a
  // quaternion, but with the engine's own atan2 (determinism, rule 7: the C library's is not the
  // same on every CPU).
  const Quat u = dq.normalized();
  const Real n = u.vec().norm();
  const Real angle = n > 0 ? Real(2 * detail::fixed_atan2(double(n), double(u.w()))) : Real(0);
  const Vec3 axis = n > 0 ? Vec3(u.vec() / n) : Vec3::UnitX();
  s.bodies.set_linear_velocity(i, (com_target - s.bodies.position(i)) / dt);
  s.bodies.set_angular_velocity(i, axis * (angle / dt));
}

void World::wake(BodyId id) {
  ELAN_RECORDED(Wake, wake(id), id);
  const std::size_t i = index_of(*state_, id);
  if (state_->bodies.is_dynamic(i)) detail::wake_index(*state_, i);
}

void World::sleep(BodyId id) {
  ELAN_RECORDED(Sleep, sleep(id), id);
  detail::BodyStore& b = state_->bodies;
  const std::size_t i = index_of(*state_, id);
  if (!b.is_dynamic(i)) return;
  b.flags[i] &= uint8_t(~detail::kAwake);
  b.set_linear_velocity(i, Vec3::Zero());
  b.set_angular_velocity(i, Vec3::Zero());
  b.sleep_time[i] = 0;
}

void World::set_friction(BodyId id, Real friction) {
  ELAN_RECORDED(SetFriction, set_friction(id, friction), id, friction);
  check_arg(std::isfinite(friction) && friction >= 0, "friction", "must be finite and >= 0");
  detail::check_range(friction, 0, limits::kMaxFriction, "friction", "");
  detail::BodyStore& b = state_->bodies;
  const std::size_t i = index_of(*state_, id);
  detail::BodyTraits t = b.traits_of(i);
  t.friction = friction;
  b.set_traits(i, t);
}

void World::set_restitution(BodyId id, Real restitution) {
  ELAN_RECORDED(SetRestitution, set_restitution(id, restitution), id, restitution);
  check_arg(std::isfinite(restitution) && restitution >= 0, "restitution",
            "must be finite and >= 0");
  detail::check_range(restitution, 0, limits::kMaxRestitution, "restitution", "");
  detail::BodyStore& b = state_->bodies;
  const std::size_t i = index_of(*state_, id);
  detail::BodyTraits t = b.traits_of(i);
  t.restitution = restitution;
  b.set_traits(i, t);
}

void World::set_mass(BodyId id, Real mass) {
  ELAN_RECORDED(SetMass, set_mass(id, mass), id, mass);
  check_arg(std::isfinite(mass) && mass > 0, "mass", "must be finite and positive");
  detail::check_range(mass, limits::kMinMass, limits::kMaxMass, "mass", "kg");
  WorldState& s = *state_;
  const std::size_t i = index_of(s, id);
  check_arg(s.bodies.is_dynamic(i), "body", "mass applies to dynamic bodies only");
  const Vec3 inv_inertia = detail::inverse_inertia(mass, s.shapes[s.bodies.shape[i]].unit_inertia);
  detail::body_extra(s, id.slot).given_mass = mass;
  s.bodies.inv_mass[i] = 1 / mass;
  s.bodies.inv_ix[i] = inv_inertia.x();
  s.bodies.inv_iy[i] = inv_inertia.y();
  s.bodies.inv_iz[i] = inv_inertia.z();
}

void World::set_collision_filter(BodyId id, uint32_t category_bits, uint32_t mask_bits) {
  ELAN_RECORDED(SetCollisionFilter, set_collision_filter(id, category_bits, mask_bits), id,
                category_bits, mask_bits);
  detail::BodyStore& b = state_->bodies;
  const std::size_t i = index_of(*state_, id);
  detail::BodyTraits t = b.traits_of(i);
  t.category = category_bits;
  t.mask = mask_bits;
  b.set_traits(i, t);
}

}  // namespace elan
