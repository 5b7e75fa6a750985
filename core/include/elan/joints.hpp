// SPDX-License-Identifier: MIT
// Joints of the public API: the creation struct, its parts (limits, motor, spring) and the
// events of joints leaving the world.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>

#include "elan/ids.hpp"
#include "elan/math.hpp"

namespace elan {

/// A joint handle, generation-checked like BodyId: a removed joint's id stays invalid even after
/// its slot is reused.
struct JointId {
  uint32_t slot = UINT32_MAX;
  uint32_t generation = 0;
  bool is_null() const { return slot == UINT32_MAX; }
  friend bool operator==(JointId, JointId) = default;
};

enum class JointType : uint8_t {
  Ball,      ///< the anchors coincide
  Hinge,     ///< as Ball, and the bodies turn only about `axis`
  Slider,    ///< relative orientation kept, relative motion only along `axis`
  Fixed,     ///< relative pose kept (weld)
  Distance,  ///< the anchors' distance stays within [min_length, max_length]
  Cone,      ///< as Ball, with a swing cone about `axis` and twist limits (ragdolls)
};

/// Bounds of the joint's coordinate: hinge angle (rad), slider position (m), cone twist (rad).
struct JointLimits {
  bool enabled = false;
  Real lower = 0;  ///< <= upper
  Real upper = 0;
};

/// Drives the joint's rate toward `speed` (rad/s for a hinge, m/s for a slider) with at most
/// `max_force` (N m for a hinge, N for a slider).
struct JointMotor {
  bool enabled = false;
  Real speed = 0;
  Real max_force = 0;  ///< >= 0
};

/// A spring-damper pulling the joint's coordinate toward `target` (hinge: rad, slider: m,
/// distance: the rest length, m).
struct JointSpring {
  bool enabled = false;
  Real frequency = 1;      ///< Hz, > 0
  Real damping_ratio = 0;  ///< >= 0 (1: critical)
  Real target = 0;  ///< distance joints: the rest length, m (negative: the distance at creation)
};

/// One creation struct for every kind, tagged by `type` (the scene format's shape: one create
/// path, one set of checks naming the field, and a type can be changed without rewriting the
/// rest). Fields a type does not use are ignored. Geometry is given in the world frame at
/// creation, from the bodies' current poses: each body keeps the anchor at the same place in its
/// own frame; the joint's angle and position are 0 at creation.
struct JointDef {
  JointType type = JointType::Ball;
  BodyId body_a;               ///< the first body; joint angles are those of A relative to B
  BodyId body_b;               ///< null: the static world
  Vec3 anchor = Vec3::Zero();  ///< m, world. Distance: the anchor on A
  /// Fixed only: when false, the anchor is the midpoint of the two bodies' shape frames.
  bool has_anchor = true;
  Vec3 anchor_b = Vec3::Zero();  ///< m, world: Distance only, the anchor on B
  Vec3 axis = Vec3::UnitY();     ///< world direction (normalised on creation; not zero)
  JointLimits limits;            ///< Hinge, Slider; Cone: the twist limits
  JointMotor motor;              ///< Hinge, Slider
  JointSpring spring;            ///< Hinge, Slider, Distance
  /// Distance: m, 0 <= min_length <= max_length; negative: the distance at creation.
  Real min_length = -1;
  Real max_length = -1;
  Real swing_limit = Real(3.14159265358979323846);  ///< Cone: rad, in [0, pi]
  /// N m (slider: N), >= 0: joint friction, a torque (force) up to this much that resists the
  /// bodies' relative turning (sliding): Ball and Cone about every axis, Hinge about its axis,
  /// Slider along it (Jolt's max friction torque; Box2D emulates it with a motor of speed 0).
  Real friction = 0;
  /// Stiffness of the joint's own rows (anchors, locked axes, limits), Hz, as Box2D's constraint
  /// hertz; 0: the default, twice the contact stiffness (92 Hz at 60 steps of 4 substeps). A soft
  /// row settles F / (m_eff (2 pi hertz)^2) under a load F, so light links holding a heavy body
  /// want stiffer rows, and stiffer rows want more solver iterations (WorldDef::iterations) to
  /// converge without overshooting.
  Real constraint_hertz = 0;
  Real constraint_damping_ratio = 2;  ///< of those rows, >= 0
  bool collide_connected = false;     ///< false: the two bodies do not collide with each other
  /// N, > 0: the joint is removed in the step in which its constraint force exceeds this.
  Real break_force = std::numeric_limits<Real>::infinity();
  uint64_t user_data = 0;  ///< the caller's value, kept through snapshots; never read by elan
};

/// Why a joint left the world.
enum class JointRemoval : uint8_t {
  Broke,          ///< its constraint force exceeded break_force in the last step
  BodyDestroyed,  ///< one of its bodies was destroyed (destroy_body)
};

/// A joint left the world other than by destroy_joint: in the last step (Broke, in joint
/// creation order) or by destroy_body since (BodyDestroyed). Its id is already invalid.
struct JointRemovedEvent {
  JointId joint;
  BodyId body_a;
  BodyId body_b;  ///< null for the world
  JointRemoval reason = JointRemoval::Broke;
  Real force = 0;  ///< N: the constraint force that broke it (0 for BodyDestroyed)
};

}  // namespace elan

template <>
struct std::hash<elan::JointId> {
  std::size_t operator()(elan::JointId id) const noexcept {
    return std::hash<uint64_t>{}(uint64_t(id.generation) << 32 | id.slot);
  }
};
