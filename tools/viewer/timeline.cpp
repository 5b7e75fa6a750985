// SPDX-License-Identifier: MIT
#include "tools/viewer/timeline.hpp"

#include <algorithm>

namespace elan::viewer {

void Timeline::seek(Simulation& sim, uint64_t step) {
  step = std::min(step, length());
  const uint64_t now = sim.step_count();
  const cli::Keyframe* k = cli::keyframe_at_or_before(*recording_, step);
  const bool forward_is_short = step >= now && (k == nullptr || k->step <= now);
  if (!forward_is_short || !error_.empty()) {
    error_.clear();
    if (k != nullptr && k->step <= step) {
      sim.restore(*k);
    } else {
      sim.reset();
    }
    check(sim);
  }
  while (sim.step_count() < step && replay_one(sim)) check(sim);
}

void Timeline::advance(Simulation& sim) {
  if (sim.step_count() >= length() || !error_.empty()) return;
  if (replay_one(sim)) check(sim);
}

bool Timeline::replay_one(Simulation& sim) {
  try {
    sim.step();
    return true;
  } catch (const cli::RecordingError& e) {
    error_ = e.what();
    return false;
  }
}

bool Timeline::matches(const Simulation& sim) const {
  const uint64_t s = sim.step_count();
  return s < recording_->hashes.size() && recording_->hashes[s] == sim.world().state_hash();
}

void Timeline::check(const Simulation& sim) {
  if (!matches(sim) && (!first_mismatch_ || sim.step_count() < *first_mismatch_)) {
    first_mismatch_ = sim.step_count();
  }
}

}  // namespace elan::viewer
