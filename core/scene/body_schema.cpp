// SPDX-License-Identifier: MIT
// The scene file's bodies and shapes, validated field by field.
#include "core/scene/body_schema.hpp"

#include <algorithm>
#include <cstdint>
#include <string>

#include "core/base/convex_hull.hpp"
#include "core/scene/geometry_schema.hpp"

namespace elan::detail::scene_file {

ShapeDef parse_shape(const Ctx& ctx, const Json& j) {
  object_of(ctx, j, "shape");
  const std::string type = to_string(ctx, require(ctx, j, "type", "shape.type"), "shape.type");
  ShapeDef s;
  auto get = [&](const char* key) -> const Json& {
    return require(ctx, j, key, std::string("shape.") + key);
  };
  auto field = [](const char* key) { return std::string("shape.") + key; };
  if (type == "sphere") {
    check_keys(ctx, j, {"type", "radius"}, "shape.", "a sphere");
    s.type = ShapeType::Sphere;
    s.radius = positive(ctx, get("radius"), field("radius"));
  } else if (type == "box") {
    check_keys(ctx, j, {"type", "half_extents"}, "shape.", "a box");
    s.type = ShapeType::Box;
    s.half_extents = to_vec3(ctx, get("half_extents"), field("half_extents"));
    for (int i = 0; i < 3; ++i) {
      if (!(s.half_extents[i] > 0)) {
        fail(ctx, field("half_extents") + "[" + std::to_string(i) + "]",
             "must be positive, got " + show(double(s.half_extents[i])));
      }
    }
  } else if (type == "capsule" || type == "cylinder") {
    check_keys(ctx, j, {"type", "radius", "half_height"}, "shape.",
               type == "capsule" ? "a capsule" : "a cylinder");
    s.type = type == "capsule" ? ShapeType::Capsule : ShapeType::Cylinder;
    s.radius = positive(ctx, get("radius"), field("radius"));
    s.half_height = positive(ctx, get("half_height"), field("half_height"));
  } else if (type == "convex_hull") {
    check_keys(ctx, j, {"type", "points", "file"}, "shape.", "a convex_hull");
    s.type = ShapeType::ConvexHull;
    // The points inline, or the vertices of an OBJ file (its faces are not needed: the hull of
    // the points is the shape).
    const auto file = j.find("file");
    if (file != j.end() && j.contains("points")) {
      fail(ctx, field("points"), "give either points or file");
    }
    const std::string points_field = file != j.end() ? field("file") : field("points");
    if (file != j.end()) {
      s.points = hull_points_from_obj(ctx, *file);
    } else {
      const Json& points = get("points");
      if (!points.is_array())
        fail(ctx, field("points"), "expected an array of [x, y, z], got " + show(points));
      s.points.reserve(points.size());
      for (std::size_t i = 0; i < points.size(); ++i) {
        s.points.push_back(
            to_vec3(ctx, points[i], field("points") + "[" + std::to_string(i) + "]"));
      }
    }
    if (s.points.size() < 4) {
      fail(ctx, points_field,
           "a hull needs at least 4 points, got " + std::to_string(s.points.size()));
    }
    try {
      detail::build_convex_hull(s.points);
    } catch (const Error& e) {
      const std::string what = e.what();
      const std::size_t skip = e.field().empty() ? 0 : e.field().size() + 2;
      fail(ctx, points_field, "degenerate hull: " + what.substr(std::min(skip, what.size())));
    }
  } else if (type == "plane") {
    check_keys(ctx, j, {"type", "normal", "offset"}, "shape.", "a plane");
    s.type = ShapeType::Plane;
    s.normal = to_vec3(ctx, get("normal"), field("normal"));
    if (s.normal.squaredNorm() == 0) fail(ctx, field("normal"), "zero normal");
    const auto it = j.find("offset");
    s.offset = it == j.end() ? Real(0) : to_real(ctx, *it, field("offset"));
  } else if (type == "mesh") {
    parse_mesh(ctx, j, s);
  } else if (type == "heightfield") {
    parse_heightfield(ctx, j, s);
  } else if (type == "compound") {
    parse_compound(ctx, j, s);
  } else {
    fail(ctx, "shape.type",
         "unknown shape type \"" + type +
             "\" (allowed: sphere, box, capsule, cylinder, convex_hull, plane, mesh, heightfield, "
             "compound)");
  }
  return s;
}

SceneBody parse_body(const Ctx& ctx, const Json& j) {
  object_of(ctx, j, "");
  check_keys(ctx, j,
             {"name", "motion", "shape", "position", "orientation", "linear_velocity",
              "angular_velocity", "mass", "density", "friction", "restitution", "linear_damping",
              "angular_damping", "category_bits", "mask_bits", "awake", "sensor"},
             "", "a body");
  SceneBody b;
  if (const auto it = j.find("name"); it != j.end()) b.name = to_string(ctx, *it, "name");
  BodyDef& d = b.body;
  if (const auto it = j.find("motion"); it != j.end()) {
    const std::string m = to_string(ctx, *it, "motion");
    if (m == "static") {
      d.motion = MotionType::Static;
    } else if (m == "dynamic") {
      d.motion = MotionType::Dynamic;
    } else if (m == "kinematic") {
      d.motion = MotionType::Kinematic;
    } else {
      fail(ctx, "motion", "unknown motion \"" + m + "\" (allowed: static, dynamic, kinematic)");
    }
  }
  b.shape = parse_shape(ctx, require(ctx, j, "shape", "shape"));
  // A plane, a mesh and a heightfield have no volume to give a mass (a mesh is a surface, and a
  // heightfield's solid below is not modelled).
  if (d.motion != MotionType::Static) {
    if (b.shape.type == ShapeType::Plane) fail(ctx, "motion", "a plane must be static");
    if (b.shape.type == ShapeType::Mesh) fail(ctx, "motion", "a mesh must be static");
    if (b.shape.type == ShapeType::Heightfield) {
      fail(ctx, "motion", "a heightfield must be static");
    }
  }
  auto opt = [&](const char* key) -> const Json* {
    const auto it = j.find(key);
    return it == j.end() ? nullptr : &*it;
  };
  if (const Json* v = opt("position")) d.position = to_vec3(ctx, *v, "position");
  if (const Json* v = opt("orientation")) d.orientation = to_quat(ctx, *v, "orientation");
  if (const Json* v = opt("linear_velocity"))
    d.linear_velocity = to_vec3(ctx, *v, "linear_velocity");
  if (const Json* v = opt("angular_velocity")) {
    d.angular_velocity = to_vec3(ctx, *v, "angular_velocity");
  }
  const Json* mass = opt("mass");
  const Json* density = opt("density");
  if (mass && density) fail(ctx, "mass", "give either mass or density, not both");
  if (mass) d.mass = positive(ctx, *mass, "mass");
  if (density) d.density = positive(ctx, *density, "density");
  if (const Json* v = opt("friction")) d.friction = non_negative(ctx, *v, "friction");
  if (const Json* v = opt("restitution")) d.restitution = non_negative(ctx, *v, "restitution");
  if (const Json* v = opt("linear_damping"))
    d.linear_damping = non_negative(ctx, *v, "linear_damping");
  if (const Json* v = opt("angular_damping")) {
    d.angular_damping = non_negative(ctx, *v, "angular_damping");
  }
  if (const Json* v = opt("category_bits")) {
    d.category_bits = uint32_t(to_int(ctx, *v, "category_bits", 0, UINT32_MAX));
  }
  if (const Json* v = opt("mask_bits"))
    d.mask_bits = uint32_t(to_int(ctx, *v, "mask_bits", 0, UINT32_MAX));
  if (const Json* v = opt("awake")) d.awake = to_bool(ctx, *v, "awake");
  if (const Json* v = opt("sensor")) d.sensor = to_bool(ctx, *v, "sensor");
  return b;
}

std::string body_where(std::size_t index, const std::string& name) {
  std::string w = "body " + std::to_string(index);
  if (!name.empty()) w += " (\"" + name + "\")";
  return w;
}

}  // namespace elan::detail::scene_file
