// SPDX-License-Identifier: MIT
// The scene file's `terrain` generator: one static body, a mesh or a heightfield over a grid of
// cells whose heights are a fixed smooth function, so that a large surface needs a line of JSON
// rather than megabytes.
#pragma once

#include <cstdint>

#include "core/scene/schema_checks.hpp"
#include "elan/scene.hpp"

namespace elan::detail::scene_file {

struct TerrainDef {
  bool mesh = false;  // a mesh; else a heightfield
  int64_t cells_x = 1, cells_z = 1;
  Real spacing_x = 1, spacing_z = 1;  // m
  Real amplitude = 1;                 // m
  Real wavelength = 10;               // m
  Real friction = Real(0.5);
  Real restitution = 0;
};

// The largest terrain: 4096 cells a side and 2^22 cells in all (a mesh of 8.4 million triangles).
inline constexpr int64_t kMaxTerrainSide = 4096;
inline constexpr int64_t kMaxTerrainCells = int64_t(1) << 22;

TerrainDef parse_terrain(const Ctx& ctx, const Json& j);

// The terrain's height at (x, z) of its shape frame (m), before rounding to float:
//   h = a (0.5 sin(k x) cos(k z) + 0.3 sin(1.7 k x + 0.4) sin(1.3 k z + 1.1)
//          + 0.2 cos(0.6 k (x + z))),  k = 2 pi / wavelength,
// so |h| <= a. Evaluated in double.
double terrain_height(const TerrainDef& t, double x, double z);

// The terrain as one static body at `origin`.
SceneBody make_terrain(const TerrainDef& t, const Vec3& origin);

}  // namespace elan::detail::scene_file
