// SPDX-License-Identifier: MIT
#include "tools/viewer/timeline.hpp"

#include <algorithm>

namespace elan::viewer {

void Timeline::seek(Simulation& sim, uint64_t step) {
  step = std::min(step, length());
  const uint64_t now = sim.step_count();
  const cli::Keyframe* k = cli::keyframe_at_or_before(*recording_, step);
  const bool forward_is_short = step >= now && (k == nullptr || k->step <= now);
  if (!forward_is_short) {
    if (k != nullptr) {
      sim.restore(*k);
    } else {
      sim.reset();
    }
    check(sim);
  }
  while (sim.step_count() < step) {
    sim.step();
    check(sim);
  }
}

void Timeline::advance(Simulation& sim) {
  if (sim.step_count() >= length()) return;
  sim.step();
  check(sim);
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
