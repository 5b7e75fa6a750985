// SPDX-License-Identifier: MIT
// `elan view`: the entry point of the viewer, called by the elan command once the scene (or the
// recording) has been read, checked and loaded into a world, so that no window opens for a bad
// file.
#pragma once

#include <optional>
#include <string>

#include "elan/scene.hpp"
#include "elan/world.hpp"
#include "tools/options.hpp"
#include "tools/recording.hpp"

namespace elan::viewer {

/// What the viewer shows: a scene and the world loaded from it, or a recording to replay.
struct Source {
  std::string name;  ///< the scene's file (or the recorded scene's), for the title and messages
  Scene scene;
  WorldDef def;  ///< the settings the world was made with (threads resolved)
  Real timestep = Real(1.0 / 60.0);
  std::optional<cli::Recording> recording;
};

/// Opens the window (or renders off screen for --screenshot / --frames) and returns the exit
/// status: 0, or 2 when no display or no OpenGL 3.3 context can be had (one line on stderr).
int run(const cli::ViewOptions& options, Source source, World world);

}  // namespace elan::viewer
