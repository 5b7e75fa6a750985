// SPDX-License-Identifier: MIT
// Scene files: the top level of the schema (world settings, bodies, generators, joints), read
// from text or from a file.
#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/base/range_checks.hpp"
#include "core/scene/body_schema.hpp"
#include "core/scene/generators.hpp"
#include "core/scene/joint_schema.hpp"
#include "core/scene/json_reader.hpp"
#include "core/scene/regular_file.hpp"
#include "core/scene/schema_checks.hpp"
#include "elan/limits.hpp"
#include "elan/scene.hpp"

namespace elan {

using namespace detail::scene_file;

namespace {

// root[key], an empty array when absent; fails unless an array.
const Json& array_or_empty(const Ctx& ctx, const Json& root, const char* key,
                           const std::string& expected) {
  static const Json kEmpty = Json::array();
  const auto it = root.find(key);
  const Json& list = it == root.end() ? kEmpty : *it;
  if (!list.is_array()) fail(ctx, key, "expected " + expected + ", got " + show(list));
  return list;
}

// The context of item i of a list (a body, a joint), named as `where` names it, with the item's
// name when it has one.
Ctx item_ctx(const std::string& file_name, const Json& item, std::size_t i,
             std::string (*where)(std::size_t, const std::string&)) {
  Ctx c{file_name, where(i, ""), ""};
  if (item.is_object()) {
    const auto name = item.find("name");
    if (name != item.end() && name->is_string()) c.where = where(i, name->get<std::string>());
  }
  return c;
}

// Records item i's `name` (if any) in `names`; fails if another `what` has it.
void claim_name(const Ctx& ctx, std::map<std::string, std::size_t>& names, const std::string& name,
                std::size_t i, const char* what) {
  if (name.empty()) return;
  const auto [it, inserted] = names.emplace(name, i);
  if (!inserted) {
    fail(ctx, "name",
         "duplicate name \"" + name + "\" (also " + what + " " + std::to_string(it->second) + ")");
  }
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& file_name) {
  const Json root = parse_json(text, file_name);
  const Ctx ctx{file_name, "", ""};
  check_keys(ctx, root,
             {"gravity", "timestep", "substeps", "iterations", "allow_sleep", "bodies",
              "generators", "joints"},
             "", "the scene");
  Scene scene;
  if (const auto it = root.find("gravity"); it != root.end()) {
    scene.world.gravity = to_vec3(ctx, *it, "gravity");
    // The World refuses it too, but with an elan::Error that names no file: parse_scene promises
    // SceneError for every bad scene (found by fuzz_scene).
    try {
      detail::check_length(scene.world.gravity, limits::kMaxGravity, "gravity", "m/s^2");
    } catch (const Error& e) {
      const std::string what = e.what();
      fail(ctx, "gravity", what.substr(std::min(what.size(), e.field().size() + 2)));
    }
  }
  if (const auto it = root.find("timestep"); it != root.end()) {
    scene.timestep = positive(ctx, *it, "timestep");
    if (!(scene.timestep >= Real(limits::kMinTimestep) &&
          scene.timestep <= Real(limits::kMaxTimestep))) {
      fail(ctx, "timestep",
           "must be in [" + show(limits::kMinTimestep) + ", " + show(limits::kMaxTimestep) +
               "] s, got " + show(*it));
    }
  }
  if (const auto it = root.find("substeps"); it != root.end()) {
    scene.world.substeps = int(to_int(ctx, *it, "substeps", 1, kMaxSubsteps));
    scene.has_substeps = true;
  }
  if (const auto it = root.find("iterations"); it != root.end()) {
    scene.world.iterations = int(to_int(ctx, *it, "iterations", 1, kMaxIterations));
    scene.has_iterations = true;
  }
  if (const auto it = root.find("allow_sleep"); it != root.end()) {
    scene.world.allow_sleep = to_bool(ctx, *it, "allow_sleep");
  }

  const Json& bodies = array_or_empty(ctx, root, "bodies", "an array of bodies");
  const Json& gens = array_or_empty(ctx, root, "generators", "an array");
  const Json& joints = array_or_empty(ctx, root, "joints", "an array of joints");
  if (bodies.size() > kMaxBodies) {
    fail(ctx, "bodies", "too many bodies: at most " + std::to_string(kMaxBodies) + " are allowed");
  }

  // determinism: ordered map; only looked up, never iterated into results.
  std::map<std::string, std::size_t> names;
  scene.bodies.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Ctx body_ctx = item_ctx(file_name, bodies[i], i, body_where);
    SceneBody b = parse_body(body_ctx, bodies[i]);
    claim_name(body_ctx, names, b.name, i, "body");
    scene.bodies.push_back(std::move(b));
  }

  std::vector<Generator> generators;
  uint64_t total = bodies.size();
  uint64_t total_joints = joints.size();
  for (std::size_t i = 0; i < gens.size(); ++i) {
    std::string where = "generator " + std::to_string(i);
    if (gens[i].is_object()) {
      const auto type = gens[i].find("type");
      if (type != gens[i].end() && type->is_string()) {
        where += " (" + type->get<std::string>() + ")";
      }
    }
    const Ctx gen_ctx{file_name, where, ""};
    generators.push_back(parse_generator(gen_ctx, gens[i]));
    total += generators.back().bodies;
    total_joints += generators.back().joints;
    if (total > kMaxBodies) {
      fail(gen_ctx, "",
           "too many bodies: the scene would have " + std::to_string(total) + ", at most " +
               std::to_string(kMaxBodies) + " are allowed");
    }
    if (total_joints > kMaxJoints) {
      fail(gen_ctx, "",
           "too many joints: the scene would have " + std::to_string(total_joints) + ", at most " +
               std::to_string(kMaxJoints) + " are allowed");
    }
  }
  scene.bodies.reserve(total);
  std::vector<SceneJoint> generated;
  generated.reserve(total_joints - joints.size());
  for (const Generator& g : generators) expand(g, scene.bodies, generated);

  // Joints name bodies as numbered after the generators, so they are read last; the generated
  // joints follow the explicit ones.
  if (joints.size() > kMaxJoints) {
    fail(ctx, "joints", "too many joints: at most " + std::to_string(kMaxJoints) + " are allowed");
  }
  const BodyRefs refs{scene.bodies, names};
  // determinism: ordered map; only looked up, never iterated into results.
  std::map<std::string, std::size_t> joint_names;
  scene.joints.reserve(total_joints);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const Ctx joint_ctx = item_ctx(file_name, joints[i], i, joint_where);
    SceneJoint sj = parse_joint(joint_ctx, joints[i], refs);
    claim_name(joint_ctx, joint_names, sj.name, i, "joint");
    scene.joints.push_back(std::move(sj));
  }
  for (SceneJoint& j : generated) scene.joints.push_back(std::move(j));
  return scene;
}

Scene load_scene(const std::string& path) {
  return parse_scene(detail::read_scene_file(path), path);
}

}  // namespace elan
