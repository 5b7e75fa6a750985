// SPDX-License-Identifier: MIT
// The scene file's ragdoll generator: a humanoid of capsules, boxes and a sphere, with cone
// joints at the spine, neck, shoulders, hips and wrists and hinges at the elbows, knees and
// ankles, each within a human range of motion.
#pragma once

#include <cstdint>
#include <vector>

#include "core/scene/schema_checks.hpp"
#include "elan/scene.hpp"

namespace elan::detail::scene_file {

struct RagdollDef {
  Quat orientation = Quat::Identity();  // of the whole figure; identity: standing, facing +z
  Real scale = 1;                       // 1: 1.78 m tall
  bool hands = true;
  // N m at scale 1, on every joint (scaled by scale^4, as the parts' weight moments are): the
  // damping of muscles and ligaments that lets a fallen body come to rest (Jolt's ragdoll
  // friction torque). Negative: the default.
  Real joint_friction = -1;
};

// Reads the ragdoll's own keys (orientation, scale, hands, joint_friction).
RagdollDef parse_ragdoll(const Ctx& ctx, const Json& j);
uint64_t ragdoll_bodies(const RagdollDef& r);
uint64_t ragdoll_joints(const RagdollDef& r);
// One ragdoll whose feet stand on `origin` (the point on the ground between them).
void expand_ragdoll(const RagdollDef& r, const Vec3& origin, std::vector<SceneBody>& bodies,
                    std::vector<SceneJoint>& joints);

}  // namespace elan::detail::scene_file
