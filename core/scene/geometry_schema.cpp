// SPDX-License-Identifier: MIT
// The scene file's mesh, heightfield and compound shapes, validated field by field.
#include "core/scene/geometry_schema.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/body_schema.hpp"
#include "core/scene/obj_file.hpp"

namespace elan::detail::scene_file {

namespace {

// "[i]", appended piece by piece (GCC 12's -Wrestrict misfires on "[" + to_string(i) + "]").
std::string at(std::size_t i) {
  std::string s(1, '[');
  s += std::to_string(i);
  s += ']';
  return s;
}

std::string triangle(std::size_t t) {
  return "triangle " + std::to_string(t) + ": ";
}

// Triangle t names three different vertices (`field`: shape.triangles, or shape.file for an
// OBJ's fanned faces). Zero area is left to the core, whose tolerance it is.
void check_distinct(const Ctx& ctx, const std::array<uint32_t, 3>& tri, std::size_t t,
                    const std::string& field, const std::string& in = "") {
  if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
    fail(ctx, field,
         triangle(t) + "repeated vertex index (" + std::to_string(tri[0]) + ", " +
             std::to_string(tri[1]) + ", " + std::to_string(tri[2]) + ")" + in);
  }
}

ObjGeometry obj_of(const Ctx& ctx, const Json& file, bool need_faces) {
  const std::string path = scene_relative(ctx, to_string(ctx, file, "shape.file"));
  try {
    return read_obj(path, need_faces);
  } catch (const ObjError& e) {
    fail(ctx, "shape.file", e.what());
  }
}

}  // namespace

std::string scene_relative(const Ctx& ctx, const std::string& file) {
  const std::filesystem::path p(file);
  if (p.is_absolute()) return file;
  return (std::filesystem::path(ctx.file).parent_path() / p).string();
}

void parse_mesh(const Ctx& ctx, const Json& j, ShapeDef& s) {
  check_keys(ctx, j, {"type", "vertices", "triangles", "file"}, "shape.", "a mesh");
  s.type = ShapeType::Mesh;
  if (const auto file = j.find("file"); file != j.end()) {
    for (const char* key : {"vertices", "triangles"}) {
      if (j.contains(key)) {
        fail(ctx, std::string("shape.") + key, "give either file or vertices and triangles");
      }
    }
    ObjGeometry g = obj_of(ctx, *file, true);
    const std::string in = " in " + scene_relative(ctx, file->get<std::string>());
    for (std::size_t t = 0; t < g.triangles.size(); ++t) {
      check_distinct(ctx, g.triangles[t], t, "shape.file", in);
    }
    s.vertices = std::move(g.vertices);
    s.triangles = std::move(g.triangles);
    return;
  }
  const Json& vertices = require(ctx, j, "vertices", "shape.vertices");
  if (!vertices.is_array() || vertices.size() < 3) {
    fail(
        ctx, "shape.vertices",
        "expected an array of at least 3 [x, y, z], got " +
            (vertices.is_array() ? std::to_string(vertices.size()) + " vertices" : show(vertices)));
  }
  if (vertices.size() > UINT32_MAX) fail(ctx, "shape.vertices", "too many vertices");
  s.vertices.reserve(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    s.vertices.push_back(to_vec3(ctx, vertices[i], "shape.vertices" + at(i)));
  }
  const Json& triangles = require(ctx, j, "triangles", "shape.triangles");
  if (!triangles.is_array() || triangles.empty()) {
    fail(ctx, "shape.triangles",
         "expected an array of at least one [i, j, k], got " +
             (triangles.is_array() ? std::string("none") : show(triangles)));
  }
  s.triangles.reserve(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Json& tri = triangles[t];
    if (!tri.is_array() || tri.size() != 3) {
      fail(ctx, "shape.triangles",
           triangle(t) + "expected 3 vertex indices, got " +
               (tri.is_array() ? std::to_string(tri.size()) : show(tri)));
    }
    std::array<uint32_t, 3> v{};
    for (int c = 0; c < 3; ++c) {
      const Json& x = tri[std::size_t(c)];
      const bool integral = x.is_number_unsigned() ||
                            (x.is_number_integer() && x.get<int64_t>() >= 0) ||
                            (x.is_number_float() && x.get<double>() >= 0 &&
                             std::floor(x.get<double>()) == x.get<double>());
      if (!integral) {
        fail(ctx, "shape.triangles",
             triangle(t) + "expected a vertex index (an integer >= 0), got " + show(x));
      }
      // Compared as a double, so an index past uint32_t is out of range, not wrapped.
      const double d = x.get<double>();
      if (d >= double(s.vertices.size())) {
        fail(ctx, "shape.triangles",
             triangle(t) + "index " + show(x) + " is out of range (the mesh has " +
                 std::to_string(s.vertices.size()) + " vertices)");
      }
      v[std::size_t(c)] = uint32_t(d);
    }
    check_distinct(ctx, v, t, "shape.triangles");
    s.triangles.push_back(v);
  }
}

void parse_heightfield(const Ctx& ctx, const Json& j, ShapeDef& s) {
  check_keys(ctx, j, {"type", "heights", "spacing"}, "shape.", "a heightfield");
  s.type = ShapeType::Heightfield;
  const Json& rows = require(ctx, j, "heights", "shape.heights");
  if (!rows.is_array()) {
    fail(ctx, "shape.heights", "expected an array of rows of heights, got " + show(rows));
  }
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (!rows[r].is_array()) {
      fail(ctx, "shape.heights",
           "row " + std::to_string(r) + ": expected an array of heights, got " + show(rows[r]));
    }
    if (rows[r].size() != rows[0].size()) {
      fail(ctx, "shape.heights",
           "row " + std::to_string(r) + " has " + std::to_string(rows[r].size()) +
               " heights, row 0 has " + std::to_string(rows[0].size()) +
               " (all rows must be the same length)");
    }
  }
  const std::size_t columns = rows.empty() ? 0 : rows[0].size();
  if (rows.size() < 2 || columns < 2) {
    fail(ctx, "shape.heights",
         "at least 2 rows of 2 heights are needed, got " + std::to_string(rows.size()) +
             " rows of " + std::to_string(columns));
  }
  if (columns > UINT32_MAX || rows.size() > UINT32_MAX) fail(ctx, "shape.heights", "too many");
  s.columns = uint32_t(columns);
  s.heights.reserve(rows.size() * columns);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t c = 0; c < columns; ++c) {
      // null: a hole (no triangle has the sample for a corner), NaN in the definition.
      const Json& h = rows[r][c];
      s.heights.push_back(h.is_null() ? std::numeric_limits<Real>::quiet_NaN()
                                      : to_real(ctx, h, "shape.heights" + at(r) + at(c)));
    }
  }
  const Json& spacing =
      array_of(ctx, require(ctx, j, "spacing", "shape.spacing"), "shape.spacing", 2);
  s.spacing_x = positive(ctx, spacing[0], "shape.spacing[0]");
  s.spacing_z = positive(ctx, spacing[1], "shape.spacing[1]");
}

void parse_compound(const Ctx& ctx, const Json& j, ShapeDef& s) {
  check_keys(ctx, j, {"type", "children"}, "shape.", "a compound");
  s.type = ShapeType::Compound;
  const Json& children = require(ctx, j, "children", "shape.children");
  if (!children.is_array()) {
    fail(ctx, "shape.children", "expected an array of children, got " + show(children));
  }
  if (children.empty()) fail(ctx, "shape.children", "a compound needs at least one child");
  s.children.reserve(children.size());
  for (std::size_t k = 0; k < children.size(); ++k) {
    const Json& child = children[k];
    const Ctx child_ctx{ctx.file, ctx.where, ctx.prefix + "shape.children" + at(k) + "."};
    object_of(ctx, child, "shape.children" + at(k));
    check_keys(child_ctx, child, {"shape", "position", "orientation"}, "", "a compound child");
    const Json& shape = require(child_ctx, child, "shape", "shape");
    // The type first, so that a forbidden child is named before its own fields are read (an OBJ
    // mesh is not loaded only to be refused).
    if (shape.is_object()) {
      const auto type = shape.find("type");
      if (type != shape.end() && type->is_string()) {
        const std::string t = type->get<std::string>();
        if (t == "plane" || t == "mesh" || t == "heightfield" || t == "compound") {
          fail(child_ctx, "shape.type",
               "a compound child cannot be a " + t +
                   " (allowed: sphere, box, capsule, cylinder, convex_hull)");
        }
      }
    }
    CompoundChild c;
    c.shape = parse_shape(child_ctx, shape);
    if (const auto it = child.find("position"); it != child.end()) {
      c.position = to_vec3(child_ctx, *it, "position");
    }
    if (const auto it = child.find("orientation"); it != child.end()) {
      c.orientation = to_quat(child_ctx, *it, "orientation");
    }
    s.children.push_back(std::move(c));
  }
}

std::vector<Vec3> hull_points_from_obj(const Ctx& ctx, const Json& file) {
  return obj_of(ctx, file, false).vertices;
}

}  // namespace elan::detail::scene_file
