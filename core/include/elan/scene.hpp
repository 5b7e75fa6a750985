// SPDX-License-Identifier: MIT
// Scene files (JSON, see README "Scene file"): parsing with validation, and loading into a World.
// These functions are in the library elan::elan_scene, so that the core elan links no JSON parser.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "elan/defs.hpp"
#include "elan/one_line.hpp"
#include "elan/world.hpp"

namespace elan {

/// A scene file was rejected. what() is one line naming the file, the body (index and name when
/// it has one) and the field, e.g.
/// `scene.json: body 3 ("ball"): shape.radius: must be positive, got -1`.
class SceneError : public std::runtime_error {
 public:
  /// Control characters in `message` (from a body name, a key, a path) are escaped (one_line).
  /// `field` is the field at fault as the message names it (e.g. "shape.radius"), or empty when
  /// the error is not about one field (unreadable file, malformed JSON).
  explicit SceneError(const std::string& message, std::string field = {})
      : std::runtime_error(one_line(message)), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

struct SceneBody {
  std::string name;  ///< empty when the file gives none
  ShapeDef shape;
  BodyDef body;  ///< body.shape is filled by load_into
};

/// A joint of the scene file, its bodies resolved to scene body indices.
struct SceneJoint {
  std::string name;  ///< empty when the file gives none
  int body_a = -1;   ///< scene body index
  int body_b = -1;   ///< scene body index, -1 = the static world
  JointDef def;      ///< def.body_a / body_b are filled by load_into
};

struct Scene {
  WorldDef world;                    ///< gravity, substeps, iterations, allow_sleep
  Real timestep = Real(1.0 / 60.0);  ///< s per step
  bool has_substeps = false;         ///< the file set `substeps`
  bool has_iterations = false;       ///< the file set `iterations`
  std::vector<SceneBody> bodies;     ///< explicit bodies first, then generated ones, in order
  std::vector<SceneJoint> joints;    ///< explicit joints first, then generated ones, in order
};

/// Parses scene text; `file_name` is used in messages only. Throws SceneError.
Scene parse_scene(const std::string& text, const std::string& file_name);
/// Reads and parses a scene file. Throws SceneError (also for an unreadable file).
Scene load_scene(const std::string& path);
/// Creates the scene's shapes (identical shape definitions are shared) and bodies in `world`,
/// in scene order, so body index i is the scene's body i, then its joints, in order (joint index
/// j is the scene's joint j). Throws SceneError.
void load_into(const Scene& scene, World& world, const std::string& file_name);

}  // namespace elan
