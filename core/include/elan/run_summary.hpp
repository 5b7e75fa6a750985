// SPDX-License-Identifier: MIT
// The summary `elan run` prints (README "elan run"), computed here so that every front end (the
// command line, the Python module) reports the same keys and values for the same run. In the
// library elan::elan_scene, which has the JSON writer.
#pragma once

#include <cstdint>
#include <string>

#include "elan/defs.hpp"
#include "elan/profile.hpp"
#include "elan/world.hpp"

namespace elan {

/// The broadphase's name in scene files and options: "sap", "all-pairs" or "tree".
const char* broadphase_name(BroadphaseType type);
/// Worker count that `threads` (0 = all cores) stands for: at most the threads oneTBB runs at
/// once (the machine's cores).
int resolve_threads(int threads);

/// What a run accumulates over its steps.
struct RunTotals {
  uint64_t steps = 0;
  uint32_t status = kStepOk;  ///< OR of every step's StepStatus flags
  double wall_seconds = 0;    ///< s spent in World::step
  StepProfile profile;        ///< ms per stage, summed over the steps

  /// Counts one step of `world` that returned `status` and took `wall_seconds`; adds its
  /// last_step() profile.
  void add(const World& world, uint32_t status, double wall_seconds);
};

/// The run's summary as one line of JSON (no newline), keys in a fixed order: scene, bodies,
/// joints, steps, threads, broadphase, timestep, substeps, iterations, wall_seconds,
/// ms_per_step, state_hash (16 hex digits), kinetic_energy, linear_momentum,
/// angular_momentum, pairs, manifolds, contacts, awake, colors, overflow, status, profile_ms.
/// `scene` is the name printed; `timestep` the s per step the run used. Bytes of `scene` that
/// are not UTF-8 are printed as U+FFFD.
std::string run_summary_json(const World& world, const std::string& scene, Real timestep,
                             const RunTotals& totals);

}  // namespace elan
