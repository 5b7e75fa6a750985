// SPDX-License-Identifier: MIT
// The scene file's generators: a grid of copies of one body, and a pyramid of cubes. Validated
// first, expanded once the scene's total body count is known to be sane.
#pragma once

#include <cstdint>
#include <vector>

#include "core/scene/schema_checks.hpp"
#include "elan/scene.hpp"

namespace elan::detail::scene_file {

// A validated generator, expanded only once the total body count is known to be sane.
struct Generator {
  bool pyramid = false;
  int64_t count[3] = {1, 1, 1};  // grid
  Vec3 spacing = Vec3::Zero();   // m, grid
  SceneBody body;                // grid template
  int64_t base = 1;              // pyramid
  Real half_extent = Real(0.5);  // m, pyramid cube
  Vec3 origin = Vec3::Zero();    // m
  uint64_t bodies = 0;
};

Generator parse_generator(const Ctx& ctx, const Json& j);
// Appends the generator's bodies to `out`.
void expand(const Generator& g, std::vector<SceneBody>& out);

}  // namespace elan::detail::scene_file
