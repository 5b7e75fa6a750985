// SPDX-License-Identifier: MIT
// A joint in solver form for one step (JointRow), and the links joints add to the islands.
#pragma once

#include <cstdint>

#include "elan/joints.hpp"
#include "solver/joint_store.hpp"
#include "solver/solver_types.hpp"

namespace elan::detail {

// What a joint uses, decided once a step from its definition.
enum JointRowFlags : uint8_t {
  kJointLimit = 1,
  kJointMotor = 2,
  kJointSpring = 4,
  kJointSwing = 8,  // a cone whose swing limit is below pi
  kJointFriction = 16,
  // Its point rows carry a load their soft spring would give under by more than kDirectJointGive
  // (direct_solve.hpp): the direct solve takes them.
  kJointLoaded = 32,
};

// A joint's geometry at the current poses: it changes only when the positions do, once a substep
// (refresh_joints), and every pass until then reads it.
struct JointPose {
  Vec3 r_a = Vec3::Zero(), r_b = Vec3::Zero();                  // m, world arms
  Vec3 separation = Vec3::Zero();                               // m: B's anchor minus A's
  Quat frame_a = Quat::Identity(), frame_b = Quat::Identity();  // joint frames, world
};

// One joint prepared for the step: its packets, its frames at the step's start, its settings and
// its impulses (copied from the store and back, so a pass reads one record a joint). Scalar, not
// bundled across lanes: a scene has far fewer joints than contacts, and the rows of a kind differ
// in shape.
struct JointRow {
  // perf: what a ball joint's passes read comes first, in the row's first two cache lines (a
  // joint grid streams 20,000 rows a pass); the frames, settings and other impulses follow.
  uint32_t joint = 0;  // dense index in the JointStore
  uint32_t packet_a = 0, packet_b = 0;
  JointType type = JointType::Ball;
  uint8_t flags = 0;
  Softness softness;                  // the joint's own rows (JointDef::constraint_hertz)
  SymMat3 point_mass;                 // (J M^-1 J^T)^-1 of the point rows at the current poses, kg
  Vec3 point_impulse = Vec3::Zero();  // N s: JointImpulses::point while the row is solved
  // At the current poses (refresh_joints).
  JointPose pose;
  Vec3 r_a = Vec3::Zero(), r_b = Vec3::Zero();  // m, world: anchors minus centres at the start
  Quat frame_a = Quat::Identity(), frame_b = Quat::Identity();  // joint frames at the start
  Vec3 delta_center = Vec3::Zero();  // m: B's centre minus A's at the start
  Real lower = 0, upper = 0;         // limits (distance: min and max length)
  Real motor_speed = 0;
  Real max_motor_impulse = 0;     // N s (N m s) per substep
  Real max_friction_impulse = 0;  // N s (N m s) per substep
  Real spring_target = 0;         // rad, m; distance: rest length
  Real swing_limit = 0;           // rad
  Softness spring;
  // Each side's inverse inertia k when it is k E (a sphere, a cube; 0 for a side the solve does
  // not move), else -1: the point mass's refresh takes a shortcut for those.
  Real isotropic_a = -1, isotropic_b = -1;
  JointImpulses impulses;  // all but `point`, which is point_impulse while the row is solved
};

// A joint as the islands see it: two dense body indices (UINT32_MAX for the world).
struct JointLink {
  uint32_t a = UINT32_MAX;
  uint32_t b = UINT32_MAX;
};

}  // namespace elan::detail
