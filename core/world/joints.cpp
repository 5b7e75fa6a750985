// SPDX-License-Identifier: MIT
// The public joint API (create, destroy, setters, readings, events) and the world's joint stages.
#include "core/world/joints.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/base/id_slots.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/range_checks.hpp"
#include "core/base/rotation_between.hpp"
#include "core/world/events.hpp"
#include "core/world/world_access.hpp"
#include "elan/limits.hpp"
#include "elan/world.hpp"
#include "solver/joint_solver.hpp"

namespace elan {

using detail::check_arg;
using detail::Joint;
using detail::JointStore;
using detail::kWorldSlot;
using detail::WorldState;

namespace {

constexpr Real kPi = Real(3.14159265358979323846);

std::size_t joint_index(const WorldState& s, JointId id) {
  const JointStore& js = s.joints;
  if (!detail::slot_live(js.slot_index, js.slot_generation, id.slot, id.generation)) {
    throw Error("joint", "invalid or removed joint id");
  }
  return js.slot_index[id.slot];
}

void check_limits(const JointDef& def, const JointLimits& l) {
  if (!l.enabled) return;
  check_arg(std::isfinite(l.lower) && std::isfinite(l.upper), "limits", "must be finite");
  check_arg(l.lower <= l.upper, "limits",
            "lower " + detail::show_value(l.lower) + " > upper " + detail::show_value(l.upper));
  if (def.type == JointType::Hinge || def.type == JointType::Cone) {
    check_arg(l.lower >= -kPi && l.upper <= kPi, "limits", "angles must be within [-pi, pi]");
  } else {
    detail::check_range(l.lower, -2 * limits::kMaxPosition, 2 * limits::kMaxPosition, "limits",
                        "m");
    detail::check_range(l.upper, -2 * limits::kMaxPosition, 2 * limits::kMaxPosition, "limits",
                        "m");
  }
}

void check_motor(const JointMotor& m) {
  if (!m.enabled) return;
  check_arg(std::isfinite(m.speed), "motor.speed", "must be finite");
  check_arg(std::isfinite(m.max_force) && m.max_force >= 0, "motor.max_force",
            "must be finite and >= 0, got " + detail::show_value(m.max_force));
}

void check_spring(const JointSpring& sp) {
  if (!sp.enabled) return;
  check_arg(std::isfinite(sp.frequency) && sp.frequency > 0, "spring.frequency",
            "must be finite and > 0, got " + detail::show_value(sp.frequency));
  check_arg(std::isfinite(sp.damping_ratio) && sp.damping_ratio >= 0, "spring.damping_ratio",
            "must be finite and >= 0, got " + detail::show_value(sp.damping_ratio));
  check_arg(std::isfinite(sp.target), "spring.target", "must be finite");
}

void check_swing(Real swing) {
  check_arg(std::isfinite(swing) && swing >= 0 && swing <= kPi, "swing_limit",
            "must be within [0, pi], got " + detail::show_value(swing));
}

void check_lengths(Real min_length, Real max_length) {
  check_arg(std::isfinite(min_length) && std::isfinite(max_length), "min_length", "must be finite");
  if (min_length >= 0 && max_length >= 0) {
    check_arg(min_length <= max_length, "min_length",
              "min_length " + detail::show_value(min_length) + " > max_length " +
                  detail::show_value(max_length));
  }
}

// The pose (centre of mass, principal frame) of a side; the world's is the identity.
struct SidePose {
  Vec3 c = Vec3::Zero();
  Quat q = Quat::Identity();
};
SidePose side_pose(const WorldState& s, uint32_t slot) {
  if (slot == kWorldSlot) return {};
  const uint32_t i = s.slot_index[slot];
  return {s.bodies.position(i), s.bodies.orientation(i)};
}

void wake_joint_bodies(WorldState& s, const Joint& j) {
  if (j.slot_a != kWorldSlot) detail::wake_index(s, s.slot_index[j.slot_a]);
  if (j.slot_b != kWorldSlot) detail::wake_index(s, s.slot_index[j.slot_b]);
}

BodyId body_of_slot(const WorldState& s, uint32_t slot) {
  return slot == kWorldSlot ? BodyId{} : BodyId{slot, s.slot_generation[slot]};
}

}  // namespace

JointId World::create_joint(const JointDef& def) {
  WorldState& s = *state_;
  JointStore& js = s.joints;
  check_arg(js.size() < detail::kMaxBodyCount, "joint", "too many joints");
  std::size_t ia = 0;
  try {
    ia = detail::index_of(s, def.body_a);
  } catch (const Error&) {
    throw Error("body_a", "invalid or destroyed body id");
  }
  std::size_t ib = SIZE_MAX;
  if (!def.body_b.is_null()) {
    try {
      ib = detail::index_of(s, def.body_b);
    } catch (const Error&) {
      throw Error("body_b", "invalid or destroyed body id");
    }
    check_arg(ib != ia, "body_b", "the same body as body_a");
  }
  const bool dynamic_a = s.bodies.is_dynamic(ia);
  const bool dynamic_b = ib != SIZE_MAX && s.bodies.is_dynamic(ib);
  check_arg(dynamic_a || dynamic_b, "bodies", "at least one body must be dynamic");
  check_arg(def.anchor.allFinite(), "anchor", "must be finite");
  detail::check_coordinates(def.anchor, limits::kMaxPosition, "anchor", "m");
  if (def.type == JointType::Distance) {
    check_arg(def.anchor_b.allFinite(), "anchor_b", "must be finite");
    detail::check_coordinates(def.anchor_b, limits::kMaxPosition, "anchor_b", "m");
  }
  const bool needs_axis =
      def.type == JointType::Hinge || def.type == JointType::Slider || def.type == JointType::Cone;
  if (needs_axis) {
    check_arg(def.axis.allFinite(), "axis", "must be finite");
    check_arg(def.axis.norm() > Real(1e-9), "axis", "zero axis");
  }
  check_limits(def, def.limits);
  check_motor(def.motor);
  check_spring(def.spring);
  if (def.type == JointType::Cone) check_swing(def.swing_limit);
  if (def.type == JointType::Distance) check_lengths(def.min_length, def.max_length);
  check_arg(std::isfinite(def.friction) && def.friction >= 0, "friction",
            "must be finite and >= 0, got " + detail::show_value(def.friction));
  check_arg(std::isfinite(def.constraint_hertz) && def.constraint_hertz >= 0, "constraint_hertz",
            "must be finite and >= 0, got " + detail::show_value(def.constraint_hertz));
  check_arg(std::isfinite(def.constraint_damping_ratio) && def.constraint_damping_ratio >= 0,
            "constraint_damping_ratio",
            "must be finite and >= 0, got " + detail::show_value(def.constraint_damping_ratio));
  check_arg(!std::isnan(def.break_force) && def.break_force > 0, "break_force",
            "must be > 0, got " + detail::show_value(def.break_force));

  Joint j;
  j.def = def;
  j.slot_a = def.body_a.slot;
  j.slot_b = def.body_b.is_null() ? kWorldSlot : def.body_b.slot;
  const SidePose a = side_pose(s, j.slot_a), b = side_pose(s, j.slot_b);
  Vec3 anchor = def.anchor;
  if (def.type == JointType::Fixed && !def.has_anchor) {
    // The midpoint of the two shape frames (the world's is its origin).
    const Vec3 pa = position(def.body_a);
    const Vec3 pb = def.body_b.is_null() ? Vec3::Zero() : position(def.body_b);
    anchor = def.body_b.is_null() ? pa : Vec3((pa + pb) / 2);
    j.def.anchor = anchor;
    j.def.has_anchor = true;
  }
  const Vec3 anchor_b = def.type == JointType::Distance ? def.anchor_b : anchor;
  j.anchor_a = a.q.conjugate() * (anchor - a.c);
  j.anchor_b = b.q.conjugate() * (anchor_b - b.c);
  // The joint frame, x along the axis, shared by both sides at creation.
  const Vec3 axis = needs_axis ? Vec3(def.axis.normalized()) : Vec3(Vec3::UnitX());
  j.def.axis = axis;
  const Quat frame = detail::rotation_between(Vec3::UnitX(), axis).normalized();
  j.frame_a = (a.q.conjugate() * frame).normalized();
  j.frame_b = (b.q.conjugate() * frame).normalized();
  if (def.type == JointType::Distance) {
    const Real load = (anchor_b - anchor).norm();
    j.min_length = def.min_length >= 0 ? def.min_length : load;
    j.max_length = def.max_length >= 0 ? def.max_length : load;
    check_arg(j.min_length <= j.max_length, "min_length",
              "min_length " + detail::show_value(j.min_length) + " > max_length " +
                  detail::show_value(j.max_length));
    j.rest_length = def.spring.enabled && def.spring.target >= 0 ? def.spring.target : load;
  }

  const uint32_t slot = detail::take_slot(js.slot_index, js.slot_generation, js.free_slots,
                                          uint32_t(js.joints.size()));
  j.slot = slot;
  js.joints.push_back(j);
  ++js.version;
  wake_joint_bodies(s, j);
  return JointId{slot, js.slot_generation[slot]};
}

void World::destroy_joint(JointId id) {
  WorldState& s = *state_;
  const std::size_t k = joint_index(s, id);
  wake_joint_bodies(s, s.joints.joints[k]);
  detail::remove_joint(s, uint32_t(k));
}

bool World::is_valid(JointId id) const {
  const JointStore& js = state_->joints;
  return detail::slot_live(js.slot_index, js.slot_generation, id.slot, id.generation);
}

std::size_t World::joint_count() const {
  return state_->joints.size();
}

JointId World::joint_at(std::size_t index) const {
  const JointStore& js = state_->joints;
  if (index >= js.size()) throw Error("index", "joint index out of range");
  const uint32_t slot = js.joints[index].slot;
  return JointId{slot, js.slot_generation[slot]};
}

const JointDef& World::joint_def(JointId id) const {
  return state_->joints.joints[joint_index(*state_, id)].def;
}

void World::set_user_data(JointId id, uint64_t value) {
  WorldState& s = *state_;
  s.joints.joints[joint_index(s, id)].def.user_data = value;
}

void World::set_joint_motor(JointId id, const JointMotor& motor) {
  WorldState& s = *state_;
  Joint& j = s.joints.joints[joint_index(s, id)];
  check_motor(motor);
  j.def.motor = motor;
  wake_joint_bodies(s, j);
}

void World::set_joint_spring(JointId id, const JointSpring& spring) {
  WorldState& s = *state_;
  Joint& j = s.joints.joints[joint_index(s, id)];
  check_spring(spring);
  j.def.spring = spring;
  if (j.def.type == JointType::Distance && spring.enabled && spring.target >= 0) {
    j.rest_length = spring.target;
  }
  wake_joint_bodies(s, j);
}

void World::set_joint_limits(JointId id, const JointLimits& limits) {
  WorldState& s = *state_;
  Joint& j = s.joints.joints[joint_index(s, id)];
  check_limits(j.def, limits);
  j.def.limits = limits;
  wake_joint_bodies(s, j);
}

void World::set_joint_swing_limit(JointId id, Real swing_limit) {
  WorldState& s = *state_;
  Joint& j = s.joints.joints[joint_index(s, id)];
  check_swing(swing_limit);
  j.def.swing_limit = swing_limit;
  wake_joint_bodies(s, j);
}

void World::set_joint_lengths(JointId id, Real min_length, Real max_length) {
  WorldState& s = *state_;
  Joint& j = s.joints.joints[joint_index(s, id)];
  check_arg(std::isfinite(min_length) && min_length >= 0, "min_length", "must be finite and >= 0");
  check_arg(std::isfinite(max_length) && max_length >= 0, "max_length", "must be finite and >= 0");
  check_lengths(min_length, max_length);
  j.def.min_length = j.min_length = min_length;
  j.def.max_length = j.max_length = max_length;
  wake_joint_bodies(s, j);
}

void World::set_joint_friction(JointId id, Real friction) {
  WorldState& s = *state_;
  Joint& j = s.joints.joints[joint_index(s, id)];
  check_arg(std::isfinite(friction) && friction >= 0, "friction",
            "must be finite and >= 0, got " + detail::show_value(friction));
  j.def.friction = friction;
  wake_joint_bodies(s, j);
}

Vec3 World::joint_force(JointId id) const {
  return state_->joints.joints[joint_index(*state_, id)].force;
}

Vec3 World::joint_torque(JointId id) const {
  return state_->joints.joints[joint_index(*state_, id)].torque;
}

Real World::joint_coordinate(JointId id) const {
  const WorldState& s = *state_;
  const Joint& j = s.joints.joints[joint_index(s, id)];
  const SidePose a = side_pose(s, j.slot_a), b = side_pose(s, j.slot_b);
  return detail::joint_coordinate(j, a.c, a.q, b.c, b.q);
}

std::span<const JointRemovedEvent> World::joint_removed_events() const {
  return state_->api.joint_events;
}

namespace detail {

void drop_jointed_pairs(WorldState& w) {
  if (w.joints.empty()) return;
  if (w.unconnected_version != w.joints.version) {
    w.unconnected_pairs.clear();
    for (const Joint& j : w.joints.joints) {
      if (j.def.collide_connected || j.slot_a == kWorldSlot || j.slot_b == kWorldSlot) continue;
      w.unconnected_pairs.push_back(make_pair_key(w.slot_index[j.slot_a], w.slot_index[j.slot_b]));
    }
    std::sort(w.unconnected_pairs.begin(), w.unconnected_pairs.end());
    w.unconnected_pairs.erase(std::unique(w.unconnected_pairs.begin(), w.unconnected_pairs.end()),
                              w.unconnected_pairs.end());
    w.unconnected_version = w.joints.version;
  }
  if (w.unconnected_pairs.empty()) return;
  // Both lists sorted: one merge.
  std::size_t kept = 0;
  auto next = w.unconnected_pairs.begin();
  const auto end = w.unconnected_pairs.end();
  for (std::size_t k = 0; k < w.pairs.size(); ++k) {
    const uint64_t key = w.pairs[k];
    while (next != end && *next < key) ++next;
    if (next != end && *next == key) continue;
    w.pairs[kept++] = key;
  }
  w.pairs.resize(kept);
}

void remove_joint(WorldState& w, uint32_t k) {
  JointStore& js = w.joints;
  const uint32_t slot = js.joints[k].slot;
  const uint32_t last = uint32_t(js.size() - 1);
  if (k != last) {
    js.joints[k] = js.joints[last];
    js.slot_index[js.joints[k].slot] = k;
  }
  js.joints.pop_back();
  release_slot(js.slot_index, js.slot_generation, js.free_slots, slot);
  ++js.version;
}

void remove_joints_of(WorldState& w, uint32_t slot) {
  JointStore& js = w.joints;
  // determinism: events in joint order; removing from the back keeps the lower indices stable.
  std::size_t first_event = w.api.joint_events.size();
  for (std::size_t k = js.size(); k-- > 0;) {
    const Joint& j = js.joints[k];
    if (j.slot_a != slot && j.slot_b != slot) continue;
    w.api.joint_events.push_back({JointId{j.slot, js.slot_generation[j.slot]},
                                  body_of_slot(w, j.slot_a), body_of_slot(w, j.slot_b),
                                  JointRemoval::BodyDestroyed, 0});
    const uint32_t other = j.slot_a == slot ? j.slot_b : j.slot_a;
    if (other != kWorldSlot) wake_index(w, w.slot_index[other]);
    remove_joint(w, uint32_t(k));
  }
  std::reverse(w.api.joint_events.begin() + std::ptrdiff_t(first_event), w.api.joint_events.end());
}

void remove_broken_joints(WorldState& w) {
  JointStore& js = w.joints;
  // The rows list them group by group; events and removals go by joint index.
  std::sort(w.broken_joints.begin(), w.broken_joints.end());
  for (const uint32_t k : w.broken_joints) {
    const Joint& j = js.joints[k];
    w.api.joint_events.push_back({JointId{j.slot, js.slot_generation[j.slot]},
                                  body_of_slot(w, j.slot_a), body_of_slot(w, j.slot_b),
                                  JointRemoval::Broke, j.force.norm()});
    wake_joint_bodies(w, j);
  }
  // From the back, so each removal leaves the lower listed indices in place.
  for (std::size_t n = w.broken_joints.size(); n-- > 0;) remove_joint(w, w.broken_joints[n]);
  w.broken_joints.clear();
}

}  // namespace detail

}  // namespace elan
