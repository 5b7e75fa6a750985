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

// Keeps the bodies (hence the key) of each touching manifold of w.contacts in w.previous_touching.
// Call before the collide stage rewrites the list.
void remember_touching(WorldState& w);

// Fills w.api.begin_events / end_events (cleared first) by merging last step's touching pairs
// (w.previous_touching) with this step's contacts (w.contacts), both sorted by key. Call after the
// solve, before the body columns are updated (event points use the step's start pose).
void compute_contact_events(WorldState& w);

}  // namespace elan::detail
