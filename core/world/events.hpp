// SPDX-License-Identifier: MIT
// Step hooks of the embedding API: the pair filter after the broadphase and contact begin/end
// events after the solve. Both run inside the step, over the world's arrays.
#pragma once

#include "core/world/world_state.hpp"

namespace elan::detail {

// Id of the body at dense index i.
inline BodyId body_id_at(const WorldState& w, uint32_t i) {
  const uint32_t slot = w.bodies.slot[i];
  return BodyId{slot, w.slot_generation[slot]};
}

// Drops the pairs of w.pairs that w.api.pair_filter rejects; the list stays sorted. No-op
// without a filter.
void filter_pairs(WorldState& w);

// Fills w.api.begin_events / end_events (cleared first) from the manifolds the collide stage
// started and ended (w.contacts.began(), .ended()): a manifold holds points, so a pair touches
// while its key is in w.contacts. Reads the impulses the solve left in the manifolds, and
// `start`: the bodies' poses at the step's start, which the manifolds' points are measured
// from (an event's point is A's centre there plus the mean of A's arms).
void compute_contact_events(WorldState& w, const BodyStore& start);

}  // namespace elan::detail
