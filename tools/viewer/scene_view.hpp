// SPDX-License-Identifier: MIT
// What the renderer draws of a simulation: one mesh per distinct shape (sphere, box and cylinder
// share unit meshes scaled per body), each body an instance at its shape frame's pose, coloured
// by motion type (sleeping bodies dimmed, the selected one highlighted), and the joints as lines.
// The body poses are read from the world after each step; nothing is written back.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tools/viewer/renderer.hpp"
#include "tools/viewer/simulation.hpp"

namespace elan::viewer {

class SceneView {
 public:
  /// Fills the renderer with this frame's instances and joint lines (meshes are rebuilt when
  /// the simulation's bodies changed). `selected` and `highlighted` are dense body indices.
  void update(const Simulation& sim, Renderer& renderer, std::optional<std::size_t> selected,
              std::optional<std::size_t> highlighted);

 private:
  void rebuild(const Simulation& sim, Renderer& renderer);

  uint64_t version_ = UINT64_MAX;
  const Simulation* sim_ = nullptr;
  std::vector<int> body_mesh_;  // per dense body index
  std::vector<Eigen::Vector3f> body_scale_;
  int unit_meshes_[3] = {-1, -1, -1};      // sphere, box, cylinder
  std::map<std::string, int> own_meshes_;  // shape key -> mesh
};

/// A body's colour: dynamic bodies from a palette by index, static grey, kinematic blue; dimmed
/// when asleep.
Eigen::Vector4f body_color(std::size_t index, MotionType motion, bool awake);

}  // namespace elan::viewer
