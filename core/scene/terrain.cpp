// SPDX-License-Identifier: MIT
// The terrain generator: the same surface as a heightfield or as a mesh.
#include "core/scene/terrain.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/base/fixed_math.hpp"

namespace elan::detail::scene_file {

TerrainDef parse_terrain(const Ctx& ctx, const Json& j) {
  TerrainDef t;
  const std::string shape = to_string(ctx, require(ctx, j, "shape", "shape"), "shape");
  if (shape == "mesh") {
    t.mesh = true;
  } else if (shape != "heightfield") {
    fail(ctx, "shape", "unknown terrain shape \"" + shape + "\" (allowed: mesh, heightfield)");
  }
  const Json& cells = array_of(ctx, require(ctx, j, "cells", "cells"), "cells", 2);
  t.cells_x = to_int(ctx, cells[0], "cells[0]", 1, kMaxTerrainSide);
  t.cells_z = to_int(ctx, cells[1], "cells[1]", 1, kMaxTerrainSide);
  if (t.cells_x * t.cells_z > kMaxTerrainCells) {
    fail(ctx, "cells",
         "too many cells: " + std::to_string(t.cells_x * t.cells_z) + ", at most " +
             std::to_string(kMaxTerrainCells) + " are allowed");
  }
  const Json& spacing = array_of(ctx, require(ctx, j, "spacing", "spacing"), "spacing", 2);
  t.spacing_x = positive(ctx, spacing[0], "spacing[0]");
  t.spacing_z = positive(ctx, spacing[1], "spacing[1]");
  if (const auto it = j.find("amplitude"); it != j.end()) {
    t.amplitude = non_negative(ctx, *it, "amplitude");
  }
  if (const auto it = j.find("wavelength"); it != j.end()) {
    t.wavelength = positive(ctx, *it, "wavelength");
  }
  if (const auto it = j.find("friction"); it != j.end()) {
    t.friction = non_negative(ctx, *it, "friction");
  }
  if (const auto it = j.find("restitution"); it != j.end()) {
    t.restitution = non_negative(ctx, *it, "restitution");
  }
  return t;
}

double terrain_height(const TerrainDef& t, double x, double z) {
  const double k = 2 * std::numbers::pi / double(t.wavelength);
  // determinism: the engine's own sine and cosine (core/base/fixed_math.hpp), not the C
  // library's, whose last bits differ between libraries and CPUs.
  using detail::fixed_cos, detail::fixed_sin;
  return double(t.amplitude) * (0.5 * fixed_sin(k * x) * fixed_cos(k * z) +
                                0.3 * fixed_sin(1.7 * k * x + 0.4) * fixed_sin(1.3 * k * z + 1.1) +
                                0.2 * fixed_cos(0.6 * k * (x + z)));
}

// Heights are rounded to float, as a heightfield stores them (which also confines a last-bit
// difference between two C libraries' sin or cos to the rare sample at a float rounding boundary),
// and a mesh vertex's x and z are computed as the heightfield computes its samples' (i * spacing in
// Real), so both shapes are the same surface to the last bit. The mesh splits each cell as the
// heightfield does (see core/base/heightfield.hpp): along the diagonal from sample (i, j) to (i+1,
// j+1), the triangle with the corner (i+1, j) first, both wound to face +y.
SceneBody make_terrain(const TerrainDef& t, const Vec3& origin) {
  SceneBody b;
  b.body.motion = MotionType::Static;
  b.body.position = origin;
  b.body.friction = t.friction;
  b.body.restitution = t.restitution;
  const uint32_t nx = uint32_t(t.cells_x) + 1, nz = uint32_t(t.cells_z) + 1;
  ShapeDef& s = b.shape;
  std::vector<Real> heights;
  heights.reserve(std::size_t(nx) * nz);
  for (uint32_t j = 0; j < nz; ++j) {
    for (uint32_t i = 0; i < nx; ++i) {
      const double x = double(Real(i) * t.spacing_x), z = double(Real(j) * t.spacing_z);
      heights.push_back(Real(float(terrain_height(t, x, z))));
    }
  }
  if (!t.mesh) {
    s.type = ShapeType::Heightfield;
    s.heights = std::move(heights);
    s.columns = nx;
    s.spacing_x = t.spacing_x;
    s.spacing_z = t.spacing_z;
    return b;
  }
  s.type = ShapeType::Mesh;
  s.vertices.reserve(heights.size());
  for (uint32_t j = 0; j < nz; ++j) {
    for (uint32_t i = 0; i < nx; ++i) {
      s.vertices.emplace_back(Real(i) * t.spacing_x, heights[std::size_t(j) * nx + i],
                              Real(j) * t.spacing_z);
    }
  }
  s.triangles.reserve(std::size_t(t.cells_x) * std::size_t(t.cells_z) * 2);
  for (uint32_t j = 0; j + 1 < nz; ++j) {
    for (uint32_t i = 0; i + 1 < nx; ++i) {
      const uint32_t v00 = j * nx + i, v10 = v00 + 1, v01 = v00 + nx, v11 = v01 + 1;
      s.triangles.push_back({v00, v11, v10});
      s.triangles.push_back({v00, v01, v11});
    }
  }
  return b;
}

}  // namespace elan::detail::scene_file
