// SPDX-License-Identifier: MIT
// The push-out cap on the velocity a step leaves: bodies spawned into each other are pushed
// apart by their contacts' soft springs at up to settings.max_push_velocity per contact
// (Box2D v3's contactPushMaxVelocity), but one relax pass per substep does not take that speed
// back where a body is pushed from many sides, and pushes along chains of overlapping bodies add
// up: 100 boxes spawned at one point, lined up on one axis, reached 56 m/s. The position change
// of the step keeps the push; the velocity the step ends with does not keep more than the cap
// (a pseudo-velocity in effect, as split impulses give, for these bodies only).
//
// When: in a step where some body has more than kPushShare deep manifolds (SolverState::
// most_deep, where the cap binds: color_contacts.hpp), the mark of bodies spawned into each
// other, which also shares their cap. Which bodies: every one with a deep manifold that step.
// A body of an ordinary scene has no deep manifold, or one where it landed hard: such a step
// never has a body with more than kPushShare of them, so no ordinary scene's bits change (a
// landing body that the solve sent off faster than it came is left as it is).
//
// The bound: a deep body ends the step with speed at most sqrt(max(|v0|, cap)^2 + 2 g . dp),
// v0 its velocity at the step's start, g its gravity and dp its displacement in the step (the
// energy of its start or of the cap, and what gravity's work adds on the way down), and with
// angular speed at most max(|w0|, cap / r), r its shape's bounding radius (its surface then
// turns no faster than the cap). Faster ones are scaled down, their direction kept.
#pragma once

#include <cstddef>
#include <span>

#include "core/base/body_store.hpp"
#include "core/base/shape.hpp"
#include "solver/solve.hpp"

namespace elan::detail {

// Stage (after the solve, before the continuous stage: the body store still holds the step's
// start). Reads: st.deep_count and st.most_deep (color_contacts), the packets' v, w and dp, the
// bodies' start velocities, gravity scales and shapes. Writes: v and w of the deep packets.
// Serial over the packets in order (indexed writes); nothing unless st.most_deep > kPushShare.
// Returns the number of packets slowed.
std::size_t cap_push_out_velocity(const BodyStore& bodies, std::span<const Shape> shapes,
                                  const SolveSettings& settings, SolverState& st);

}  // namespace elan::detail
