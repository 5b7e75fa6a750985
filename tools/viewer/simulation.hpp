// SPDX-License-Identifier: MIT
// The viewer's simulation: the world stepped exactly as `elan run` steps it (the same library,
// the same timestep), plus what the viewer adds between steps (balls shot from the camera, every
// body kept awake when sleeping is switched off), the shape of every body for drawing, and the
// joints' anchors in their bodies' frames.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/recording.hpp"
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
  Real timestep() const { return source_.timestep; }
  /// Steps since the scene was loaded (or since the keyframe restored).
  uint64_t step_count() const { return steps_; }
  /// The shape of body `index` (dense index): the scene's, or a ball shot from the camera.
  const ShapeDef& body_shape(std::size_t index) const;
  /// Changes whenever bodies are added or the world is replaced: the renderer rebuilds meshes.
  uint64_t version() const { return version_; }
  const std::vector<JointLink>& joints() const { return joints_; }

  /// One step of the scene's timestep. With sleeping switched off, every dynamic body is woken
  /// first.
  uint32_t step();
  /// The world as loaded from the scene, settings (substeps, iterations, threads, gravity) kept.
  void reset();
  /// The state of a recording's keyframe (for seeking on the replay timeline).
  void restore(const cli::Keyframe& keyframe);
  /// Shoots a ball from `origin` along `direction` (unit) at `speed` m/s.
  void shoot(const Vec3& origin, const Vec3& direction, Real radius, Real speed);

  bool sleeping = true;  ///< false: every dynamic body is kept awake
  Vec3 gravity;          ///< as last set

 private:
  void load_joints();

  Source source_;
  World world_;
  uint64_t steps_ = 0;
  uint64_t version_ = 0;
  std::vector<ShapeDef> added_;  // shapes of bodies the viewer added, after the scene's
  std::vector<JointLink> joints_;
};

}  // namespace elan::viewer
