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
// started and ended (w.contact_blocks.began, .ended): a manifold holds points, so a pair touches
// while its key is in w.contacts. Call after the solve, before the body columns are updated
// (event points use the step's start pose).
void compute_contact_events(WorldState& w);

}  // namespace elan::detail
