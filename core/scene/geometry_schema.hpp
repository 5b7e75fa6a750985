// SPDX-License-Identifier: MIT
// The scene file's surface and compound shapes: `mesh` (inline or from an OBJ file),
// `heightfield` and `compound`, and a `convex_hull`'s points read from an OBJ file. Structure is
// checked here (index ranges, repeated indices, row lengths, child types), with the triangle, row
// or child index in the message; the geometric checks (zero-area triangles, sizes) are the core's
// (make_shape), whose errors load_into reports the same way.
#pragma once

#include <string>
#include <vector>

#include "core/scene/schema_checks.hpp"
#include "elan/defs.hpp"

namespace elan::detail::scene_file {

// `file` as given in the scene: absolute, or relative to the directory of the scene file.
std::string scene_relative(const Ctx& ctx, const std::string& file);

// Each fills `s` from the shape object `j` (its `type` already read).
void parse_mesh(const Ctx& ctx, const Json& j, ShapeDef& s);
void parse_heightfield(const Ctx& ctx, const Json& j, ShapeDef& s);
void parse_compound(const Ctx& ctx, const Json& j, ShapeDef& s);
// The vertices of the OBJ file named by `file` (shape.file), for a convex hull.
std::vector<Vec3> hull_points_from_obj(const Ctx& ctx, const Json& file);

}  // namespace elan::detail::scene_file
