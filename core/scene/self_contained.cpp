// SPDX-License-Identifier: MIT
// Scene text with its OBJ files written in: every object of the JSON is visited, and a shape
// (`type` mesh or convex_hull) with a `file` gets the file's contents as inline keys.
#include "core/scene/self_contained.hpp"

#include <string>

#include "core/scene/geometry_schema.hpp"
#include "core/scene/json_reader.hpp"
#include "core/scene/obj_file.hpp"
#include "core/scene/schema_checks.hpp"

namespace elan::detail::scene_file {

namespace {

Json points_of(const std::vector<Vec3>& points) {
  Json out = Json::array();
  for (const Vec3& p : points) {
    // double(Real) is exact, and the JSON writer prints the shortest text that reads back to the
    // same double, so the parser's Real(double) gives this Real again.
    out.push_back({double(p.x()), double(p.y()), double(p.z())});
  }
  return out;
}

// Replaces the files under `j`; returns whether it found any.
bool inline_files(const Ctx& ctx, Json& j) {
  bool found = false;
  if (j.is_object()) {
    const auto type = j.find("type");
    const auto file = j.find("file");
    if (type != j.end() && type->is_string() && file != j.end() && file->is_string()) {
      const std::string kind = type->get<std::string>();
      const std::string path = scene_relative(ctx, file->get<std::string>());
      if (kind == "mesh" || kind == "convex_hull") {
        ObjGeometry g;
        try {
          g = read_obj(path, kind == "mesh");
        } catch (const ObjError& e) {
          fail(ctx, "shape.file", e.what());
        }
        j.erase("file");
        if (kind == "mesh") {
          j["vertices"] = points_of(g.vertices);
          Json triangles = Json::array();
          for (const auto& t : g.triangles) triangles.push_back({t[0], t[1], t[2]});
          j["triangles"] = std::move(triangles);
        } else {
          j["points"] = points_of(g.vertices);
        }
        return true;
      }
    }
    for (auto& item : j.items()) found = inline_files(ctx, item.value()) || found;
  } else if (j.is_array()) {
    for (Json& item : j) found = inline_files(ctx, item) || found;
  }
  return found;
}

}  // namespace

std::string self_contained(const std::string& text, const std::string& file_name) {
  Json root = parse_json(text, file_name);
  const Ctx ctx{file_name, "", ""};
  if (!inline_files(ctx, root)) return text;
  return root.dump();
}

}  // namespace elan::detail::scene_file
