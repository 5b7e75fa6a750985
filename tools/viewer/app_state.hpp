// SPDX-License-Identifier: MIT
// The state of an interactive viewer session that the panels show and change: the simulation,
// the camera, play controls, the selection, the overlays, and the live histories for the plots.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tools/viewer/camera.hpp"
#include "tools/viewer/picking.hpp"
#include "tools/viewer/simulation.hpp"
#include "tools/viewer/timeline.hpp"

namespace elan::viewer {

/// The last `capacity` values of a quantity, oldest first, for a plot.
struct History {
  std::vector<float> values;
  std::size_t capacity = 300;
  void push(float v) {
    if (values.size() == capacity) values.erase(values.begin());
    values.push_back(v);
  }
};

struct AppState {
  std::unique_ptr<Simulation> sim;
  std::unique_ptr<Timeline> timeline;  ///< set when replaying a recording
  Camera camera;
  bool paused = false;
  bool step_once = false;
  float speed = 1;                      ///< simulated seconds per wall second (slow motion below 1)
  std::optional<std::size_t> selected;  ///< dense body index
  std::optional<std::size_t> highlighted;  ///< the body `--body` named
  bool follow = false;                     ///< the camera's target follows the selected body
  bool frame_request = false;
  bool reset_request = false;
  bool shoot_request = false;
  std::string open_request;  ///< a scene path to open
  std::string message;       ///< the last error, shown in the panel
  uint32_t overlays = 0;     ///< elan::DebugDrawFlags beyond the shapes
  Dragger dragger;
  Real drag_stiffness = 1;
  History step_ms, kinetic_energy;
  double frame_ms = 0;
  bool show_panels = true;
};

}  // namespace elan::viewer
