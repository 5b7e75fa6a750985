// SPDX-License-Identifier: MIT
// Command-line options of `elan run`, `elan replay`, `elan diverge` and `elan view`: hand-written
// parsing, strict numbers.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "elan/defs.hpp"
#include "elan/one_line.hpp"
#include "elan/run_summary.hpp"

namespace elan::cli {

/// A bad command line: reported with a hint to --help, exit status 2.
class UsageError : public std::runtime_error {
 public:
  /// Control characters in `message` (from a command-line word) are escaped (one_line).
  explicit UsageError(const std::string& message) : std::runtime_error(one_line(message)) {}
};

struct RunOptions {
  bool help = false;
  std::string scene;
  uint64_t steps = 600;
  std::optional<double> timestep;  // s; overrides the scene's
  std::optional<int> substeps;
  std::optional<int> iterations;
  int threads = 0;  // 0 = all cores
  BroadphaseType broadphase = BroadphaseType::SweepAndPrune;
  SimdPath simd = SimdPath::Best;  // --simd; Best: ELAN_SIMD, else the CPU's widest
  std::string trajectory;          // CSV path, empty = none
  uint64_t every = 1;
  bool has_every = false;
  std::string record;            // recording path, empty = none
  uint64_t keyframe_every = 60;  // a full snapshot in the recording every K steps; 0 = none
  bool has_keyframe_every = false;
};

/// `--perturb BODY:STEP`, a testing aid: after STEP steps (0 = before the first), body BODY's
/// stored x position is moved up by one ulp, so a divergence finder has something to find.
struct Perturbation {
  uint64_t body = 0;
  uint64_t step = 0;
};

struct ReplayOptions {
  bool help = false;
  std::string file;
  int threads = 0;                           // 0 = all cores
  std::optional<BroadphaseType> broadphase;  // default: the recorded one
  std::optional<Perturbation> perturb;
  std::optional<uint64_t> until;  // --until STEP: stop after STEP steps
  std::string save_snapshot;      // --save-snapshot OUT: the state there, as a snapshot
  std::string save_scene;         // --save-scene OUT: the state there, as a scene file
};

/// The settings of one side of `elan diverge`.
struct SideOptions {
  int threads = 1;
  BroadphaseType broadphase = BroadphaseType::SweepAndPrune;
  std::optional<int> substeps;
  std::optional<int> iterations;
  std::optional<Perturbation> perturb;
};

struct DivergeOptions {
  bool help = false;
  std::string scene;
  uint64_t steps = 600;
  std::optional<double> timestep;  // s; overrides the scene's
  SideOptions a, b;
};

/// `elan view`: a window on a scene or a recording, or (with --screenshot / --frames) pictures
/// rendered off screen.
struct ViewOptions {
  bool help = false;
  std::string file;  // a scene or a recording
  bool paused = false;
  int threads = 0;                 // 0 = all cores
  std::string screenshot;          // PNG path, empty = none
  std::string frames;              // directory of numbered PNG frames, empty = none
  uint64_t every = 1;              // with --frames: a frame every K steps
  uint64_t steps = 0;              // steps before the screenshot (or before the window opens)
  int width = 1280, height = 720;  // pixels, of the off-screen picture or the window
  bool has_camera = false;
  double camera[6] = {0, 0, 0, 0, 0, 0};  // eye x y z, target x y z (m, world)
  std::optional<uint64_t> step;           // recording: open at this step
  std::optional<uint64_t> body;           // recording: highlight this body
  uint32_t draw = 0;                      // overlays (elan::DebugDrawFlags) from --draw
};

/// `args` are the words after the command name. Throw UsageError.
RunOptions parse_run_options(std::span<const std::string> args);
ReplayOptions parse_replay_options(std::span<const std::string> args);
DivergeOptions parse_diverge_options(std::span<const std::string> args);
ViewOptions parse_view_options(std::span<const std::string> args);

extern const char* const kMainUsage;
extern const char* const kRunUsage;
extern const char* const kReplayUsage;
extern const char* const kDivergeUsage;
extern const char* const kViewUsage;

}  // namespace elan::cli
