// SPDX-License-Identifier: MIT
// Contact events and the pair filter of the public API: what the world reports after a step and
// how the caller vetoes pairs.
#pragma once

#include <functional>

#include "elan/ids.hpp"
#include "elan/math.hpp"

namespace elan {

/// A pair started touching in the last step: its manifold went from 0 points (or no manifold)
/// to at least one. Speculative points (a small positive gap) count, as in Box2D.
struct ContactBeginEvent {
  BodyId body_a;  ///< the static or kinematic body, if any, is body_b
  BodyId body_b;
  Vec3 point = Vec3::Zero();    ///< m, world: mean of the manifold's points at the step's start
  Vec3 normal = Vec3::UnitY();  ///< unit, world, from body_a towards body_b
  Real normal_impulse = 0;      ///< N s: sum over the points of the impulse applied this step
};

/// A pair stopped touching: its manifold went from at least one point to none, the pair left
/// the broadphase, or one of the bodies was destroyed (then that id is already stale).
struct ContactEndEvent {
  BodyId body_a;
  BodyId body_b;
};

/// Pair filter, called for every pair the broadphase finds (after the category/mask test);
/// return false to drop the pair (no contact, no events). threading: called from the step's
/// worker threads concurrently and in no fixed order, so it must be thread-safe and must not
/// throw; it must be deterministic (same answer for the same two ids), or the simulation is not.
using PairFilter = std::function<bool(BodyId, BodyId)>;

}  // namespace elan
