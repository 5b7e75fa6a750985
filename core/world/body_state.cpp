// SPDX-License-Identifier: MIT
// Body state of the public API that issue 39 added: a body's shape, inertia, bounds, sensor flag,
// gravity scale and damping, the caller's user data on bodies, shapes and joints, and the changes
// of motion type, shape, sensor flag, gravity scale, damping and world gravity. All validated,
// all by id, all between steps.
#include <Eigen/Geometry>

#include <cmath>

#include "broadphase/bounds.hpp"
#include "core/base/range_checks.hpp"
#include "core/world/shape_defs.hpp"
#include "core/world/world_access.hpp"
#include "elan/world.hpp"

namespace elan {

using detail::check_arg;
using detail::index_of;
using detail::WorldState;

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
  index_of(*state_, id);
  detail::body_extra(*state_, id.slot).user_data = value;
}
uint64_t World::user_data(ShapeId id) const {
  check_arg(detail::shape_live(*state_, id), "shape", "invalid or destroyed shape id");
  return detail::shape_user_data(*state_, id.index);
}
void World::set_user_data(ShapeId id, uint64_t value) {
  WorldState& s = *state_;
  check_arg(detail::shape_live(s, id), "shape", "invalid or destroyed shape id");
  if (s.api.shape_user_data.size() < s.shapes.size()) s.api.shape_user_data.resize(s.shapes.size());
  s.api.shape_user_data[id.index] = value;
}
uint64_t World::user_data(JointId id) const {
  return joint_def(id).user_data;
}

}  // namespace elan
