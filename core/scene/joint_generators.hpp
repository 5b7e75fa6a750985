// SPDX-License-Identifier: MIT
// The scene file's chain and joint_grid generators: bodies and the joints between them.
#pragma once

#include <cstdint>
#include <vector>

#include "core/scene/schema_checks.hpp"
#include "elan/scene.hpp"

namespace elan::detail::scene_file {

// A chain of `links` copies of one body hanging from a point pinned to the world.
struct ChainDef {
  int64_t links = 1;
  Vec3 direction = -Vec3::UnitY();  // unit: from the pinned point down the chain
  Real link_spacing = 0;            // m, between consecutive link centres
  JointType joint = JointType::Ball;
  Vec3 axis = Vec3::UnitZ();  // unit, world: a hinge chain's axis
};

// Box2D's joint_grid benchmark: count x count spheres in the x-y plane, each jointed to the one
// above it and the one to its left.
struct JointGridDef {
  int64_t count = 1;
  Real spacing = 1;         // m
  Real radius = Real(0.4);  // m
  bool pin_row = false;     // the whole top row static, rather than Box2D's middle seven
};

// Reads a chain's own keys (links, link, direction, link_spacing, joint, axis); `link` gets the
// link body. Fails naming the field.
ChainDef parse_chain(const Ctx& ctx, const Json& j, SceneBody& link);
JointGridDef parse_joint_grid(const Ctx& ctx, const Json& j);
// Joints per chain and per grid.
uint64_t chain_joints(const ChainDef& c);
uint64_t joint_grid_joints(const JointGridDef& g);

// One chain pinned at `origin`.
void expand_chain(const ChainDef& c, const SceneBody& link, const Vec3& origin,
                  std::vector<SceneBody>& bodies, std::vector<SceneJoint>& joints);
// The grid's top-left sphere at `origin`, columns along +x, rows down -y.
void expand_joint_grid(const JointGridDef& g, const Vec3& origin, std::vector<SceneBody>& bodies,
                       std::vector<SceneJoint>& joints);

}  // namespace elan::detail::scene_file
