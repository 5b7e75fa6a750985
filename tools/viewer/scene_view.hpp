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
  /// With kDrawIslands in `overlays`, dynamic bodies take their island's colour (the library's
  /// debug draw) instead of their own.
  void update(const Simulation& sim, Renderer& renderer, std::optional<std::size_t> selected,
              std::optional<std::size_t> highlighted, uint32_t overlays = 0);

 private:
  void rebuild(const Simulation& sim, Renderer& renderer);
  // The mesh and scale of body `i` for its current shape.
  void assign(const Simulation& sim, Renderer& renderer, std::size_t i);

  uint64_t version_ = UINT64_MAX;
  const Simulation* sim_ = nullptr;
  std::vector<int> body_mesh_;  // per dense body index
  std::vector<Eigen::Vector3f> body_scale_;
  std::vector<ShapeId> body_shape_;        // the shape each body had when its mesh was chosen
  int unit_meshes_[3] = {-1, -1, -1};      // sphere, box, cylinder
  std::map<std::string, int> own_meshes_;  // shape key -> mesh
  std::vector<Eigen::Vector4f> island_colors_;
};

/// A body's colour: dynamic bodies from a palette by index, static grey, kinematic blue; dimmed
/// when asleep.
Eigen::Vector4f body_color(std::size_t index, MotionType motion, bool awake);

/// A sensor's colour, whatever its motion: translucent green (drawn after the solid bodies,
/// blended, so what is inside or behind it shows through).
inline constexpr float kSensorColor[4] = {0.3f, 0.9f, 0.4f, 0.35f};

}  // namespace elan::viewer
