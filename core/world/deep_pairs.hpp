// SPDX-License-Identifier: MIT
// The deep-pair budget: bodies spawned at one point overlap all the others, and n of them make
// n (n - 1) / 2 deeply interpenetrating pairs, each a manifold of up to four points for the
// collide stage and the solver, so a step grew with the square of the bodies (1,000 boxes at
// one point: 2 million contact points, seconds a step). A body keeps at most kDeepPairBudget of
// its deep pairs with other dynamic bodies a step; the others wait until the kept ones have
// pushed it out (Jolt bounds its contact constraints the same way, by a global budget, and
// drops the rest). Which it keeps is fixed by the sorted pair list alone, so the choice is the
// same for any thread count and either broadphase.
//
// Which pairs are deep: core/base/deep_overlap.hpp (kDeepFraction, inner_ball_radius), the test
// the collide stage shares: in a step where this budget dropped pairs, it gives the kept deep
// pairs a contact of constant cost (narrowphase/deep_contact.hpp). No body of an ordinary scene
// has more deep pairs than the budget, so its pair list and its contacts are never changed.
#pragma once

#include <cstdint>

#include <cstddef>

#include "core/base/deep_overlap.hpp"
#include "elan/math.hpp"

namespace elan::detail {

struct WorldState;

// Deep pairs a dynamic body keeps in one step: more than the face neighbours of a box in a
// grid (6), so that a body packed in harder than any ordinary load presses it keeps its
// neighbours.
inline constexpr uint32_t kDeepPairBudget = 8;

// Stage (after the pair filters, before the collide stage): drops from w.pairs, in key order,
// each deep pair one of whose bodies already keeps kDeepPairBudget deep pairs. Parallel over
// blocks of pairs for the test (a flag per pair, rule 1); the budget is counted serially in pair
// order, and only when some block found a deep pair. Returns the number of pairs dropped.
std::size_t limit_deep_pairs(WorldState& w);

}  // namespace elan::detail
