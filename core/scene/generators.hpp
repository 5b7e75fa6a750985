// SPDX-License-Identifier: MIT
// The scene file's generators: a grid of copies of one body, a pyramid of cubes, a terrain, and
// the jointed ones (chains, ragdolls, Box2D's joint grid). Validated first, expanded once the
// scene's total body count is known to be sane.
#pragma once

#include <cstdint>
#include <vector>

#include "core/scene/joint_generators.hpp"
#include "core/scene/ragdoll.hpp"
#include "core/scene/schema_checks.hpp"
#include "core/scene/terrain.hpp"
#include "elan/scene.hpp"

namespace elan::detail::scene_file {

enum class GeneratorKind : uint8_t { Grid, Pyramid, Chain, Ragdoll, JointGrid, Terrain };

// A validated generator, expanded only once the total body count is known to be sane.
struct Generator {
  GeneratorKind kind = GeneratorKind::Grid;
  int64_t count[3] = {1, 1, 1};  // grid; copies of a chain or a ragdoll
  Vec3 spacing = Vec3::Zero();   // m, grid; between copies of a chain or a ragdoll
  SceneBody body;                // grid template; a chain's link
  int64_t base = 1;              // pyramid
  Real half_extent = Real(0.5);  // m, pyramid cube
  Vec3 origin = Vec3::Zero();    // m
  ChainDef chain;
  RagdollDef ragdoll;
  JointGridDef joint_grid;
  TerrainDef terrain;
  uint64_t bodies = 0;
  uint64_t joints = 0;
};

Generator parse_generator(const Ctx& ctx, const Json& j);
// Appends the generator's bodies to `bodies` and its joints, which name bodies by their index
// in `bodies`, to `joints`.
void expand(const Generator& g, std::vector<SceneBody>& bodies, std::vector<SceneJoint>& joints);

}  // namespace elan::detail::scene_file
