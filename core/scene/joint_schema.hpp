// SPDX-License-Identifier: MIT
// The scene file's joints: a joint object (type, bodies, geometry, limits, motor, spring, break
// force), validated into a SceneJoint whose bodies are scene body indices.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "core/scene/schema_checks.hpp"
#include "elan/scene.hpp"

namespace elan::detail::scene_file {

// The bodies a joint may name: every scene body (generated ones included) by index, the named
// ones by name.
struct BodyRefs {
  const std::vector<SceneBody>& bodies;
  const std::map<std::string, std::size_t>& names;
};

SceneJoint parse_joint(const Ctx& ctx, const Json& j, const BodyRefs& refs);
// "joint 2" or "joint 2 ("door")", for messages.
std::string joint_where(std::size_t index, const std::string& name);
// The scene file's name for a JointDef field that the World named in an Error (the library
// speaks of motor.max_force, the file of a hinge's motor.max_torque).
std::string scene_field(JointType type, const std::string& api_field);

}  // namespace elan::detail::scene_file
