// SPDX-License-Identifier: MIT
// The world's side of joints: the step's joint stages that need the world (pairs of jointed
// bodies that do not collide, broken joints) and the removals shared by the API.
#pragma once

#include <cstdint>

#include "core/world/world_state.hpp"

namespace elan::detail {

// Drops from w.pairs (sorted) the pairs of bodies joined by a joint without collide_connected.
// Reads the joint store (the sorted keys are rebuilt when its version moved). Nothing to do, and
// nothing read, in a world without such joints.
void drop_jointed_pairs(WorldState& w);

// Removes the joint at dense index k (the last joint takes its place) and frees its id.
void remove_joint(WorldState& w, uint32_t k);

// Removes every joint of the body in id slot `slot`, with a BodyDestroyed event each, in joint
// order; wakes their other bodies.
void remove_joints_of(WorldState& w, uint32_t slot);

// Removes the joints in w.broken_joints (ascending dense indices), with a Broke event each, in
// that order, and wakes their bodies.
void remove_broken_joints(WorldState& w);

}  // namespace elan::detail
