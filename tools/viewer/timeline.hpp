// SPDX-License-Identifier: MIT
// Replay of a recording on a timeline: the simulation is moved to any step by restoring the
// keyframe at or before it (a full snapshot) and replaying the rest (a program recording's calls
// included), so a seek costs at most one keyframe interval of steps; every state reached is
// checked against the recorded hash.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "tools/recording.hpp"
#include "tools/viewer/simulation.hpp"

namespace elan::viewer {

class Timeline {
 public:
  explicit Timeline(const cli::Recording& recording) : recording_(&recording) {}

  uint64_t length() const { return recording_->steps; }
  /// Moves `sim` to `step` (clamped to the recording): forward by stepping when that is no
  /// farther than the keyframe interval, else from the nearest keyframe at or before it.
  void seek(Simulation& sim, uint64_t step);
  /// One step forward, if the recording goes on.
  void advance(Simulation& sim);
  /// Whether the state's hash is the recorded one at the simulation's step.
  bool matches(const Simulation& sim) const;
  /// The first step seen whose hash differed from the recording's.
  std::optional<uint64_t> first_mismatch() const { return first_mismatch_; }
  /// Why the replay stopped short, if it did: a recorded call that failed on replay (the replay
  /// had parted from the recording). Advancing then stops at that step; seeking clears it.
  const std::string& error() const { return error_; }

 private:
  void check(const Simulation& sim);
  // One step of the recording; false (error_ set) when a recorded call fails.
  bool replay_one(Simulation& sim);

  const cli::Recording* recording_;
  std::optional<uint64_t> first_mismatch_;
  std::string error_;
};

}  // namespace elan::viewer
