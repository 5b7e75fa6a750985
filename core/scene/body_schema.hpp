// SPDX-License-Identifier: MIT
// The scene file's bodies: a body object (motion, shape, pose, velocities, mass, material,
// filter) and its shape object, validated into a SceneBody.
#pragma once

#include <cstddef>
#include <string>

#include "core/scene/schema_checks.hpp"
#include "elan/scene.hpp"

namespace elan::detail::scene_file {

ShapeDef parse_shape(const Ctx& ctx, const Json& j);
SceneBody parse_body(const Ctx& ctx, const Json& j);
// "body 3" or "body 3 ("ball")", for messages.
std::string body_where(std::size_t index, const std::string& name);

}  // namespace elan::detail::scene_file
