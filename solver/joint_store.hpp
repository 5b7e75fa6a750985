// SPDX-License-Identifier: MIT
// The joints kept from step to step: each joint's definition, its frames in its bodies' own
// frames, and the impulses it warm starts with; and the JointId slots.
//
// Joints are dense, in creation order while none is removed (a removal moves the last joint into
// the hole, as bodies do), and they name their bodies by BodyId slot, which a body's swap-remove
// does not change. Everything the step derives from them (solver rows, island links, the pairs
// they keep from colliding) is rebuilt from this list, in this order, so the order is part of
// the result: it depends on the calls made, never on threads.
#pragma once

#include <cstdint>
#include <vector>

#include "elan/joints.hpp"
#include "elan/math.hpp"

namespace elan::detail {

inline constexpr uint32_t kWorldSlot = UINT32_MAX;  // a joint side that is the static world

// The impulses a joint accumulates over a substep and warm starts the next with (N s; N m s for
// angular ones), world frame. Which of them a joint uses depends on its type.
struct JointImpulses {
  Vec3 point = Vec3::Zero();    // the anchors' coincidence (ball, hinge, cone, fixed)
  Vec3 angular = Vec3::Zero();  // the orientation lock (fixed, slider; hinge: two of them)
  Vec3 linear = Vec3::Zero();   // the slider's two perpendicular rows (x, y)
  Real axial = 0;               // the rigid distance row
  Real spring = 0;
  Real motor = 0;
  Real lower = 0;  // limits: >= 0 each
  Real upper = 0;
  Real swing = 0;                // the cone's swing limit, >= 0
  Vec3 friction = Vec3::Zero();  // ball, cone: angular; hinge, slider: x along the axis
};

struct Joint {
  JointDef def;  // as created (bodies, world geometry at creation), as changed by the setters
  uint32_t slot_a = kWorldSlot;  // body id slots
  uint32_t slot_b = kWorldSlot;
  // Each side's anchor and joint frame (x: the axis) in that body's principal frame, relative to
  // its centre of mass; for the world, in the world frame.
  Vec3 anchor_a = Vec3::Zero(), anchor_b = Vec3::Zero();
  Quat frame_a = Quat::Identity(), frame_b = Quat::Identity();
  Real min_length = 0, max_length = 0, rest_length = 0;  // m: distance joints
  JointImpulses impulses;
  Vec3 force = Vec3::Zero();   // N, on A: the last substep's impulses over the substep time
  Vec3 torque = Vec3::Zero();  // N m, on A
  uint32_t slot = 0;           // its JointId slot
};

struct JointStore {
  std::vector<Joint> joints;
  // JointId slot -> dense index (UINT32_MAX: free) and generation; freed slots reused last first.
  std::vector<uint32_t> slot_index;
  std::vector<uint32_t> slot_generation;
  std::vector<uint32_t> free_slots;
  // Bumped by every change of the joint list or of a joint's bodies' indices, so that what the
  // step derives from the list only (the pairs kept from colliding) is rebuilt when stale.
  uint64_t version = 0;

  std::size_t size() const { return joints.size(); }
  bool empty() const { return joints.empty(); }
};

}  // namespace elan::detail
