// SPDX-License-Identifier: MIT
// What a step did: counts, per-stage times and status flags, read after World::step.
#pragma once

#include <cstddef>
#include <cstdint>

namespace elan {

/// Status flags returned by World::step. The step never throws; problems are reported here.
enum StepStatus : uint32_t {
  kStepOk = 0,
  kStepFrozeNonFinite = 1u << 0,  ///< a body's state became non-finite and it was frozen
  kStepColorOverflow = 1u << 1,   ///< some constraints did not fit the colours: solved serially
  kStepBadTimestep = 1u << 2,     ///< dt was outside elan/limits.hpp's: nothing was simulated
};

/// Wall-clock milliseconds spent in each stage of the last step, in the step's order.
struct StepProfile {
  double bounds = 0;    ///< bounding boxes and the bodies' broadphase kinds
  double pairs = 0;     ///< the broadphase's pair list
  double collide = 0;   ///< manifolds of the pairs
  double islands = 0;   ///< islands, sleep and wake
  double split = 0;     ///< the median cut of the awake bodies into the solver's two halves
  double packets = 0;   ///< the solver's per-body packets for the step
  double color = 0;     ///< the contacts' groups and colours
  double bundles = 0;   ///< the layout of the constraint bundles
  double prepare = 0;   ///< the constraints' preparation
  double solve = 0;     ///< substeps, restitution, and the contact events
  double ccd = 0;       ///< continuous collision
  double finalize = 0;  ///< results written back, sleep timers
  double total = 0;
};

/// Counts of the last step.
struct StepStats {
  std::size_t pairs = 0;      ///< pairs the broadphase reported
  std::size_t manifolds = 0;  ///< touching or near pairs
  std::size_t contacts = 0;   ///< contact points in all manifolds (speculative included)
  std::size_t awake = 0;      ///< awake dynamic bodies
  std::size_t colors = 0;     ///< most colours used by one solver group (overflow not counted)
  std::size_t overflow = 0;   ///< manifolds in the groups' overflows (one per SIMD bundle)
  uint32_t status = kStepOk;  ///< StepStatus flags
  StepProfile profile;
};

}  // namespace elan
