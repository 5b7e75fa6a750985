// SPDX-License-Identifier: MIT
// Scene files: the top level of the schema (world settings, bodies, generators, joints), read
// from text or from a file.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

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

  static const Json kEmpty = Json::array();
  const auto bodies_it = root.find("bodies");
  const Json& bodies = bodies_it == root.end() ? kEmpty : *bodies_it;
  if (!bodies.is_array()) fail(ctx, "bodies", "expected an array of bodies, got " + show(bodies));
  const auto gens_it = root.find("generators");
  const Json& gens = gens_it == root.end() ? kEmpty : *gens_it;
  if (!gens.is_array()) fail(ctx, "generators", "expected an array, got " + show(gens));
  const auto joints_it = root.find("joints");
  const Json& joints = joints_it == root.end() ? kEmpty : *joints_it;
  if (!joints.is_array()) fail(ctx, "joints", "expected an array of joints, got " + show(joints));
  if (bodies.size() > kMaxBodies) {
    fail(ctx, "bodies", "too many bodies: at most " + std::to_string(kMaxBodies) + " are allowed");
  }

  // determinism: ordered map; only looked up, never iterated into results.
  std::map<std::string, std::size_t> names;
  scene.bodies.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Ctx body_ctx{file_name, body_where(i, ""), ""};
    if (bodies[i].is_object()) {
      const auto name = bodies[i].find("name");
      if (name != bodies[i].end() && name->is_string()) {
        body_ctx.where = body_where(i, name->get<std::string>());
      }
    }
    SceneBody b = parse_body(body_ctx, bodies[i]);
    if (!b.name.empty()) {
      const auto [it, inserted] = names.emplace(b.name, i);
      if (!inserted) {
        fail(body_ctx, "name",
             "duplicate name \"" + b.name + "\" (also body " + std::to_string(it->second) + ")");
      }
    }
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
    Ctx joint_ctx{file_name, joint_where(i, ""), ""};
    if (joints[i].is_object()) {
      const auto name = joints[i].find("name");
      if (name != joints[i].end() && name->is_string()) {
        joint_ctx.where = joint_where(i, name->get<std::string>());
      }
    }
    SceneJoint sj = parse_joint(joint_ctx, joints[i], refs);
    if (!sj.name.empty()) {
      const auto [it, inserted] = joint_names.emplace(sj.name, i);
      if (!inserted) {
        fail(joint_ctx, "name",
             "duplicate name \"" + sj.name + "\" (also joint " + std::to_string(it->second) + ")");
      }
    }
    scene.joints.push_back(std::move(sj));
  }
  for (SceneJoint& j : generated) scene.joints.push_back(std::move(j));
  return scene;
}

Scene load_scene(const std::string& path) {
  return parse_scene(detail::read_scene_file(path), path);
}

}  // namespace elan
