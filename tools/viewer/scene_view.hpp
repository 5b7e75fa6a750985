// SPDX-License-Identifier: MIT
// What the renderer draws of a simulation: one mesh per distinct shape (sphere, box and cylinder
// share unit meshes scaled per body), each body an instance at its shape frame's pose, coloured
// by motion type (sleeping bodies dimmed, the selected one highlighted), and the joints as lines.
// The body poses are read from the world after each step; nothing is written back.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tools/viewer/renderer.hpp"
#include "tools/viewer/simulation.hpp"

namespace elan::viewer {

/// Where the picture is seen from, for choosing each body's tessellation: a curved body whose
/// bounding sphere spans fewer than kCoarseBelowPixels pixels of radius is drawn with kCoarse.
struct DetailView {
  Eigen::Vector3f eye = Eigen::Vector3f::Zero();
  /// Pixels per unit of (size / distance): (picture height / 2) / tan(vertical field / 2).
  float pixels_per_unit = 0;
};
inline constexpr float kCoarseBelowPixels = 10;

class SceneView {
 public:
  /// Fills the renderer with this frame's instances and joint lines (meshes are rebuilt when
  /// the simulation's bodies changed). `selected` and `highlighted` are dense body indices.
  /// With kDrawIslands in `overlays`, dynamic bodies take their island's colour (the library's
  /// debug draw) instead of their own; with kDrawSolverHalves, awake dynamic bodies take the
  /// colour of the half the last step's solver put them in.
  /// Without `detail` every body gets the fine tessellation.
  void update(const Simulation& sim, Renderer& renderer, std::optional<std::size_t> selected,
              std::optional<std::size_t> highlighted, uint32_t overlays = 0,
              const DetailView* detail = nullptr);

 private:
  void rebuild(const Simulation& sim, Renderer& renderer);
  // The mesh and scale of body `i` for its current shape.
  void assign(const Simulation& sim, Renderer& renderer, std::size_t i);

  uint64_t version_ = UINT64_MAX;
  const Simulation* sim_ = nullptr;
  // Per dense body index: its mesh, fine and coarse (the same for a shape with no curve).
  std::vector<std::array<int, 2>> body_mesh_;
  std::vector<Eigen::Vector3f> body_scale_;
  std::vector<float> body_radius_;   // m, of the bounding sphere about the shape frame's origin
  std::vector<ShapeId> body_shape_;  // the shape each body had when its mesh was chosen
  // Capsules are drawn as three instances of shared unit meshes (two hemispheres and a tube),
  // so that a pile of capsules of many sizes costs three draw calls, not one per size.
  std::vector<Eigen::Vector2f> body_capsule_;  // radius, half height; radius 0: not a capsule
  int unit_meshes_[2][5] = {{-1, -1, -1, -1, -1}, {-1, -1, -1, -1, -1}};  // fine, coarse:
  // sphere, box, cylinder, hemisphere, tube
  std::map<std::string, std::array<int, 2>> own_meshes_;  // shape key -> fine, coarse mesh
  std::vector<Eigen::Vector4f> island_colors_;
};

/// A body's colour: dynamic bodies from a palette by index, static grey, kinematic blue; dimmed
/// when asleep.
Eigen::Vector4f body_color(std::size_t index, MotionType motion, bool awake);

/// A sensor's colour, whatever its motion: translucent green (drawn after the solid bodies,
/// blended, so what is inside or behind it shows through).
inline constexpr float kSensorColor[4] = {0.3f, 0.9f, 0.4f, 0.35f};

}  // namespace elan::viewer
