// SPDX-License-Identifier: MIT
// Body state of the public API that issue 39 added: a body's shape, inertia, bounds, sensor flag,
// gravity scale and damping, the caller's user data on bodies, shapes and joints, and the changes
// of motion type, shape, sensor flag, gravity scale, damping and world gravity. All validated,
// all by id, all between steps.
#include <Eigen/Geometry>

#include <cmath>

#include "broadphase/bounds.hpp"
#include "core/base/range_checks.hpp"
#include "core/world/events.hpp"
#include "core/world/query_tree.hpp"
#include "core/world/recorder_hooks.hpp"
#include "core/world/sensors.hpp"
#include "core/world/shape_defs.hpp"
#include "core/world/world_access.hpp"
#include "elan/world.hpp"

namespace elan {

using detail::check_arg;
using detail::index_of;
using detail::WorldState;

namespace {

// A body's contacts end between steps (a change of motion type, shape or sensor flag): each
// touching manifold gets its end event now, as destroy_body gives them, and the dynamic partners
// wake. The next step finds the pairs again, as new contacts of the body as it now is.
void drop_contacts(WorldState& s, uint32_t i) {
  s.contacts.remove_body(i, i, [&](const detail::ManifoldHead& m) {
    if (m.point_count > 0) {
      s.api.end_events.push_back(
          {detail::body_id_at(s, m.body_a), detail::body_id_at(s, m.body_b)});
    }
    const uint32_t other = m.body_a == i ? m.body_b : m.body_a;
    if (s.bodies.is_dynamic(other)) detail::wake_index(s, other);
  });
}

// The mass a body has when dynamic: the one it was given (BodyDef::mass, set_mass), else its
// density times its shape's volume. elan::Error "mass" when out of range.
Real dynamic_mass(const WorldState& s, uint32_t slot, const detail::Shape& shape) {
  const detail::BodyExtra extra = detail::body_extra(s, slot);
  if (extra.given_mass > 0) return extra.given_mass;
  return detail::checked_mass(extra.density, shape.volume);
}

void set_dynamic_mass(detail::BodyStore& b, std::size_t i, Real mass, const detail::Shape& shape) {
  const Vec3 inv_inertia = detail::inverse_inertia(mass, shape.unit_inertia);
  b.inv_mass[i] = 1 / mass;
  b.inv_ix[i] = inv_inertia.x();
  b.inv_iy[i] = inv_inertia.y();
  b.inv_iz[i] = inv_inertia.z();
}

bool static_only(ShapeType t) {
  return t == ShapeType::Plane || t == ShapeType::Mesh || t == ShapeType::Heightfield;
}

}  // namespace

ShapeId World::shape(BodyId id) const {
  return ShapeId{state_->bodies.shape[index_of(*state_, id)]};
}

const ShapeDef& World::shape_def(ShapeId id) const {
  const WorldState& s = *state_;
  check_arg(detail::shape_live(s, id), "shape", "invalid or destroyed shape id");
  auto& defs = s.api.shape_defs;
  if (defs.size() < s.shapes.size()) defs.resize(s.shapes.size());
  if (!defs[id.index]) {
    defs[id.index] = std::make_unique<ShapeDef>(detail::shape_def_of(s.shapes[id.index]));
  }
  defs[id.index]->user_data = detail::shape_user_data(s, id.index);
  return *defs[id.index];
}

Mat3 World::inertia(BodyId id) const {
  const detail::BodyStore& b = state_->bodies;
  const std::size_t i = index_of(*state_, id);
  if (!b.is_dynamic(i)) return Mat3::Zero();
  // I = R diag(1 / inv_i) R^T, R the principal axes to world.
  const Mat3 r = b.orientation(i).toRotationMatrix();
  const Vec3 moments(1 / b.inv_ix[i], 1 / b.inv_iy[i], 1 / b.inv_iz[i]);
  return r * moments.asDiagonal() * r.transpose();
}

Aabb World::bounds(BodyId id) const {
  const WorldState& s = *state_;
  const std::size_t i = index_of(s, id);
  const detail::Aabb box =
      detail::shape_box(s.shapes[s.bodies.shape[i]], s.bodies.position(i), s.bodies.orientation(i));
  return Aabb{box.min, box.max};
}

bool World::is_sensor(BodyId id) const {
  return (state_->bodies.traits_of(index_of(*state_, id)).flags & detail::kTraitSensor) != 0;
}
Real World::gravity_scale(BodyId id) const {
  return state_->bodies.traits_of(index_of(*state_, id)).gravity_scale;
}
Real World::linear_damping(BodyId id) const {
  return state_->bodies.traits_of(index_of(*state_, id)).linear_damping;
}
Real World::angular_damping(BodyId id) const {
  return state_->bodies.traits_of(index_of(*state_, id)).angular_damping;
}

uint64_t World::user_data(BodyId id) const {
  index_of(*state_, id);
  return detail::body_extra(std::as_const(*state_), id.slot).user_data;
}
void World::set_user_data(BodyId id, uint64_t value) {
  ELAN_RECORDED(SetBodyUserData, set_user_data(id, value), id, value);
  index_of(*state_, id);
  detail::body_extra(*state_, id.slot).user_data = value;
}
uint64_t World::user_data(ShapeId id) const {
  check_arg(detail::shape_live(*state_, id), "shape", "invalid or destroyed shape id");
  return detail::shape_user_data(*state_, id.index);
}
void World::set_user_data(ShapeId id, uint64_t value) {
  ELAN_RECORDED(SetShapeUserData, set_user_data(id, value), id, value);
  WorldState& s = *state_;
  check_arg(detail::shape_live(s, id), "shape", "invalid or destroyed shape id");
  if (s.api.shape_user_data.size() < s.shapes.size()) s.api.shape_user_data.resize(s.shapes.size());
  s.api.shape_user_data[id.index] = value;
}
uint64_t World::user_data(JointId id) const {
  return joint_def(id).user_data;
}

void World::set_gravity_scale(BodyId id, Real scale) {
  ELAN_RECORDED(SetGravityScale, set_gravity_scale(id, scale), id, scale);
  check_arg(std::isfinite(scale), "gravity_scale", "must be finite");
  detail::check_range(scale, -limits::kMaxGravityScale, limits::kMaxGravityScale, "gravity_scale",
                      "");
  WorldState& s = *state_;
  const std::size_t i = index_of(s, id);
  detail::BodyTraits t = s.bodies.traits_of(i);
  t.gravity_scale = scale;
  s.bodies.set_traits(i, t);
  if (s.bodies.is_dynamic(i)) detail::wake_index(s, i);
}

void World::set_damping(BodyId id, Real linear, Real angular) {
  ELAN_RECORDED(SetDamping, set_damping(id, linear, angular), id, linear, angular);
  check_arg(std::isfinite(linear) && linear >= 0, "linear_damping", "must be finite and >= 0");
  check_arg(std::isfinite(angular) && angular >= 0, "angular_damping", "must be finite and >= 0");
  WorldState& s = *state_;
  const std::size_t i = index_of(s, id);
  detail::BodyTraits t = s.bodies.traits_of(i);
  t.linear_damping = linear;
  t.angular_damping = angular;
  s.bodies.set_traits(i, t);
  if (s.bodies.is_dynamic(i)) detail::wake_index(s, i);
}

void World::set_gravity(const Vec3& gravity) {
  ELAN_RECORDED(SetGravity, set_gravity(gravity), gravity);
  check_arg(gravity.allFinite(), "gravity", "must be finite");
  detail::check_length(gravity, limits::kMaxGravity, "gravity", "m/s^2");
  WorldState& s = *state_;
  s.def.gravity = gravity;
  // Bodies asleep under the old gravity may not rest under the new one.
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    if (s.bodies.is_dynamic(i)) detail::wake_index(s, i);
  }
}

void World::set_sensor(BodyId id, bool sensor) {
  ELAN_RECORDED(SetSensor, set_sensor(id, sensor), id, sensor);
  WorldState& s = *state_;
  const uint32_t i = uint32_t(index_of(s, id));
  detail::BodyTraits t = s.bodies.traits_of(i);
  if (((t.flags & detail::kTraitSensor) != 0) == sensor) return;
  t.flags = sensor ? (t.flags | detail::kTraitSensor) : (t.flags & ~detail::kTraitSensor);
  // A new sensor's contacts end; a body that stops being a sensor ends its overlaps (and, as a
  // sensor, had no contacts). Either way the next step finds its pairs as what it now is.
  drop_contacts(s, i);
  detail::sensor_remove_body(s, i, i);
  s.bodies.set_traits(i, t);
  if (s.bodies.is_dynamic(i)) detail::wake_index(s, i);
  detail::query_tree_update(s, uint32_t(i));
}

void World::set_motion_type(BodyId id, MotionType type) {
  ELAN_RECORDED(SetMotionType, set_motion_type(id, type), id, type);
  WorldState& s = *state_;
  const uint32_t i = uint32_t(index_of(s, id));
  check_arg(
      type == MotionType::Static || type == MotionType::Kinematic || type == MotionType::Dynamic,
      "motion", "unknown motion type");
  detail::BodyStore& b = s.bodies;
  if (MotionType(b.motion[i]) == type) return;
  const detail::Shape& shape = s.shapes[b.shape[i]];
  if (type != MotionType::Static) {
    check_arg(!static_only(shape.type), "motion",
              "a plane, mesh or heightfield body must be static");
  }
  if (type != MotionType::Dynamic) {
    // Every joint needs a dynamic body (create_joint's rule).
    for (const detail::Joint& j : s.joints.joints) {
      if (j.slot_a != id.slot && j.slot_b != id.slot) continue;
      const uint32_t other = j.slot_a == id.slot ? j.slot_b : j.slot_a;
      const bool other_dynamic = other != detail::kWorldSlot && b.is_dynamic(s.slot_index[other]);
      check_arg(other_dynamic, "motion", "a joint of this body would have no dynamic body");
    }
  }
  // Checked before anything changes: the mass a dynamic body gets.
  const Real mass = type == MotionType::Dynamic ? dynamic_mass(s, id.slot, shape) : 0;
  drop_contacts(s, i);
  detail::wake_sensor_partners(s, i);
  b.motion[i] = uint8_t(type);
  const uint8_t frozen = b.flags[i] & detail::kFrozen;
  switch (type) {
    case MotionType::Dynamic:
      set_dynamic_mass(b, i, mass, shape);
      b.flags[i] = frozen | detail::kAwake;
      break;
    case MotionType::Kinematic:
      b.inv_mass[i] = b.inv_ix[i] = b.inv_iy[i] = b.inv_iz[i] = 0;
      b.flags[i] = frozen | detail::kAwake;
      break;
    case MotionType::Static:
      b.inv_mass[i] = b.inv_ix[i] = b.inv_iy[i] = b.inv_iz[i] = 0;
      b.set_linear_velocity(i, Vec3::Zero());
      b.set_angular_velocity(i, Vec3::Zero());
      b.flags[i] = frozen;
      break;
  }
  b.sleep_time[i] = 0;
  // Forces wait for a dynamic body's next step; other bodies take none.
  if (type != MotionType::Dynamic) b.drop_forces_if([i](uint32_t body) { return body == i; });
  detail::query_tree_update(s, uint32_t(i));
}

void World::set_shape(BodyId id, ShapeId shape_id) {
  ELAN_RECORDED(SetShape, set_shape(id, shape_id), id, shape_id);
  WorldState& s = *state_;
  const uint32_t i = uint32_t(index_of(s, id));
  check_arg(detail::shape_live(s, shape_id), "shape", "invalid or destroyed shape id");
  detail::BodyStore& b = s.bodies;
  const detail::Shape& old_shape = s.shapes[b.shape[i]];
  const detail::Shape& shape = s.shapes[shape_id.index];
  if (!b.is_static(i)) {
    check_arg(!static_only(shape.type), "shape",
              "a plane, mesh or heightfield shape needs a static body");
  }
  // The mass at the body's density: a given mass sets the density it has in its old shape.
  detail::BodyExtra& extra = detail::body_extra(s, id.slot);
  Real density = extra.density;
  if (extra.given_mass > 0 && old_shape.volume > 0) {
    density = Real(double(extra.given_mass) / double(old_shape.volume));
  }
  Real mass = 0;
  if (b.is_dynamic(i)) mass = detail::checked_mass(density, shape.volume);
  extra.density = density;
  extra.given_mass = 0;

  // The shape frame stays where it is; the principal frame moves with the new shape's.
  const Vec3 position = this->position(id);
  const Quat rotation = orientation(id);
  const Vec3 old_centre = b.position(i);
  const Quat old_q = b.orientation(i);
  drop_contacts(s, i);
  detail::wake_sensor_partners(s, i);
  b.shape[i] = shape_id.index;
  b.set_position(i, position + rotation * shape.frame_position);
  b.set_orientation(i, (rotation * shape.frame_rotation).normalized());
  if (b.is_dynamic(i)) set_dynamic_mass(b, i, mass, shape);
  // Joints keep their world anchors and frames: re-expressed in the new principal frame.
  const Vec3 centre = b.position(i);
  const Quat q = b.orientation(i);
  for (detail::Joint& j : s.joints.joints) {
    if (j.slot_a == id.slot) {
      j.anchor_a = q.conjugate() * (old_centre + old_q * j.anchor_a - centre);
      j.frame_a = (q.conjugate() * old_q * j.frame_a).normalized();
    }
    if (j.slot_b == id.slot) {
      j.anchor_b = q.conjugate() * (old_centre + old_q * j.anchor_b - centre);
      j.frame_b = (q.conjugate() * old_q * j.frame_b).normalized();
    }
  }
  detail::wake_index(s, i);
  detail::query_tree_update(s, uint32_t(i));
}

}  // namespace elan
