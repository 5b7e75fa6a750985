// SPDX-License-Identifier: MIT
// The viewer's simulation: the world stepped exactly as `elan run` steps it (the same library,
// the same timestep) or as `elan replay` replays a recording (a program recording's calls
// applied before each step), plus what the viewer adds between steps (balls shot from the
// camera, the live settings), the shape of every body for drawing, and the joints' anchors in
// their bodies' frames. No window or OpenGL here: tests drive it directly.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/recording.hpp"
#include "tools/viewer/live_settings.hpp"
#include "tools/viewer/viewer.hpp"

namespace elan::viewer {

/// A joint as drawn: lines from body A's origin to its anchor, across to B's anchor, and to B's
/// origin (B may be the static world: its anchor is then fixed in the world).
struct JointLink {
  JointId id;
  int body_a = -1, body_b = -1;  ///< dense body indices, -1 = the world
  Vec3 local_a = Vec3::Zero();   ///< m, anchor in A's shape frame
  Vec3 local_b = Vec3::Zero();   ///< m, anchor in B's shape frame (world when body_b is -1)
};

class Simulation {
 public:
  Simulation(Source source, World world);

  World& world() { return world_; }
  const World& world() const { return world_; }
  const Source& source() const { return source_; }
  /// A recording is played (its calls and timesteps), rather than the scene simulated.
  bool replaying() const { return source_.recording.has_value(); }
  Real timestep() const { return source_.timestep; }
  /// Steps since the scene was loaded (or the recording's step, after seeking).
  uint64_t step_count() const { return steps_; }
  /// The shape of body `index` (dense index): the scene's for a scene's body, else the world's
  /// (balls shot from the camera, bodies a recorded program created).
  const ShapeDef& body_shape(std::size_t index) const;
  /// Changes whenever the world is replaced or bodies are added by the viewer: the renderer
  /// rebuilds its meshes.
  uint64_t version() const { return version_; }
  /// Scene joints with their anchors; a program recording's joints are drawn from the world.
  const std::vector<JointLink>& joints() const { return joints_; }

  /// One step: the scene's timestep, or the recording's next step with the calls before it
  /// (elan::replay_step; throws RecordingError past the recording's end or when a recorded call
  /// fails).
  uint32_t step();
  /// The start again: the scene's world (or the recording's), live settings kept for a scene.
  void reset();
  /// The state of a recording's keyframe (for seeking on the replay timeline).
  void restore(const cli::Keyframe& keyframe);
  /// Shoots a ball from `origin` along `direction` (unit) at `speed` m/s.
  void shoot(const Vec3& origin, const Vec3& direction, Real radius, Real speed);

  /// The live settings: as the world has them, and applied to it (apply_settings).
  LiveSettings settings() const { return settings_of(world_); }
  void apply(const LiveSettings& s) { apply_settings(world_, s); }

 private:
  void load_joints();
  World start_world() const;

  Source source_;
  World world_;
  uint64_t steps_ = 0;
  uint64_t version_ = 0;
  std::vector<JointLink> joints_;
};

}  // namespace elan::viewer
