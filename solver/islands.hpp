// SPDX-License-Identifier: MIT
// The islands and sleep stage: bodies linked by touching contacts form islands (union-find that
// links toward the lower index, as Jolt does); an island sleeps when all its bodies have been
// slow for a while, and wakes as a whole when any of its bodies is awake or touched by a moving
// kinematic body.
//
// Reads: contacts, joint links, motion types, flags, sleep timers, kinematic velocities.
// Writes: awake flags, sleep timers and the velocities of bodies put to sleep (zeroed).
// Serial: union-find is cheap next to the solve, and its result does not depend on link order.
#pragma once

#include <cstdint>
#include <span>

#include "core/base/body_store.hpp"
#include "core/base/contact.hpp"
#include "core/base/shape.hpp"
#include "core/base/step_scratch.hpp"
#include "solver/joint_rows.hpp"

namespace elan::detail {

// Taken from the step's scratch and given back within update_islands.
struct IslandScratch {
  ScratchVector<uint32_t> parent;
  ScratchVector<Real> island_sleep_time;
  ScratchVector<uint8_t> island_awake;
  // Kept after the stage (the direct solve reads them): per body its island's root (its lowest
  // body), UINT32_MAX for a body outside any island (static, kinematic, frozen); per root the
  // island's body count.
  std::vector<uint32_t> root;
  std::vector<uint32_t> size;
};

struct IslandSettings {
  bool allow_sleep = true;
  Real time_to_sleep = Real(0.5);  // s an island must stay slow before it sleeps
};

// Joints link their bodies like touching contacts (a joint to the world or to a static body links
// nothing; one to a moving kinematic body keeps its island awake, as a contact does).
// Returns the number of islands with more than one body (for the profile).
// `scratch`'s arrays are taken from `step_scratch` in its current phase and given back.
std::size_t update_islands(BodyStore& bodies, std::span<const ManifoldHead> contacts,
                           std::span<const JointLink> joints, const IslandSettings& settings,
                           IslandScratch& scratch, StepScratch& step_scratch);

// Updates each awake dynamic body's sleep timer from its velocity after the step: the timer
// grows by dt while max(|v|, |w| * bounding_radius) stays under `threshold` m/s (Box2D v3's
// sleep velocity), and resets otherwise.
void update_sleep_timers(BodyStore& bodies, std::span<const Shape> shapes, Real dt, Real threshold);

}  // namespace elan::detail
