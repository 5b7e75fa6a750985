// The step pipeline: the stages of architecture.md called in order over the world's arrays.
#pragma once

#include "core/world/world_state.hpp"

namespace elan::detail {

// Advances `w` by dt (validated by the caller). Runs inside the world's arena. Returns status.
uint32_t run_step(WorldState& w, Real dt);

// Keeps last step's manifolds of pairs the broadphase no longer reports because neither body is
// awake (a sleeping island keeps its contacts, so it wakes whole and warm-started), merged into
// `contacts` by key, in place. Both inputs are sorted by key; so is the result.
void carry_sleeping_contacts(const BodyStore& bodies, std::span<const Manifold> previous,
                             std::vector<Manifold>& contacts);

}  // namespace elan::detail
