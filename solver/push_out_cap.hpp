// SPDX-License-Identifier: MIT
// The push-out cap on the velocity a step leaves: bodies spawned into each other are pushed
// apart by their contacts' soft springs at up to settings.max_push_velocity per contact
// (Box2D v3's contactPushMaxVelocity), but one relax pass per substep does not take that speed
// back where a body is pushed from many sides, and pushes along chains of overlapping bodies add
// up: 100 boxes spawned at one point, lined up on one axis, reached 56 m/s. The position change
// of the step keeps the push; the velocity the step ends with does not keep more than the cap
// (a pseudo-velocity in effect, as split impulses give, for these bodies only).
//
// Which bodies: those marked as separating (kSeparating, separating_mark.hpp), from the step
// where they are found in a clique of deep overlaps until they are out of every overlap deeper
// than kSeparatingDepth, so that a chain of shallow overlaps, each link pushing below the cap,
// does not throw its ends out either. No body of an ordinary scene is ever marked, so no
// ordinary scene's bits change (a landing body that the solve sent off faster than it came is
// left as it is).
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
#include "core/base/contact.hpp"
#include "core/base/shape.hpp"
#include "solver/solve.hpp"

namespace elan::detail {

// Stage (after the colouring, before the solve): which packets are capped in this step, in
// st.capped (cleared when none): those that carry the mark (kSeparating) or have a deep manifold
// (deep_count > 0) while `marked` or st.most_deep > kPushShare (st.capped 1: capped in the
// substeps and at the step's end), and those with a touching manifold (a point, any depth) with
// a body that carries the mark (st.capped 2: at the step's end only). Why the neighbours: a
// marked body pushed from behind by its own overlaps hands the push on through a shallow contact
// within the substep, before any cap slows it, and a box beside the pushed cloud, not marked,
// was sped from 3 to 7 m/s along the slab that way (1,000 boxes at one point). Not in the
// substeps: slowing a neighbour there while its marked partner's contact impulse stays made 100
// boxes throw one out at 17 m/s. Serial over the packets and
// the manifolds in order (indexed writes); nothing unless `marked` or a clique (an ordinary scene
// has neither).
void find_capped(const BodyStore& bodies, std::span<const ManifoldHead> contacts, bool marked,
                 SolverState& st);

// Stage (after the solve and mark_separating, before the continuous stage: the body store still
// holds the step's start). Reads: st.capped, the bodies' start velocities, gravity scales and
// shapes, the packets' v, w and dp. Writes: v and w of the capped packets. Serial over the
// packets in order (indexed writes); nothing when st.capped is empty. Returns the number of
// packets slowed.
std::size_t cap_push_out_velocity(const BodyStore& bodies, std::span<const Shape> shapes,
                                  const SolveSettings& settings, SolverState& st);

// Within the step, before each substep moves the bodies (the relax pass's position update): the
// same bound on the linear speed of the packets in [begin, end) with st.capped 1,
// |v| <= max(|v0|, cap) + |g| dt.
// Why: the end-of-step cap alone left the substeps free to move a marked body at the chain's
// summed push (17 m/s), and a body it ran into, not yet marked, kept that speed as its own
// (3 m/s to 16.5 m/s in one step). Capped here, a marked body moves no faster than the cap, and
// hands no more on. |g| dt, not the energy bound: the step's fall is not known per substep; the
// end-of-step cap takes the rest. Run by the halves' blocks on their own packets, only when
// st.capped is not empty (never in an ordinary scene).
void cap_push_out_substep(const BodyStore& bodies, const SolveSettings& settings, SolverState& st,
                          uint32_t begin, uint32_t end);

}  // namespace elan::detail
