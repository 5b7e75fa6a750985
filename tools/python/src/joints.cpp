// SPDX-License-Identifier: MIT
// Joints: creation with keyword arguments, runtime changes, and their forces and coordinates.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>
#include <optional>
#include <string>

#include "convert.hpp"
#include "errors.hpp"
#include "py_world.hpp"

namespace elan::py {
namespace {

constexpr const char* kJointNames[] = {"ball", "hinge", "slider", "fixed", "distance", "cone"};

JointType joint_type(const std::string& name) {
  for (std::size_t i = 0; i < std::size(kJointNames); ++i) {
    if (name == kJointNames[i]) return JointType(i);
  }
  raise("joint.type", "expected ball, hinge, slider, fixed, distance or cone, got '" + name + "'");
}

using Pair = std::optional<std::array<double, 2>>;
using Triple = std::optional<std::array<double, 3>>;

JointLimits limits_of(const Pair& p) {
  JointLimits l;
  if (p) {
    l.enabled = true;
    l.lower = Real((*p)[0]);
    l.upper = Real((*p)[1]);
  }
  return l;
}

JointMotor motor_of(const Pair& p) {
  JointMotor m;
  if (p) {
    m.enabled = true;
    m.speed = Real((*p)[0]);
    m.max_force = Real((*p)[1]);
  }
  return m;
}

JointSpring spring_of(const Triple& p) {
  JointSpring s;
  if (p) {
    s.enabled = true;
    s.frequency = Real((*p)[0]);
    s.damping_ratio = Real((*p)[1]);
    s.target = Real((*p)[2]);
  }
  return s;
}

}  // namespace

void bind_joints(pybind11::class_<PyWorld>& c) {
  using pybind11::arg;
  c.def(
      "create_joint",
      [](PyWorld& w, const std::string& type, uint64_t body_a, std::optional<uint64_t> body_b,
         std::optional<V3> anchor, V3 anchor_b, V3 axis, Pair limits, Pair motor, Triple spring,
         double min_length, double max_length, double swing_limit, double friction,
         double constraint_hertz, double constraint_damping_ratio, bool collide_connected,
         double break_force, uint64_t user_data) {
        World& world = w.get();
        JointDef d;
        d.type = joint_type(type);
        d.body_a = body_id(body_a);
        if (body_b) d.body_b = body_id(*body_b);
        d.has_anchor = anchor.has_value();
        if (anchor) d.anchor = vec3(*anchor);
        d.anchor_b = vec3(anchor_b);
        d.axis = vec3(axis);
        d.limits = limits_of(limits);
        d.motor = motor_of(motor);
        d.spring = spring_of(spring);
        d.min_length = Real(min_length);
        d.max_length = Real(max_length);
        d.swing_limit = Real(swing_limit);
        d.friction = Real(friction);
        d.constraint_hertz = Real(constraint_hertz);
        d.constraint_damping_ratio = Real(constraint_damping_ratio);
        d.collide_connected = collide_connected;
        d.break_force = Real(break_force);
        d.user_data = user_data;
        return to_int(world.create_joint(d));
      },
      arg("type"), arg("body_a"), arg("body_b") = pybind11::none(), pybind11::kw_only(),
      arg("anchor") = pybind11::none(), arg("anchor_b") = V3{0, 0, 0}, arg("axis") = V3{0, 1, 0},
      arg("limits") = pybind11::none(), arg("motor") = pybind11::none(),
      arg("spring") = pybind11::none(), arg("min_length") = -1.0, arg("max_length") = -1.0,
      arg("swing_limit") = 3.14159265358979323846, arg("friction") = 0.0,
      arg("constraint_hertz") = 0.0, arg("constraint_damping_ratio") = 2.0,
      arg("collide_connected") = false,
      arg("break_force") = std::numeric_limits<double>::infinity(), arg("user_data") = 0,
      "Creates a joint; returns its id (int). type: 'ball', 'hinge', 'slider', 'fixed', "
      "'distance' or 'cone'. body_b None: the static world. anchor: m, world (distance: the "
      "anchor on A; fixed: None = midway between the bodies); anchor_b: m, world (distance). "
      "axis: world direction (hinge, slider, cone). limits=(lower, upper) rad or m; "
      "motor=(speed rad/s or m/s, max_force N m or N); spring=(frequency Hz, damping_ratio, "
      "target rad or m). min_length/max_length: m (negative: the distance at creation). "
      "swing_limit: rad (cone). friction: N m (slider: N). break_force: N. Raises elan.Error "
      "naming the field.");
  c.def(
      "destroy_joint", [](PyWorld& w, uint64_t j) { w.get().destroy_joint(joint_id(j)); },
      arg("joint"));
  c.def(
      "is_valid_joint", [](const PyWorld& w, uint64_t j) { return w.get().is_valid(joint_id(j)); },
      arg("joint"));
  c.def_property_readonly(
      "joint_count", [](const PyWorld& w) { return w.get().joint_count(); },
      "Joints in the world.");
  c.def(
      "joint_at",
      [](const PyWorld& w, std::size_t index) {
        const World& world = w.get();
        if (index >= world.joint_count()) raise("index", "out of range");
        return to_int(world.joint_at(index));
      },
      arg("index"), "The id of the joint at dense index `index`.");
  c.def(
      "joint_type",
      [](const PyWorld& w, uint64_t j) {
        return std::string(kJointNames[std::size_t(w.get().joint_def(joint_id(j)).type)]);
      },
      arg("joint"));
  c.def(
      "joint_bodies",
      [](const PyWorld& w, uint64_t j) {
        const JointDef& d = w.get().joint_def(joint_id(j));
        return pybind11::make_tuple(to_int(d.body_a), body_or_none(d.body_b));
      },
      arg("joint"), "(body_a, body_b or None).");
  c.def(
      "joint_force",
      [](const PyWorld& w, uint64_t j) { return tuple3(w.get().joint_force(joint_id(j))); },
      arg("joint"), "N, world: the force the joint applied to body A over the last step.");
  c.def(
      "joint_torque",
      [](const PyWorld& w, uint64_t j) { return tuple3(w.get().joint_torque(joint_id(j))); },
      arg("joint"), "N m, world: the torque the joint applied to body A over the last step.");
  c.def(
      "joint_coordinate",
      [](const PyWorld& w, uint64_t j) { return double(w.get().joint_coordinate(joint_id(j))); },
      arg("joint"),
      "Hinge angle and cone twist (rad, in (-pi, pi]), slider position (m), distance (m); 0 for "
      "ball and fixed joints.");
  c.def(
      "set_joint_motor",
      [](PyWorld& w, uint64_t j, Pair motor) {
        w.get().set_joint_motor(joint_id(j), motor_of(motor));
      },
      arg("joint"), arg("motor"), "(speed, max_force), or None to turn it off.");
  c.def(
      "set_joint_spring",
      [](PyWorld& w, uint64_t j, Triple s) { w.get().set_joint_spring(joint_id(j), spring_of(s)); },
      arg("joint"), arg("spring"), "(frequency Hz, damping_ratio, target), or None.");
  c.def(
      "set_joint_limits",
      [](PyWorld& w, uint64_t j, Pair l) { w.get().set_joint_limits(joint_id(j), limits_of(l)); },
      arg("joint"), arg("limits"), "(lower, upper), or None.");
  c.def(
      "set_joint_swing_limit",
      [](PyWorld& w, uint64_t j, double v) { w.get().set_joint_swing_limit(joint_id(j), Real(v)); },
      arg("joint"), arg("swing_limit"), "rad in [0, pi] (cone).");
  c.def(
      "set_joint_lengths",
      [](PyWorld& w, uint64_t j, double lo, double hi) {
        w.get().set_joint_lengths(joint_id(j), Real(lo), Real(hi));
      },
      arg("joint"), arg("min_length"), arg("max_length"), "m (distance).");
  c.def(
      "set_joint_friction",
      [](PyWorld& w, uint64_t j, double f) { w.get().set_joint_friction(joint_id(j), Real(f)); },
      arg("joint"), arg("friction"), "N m (slider: N), >= 0.");
  c.def(
      "joint_user_data",
      [](const PyWorld& w, uint64_t j) { return w.get().user_data(joint_id(j)); }, arg("joint"));
  c.def(
      "set_joint_user_data",
      [](PyWorld& w, uint64_t j, uint64_t v) { w.get().set_user_data(joint_id(j), v); },
      arg("joint"), arg("value"));
}

}  // namespace elan::py
