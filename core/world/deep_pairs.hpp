// SPDX-License-Identifier: MIT
// The deep-pair budget: bodies spawned at one point overlap all the others, and n of them make
// n (n - 1) / 2 deeply interpenetrating pairs, each a manifold of up to four points for the
// collide stage and the solver, so a step grew with the square of the bodies (1,000 boxes at
// one point: 2 million contact points, seconds a step). A body keeps at most kDeepPairBudget of
// its deep pairs with other dynamic bodies a step; the others wait until the kept ones have
// pushed it out (Jolt bounds its contact constraints the same way, by a global budget, and
// drops the rest).
//
// Two cuts, each a function of the scene's state alone, so the pairs are the same for any thread
// count and every broadphase:
// - in the broadphase, the deep sieve (broadphase/deep_sieve.hpp) keeps of each body's deep
//   pairs only its DeepSieve::kCandidates best (those in its own run of 9 consecutive indices,
//   then those of its run's group of 8 runs, 64, ..., each level by a hash of the pair), so a
//   crowd's pairs are never all stored nor sorted (10,000 boxes at one point: 50 million pairs),
//   and the sweep passes by, without offering them, the pairs the sieve would turn away
//   (broadphase/closed_runs.hpp);
// - after the pair filters, the budget: in sorted pair order, each deep pair one of whose bodies
//   already keeps kDeepPairBudget deep pairs is dropped; and a crowd's near pairs have a budget
//   of their own: a pair of two dynamic convex bodies that is not deep, one of whose bodies has at
//   least kDeepPairBudget deep partners (its sieve set is full), is dropped when one of its bodies
//   already keeps kDeepPairBudget such pairs. A crowd that spreads has, besides its deep pairs,
//   hundreds of overlaps a body just outside the deep test (10,000 boxes at one point after ten
//   steps: 2.7 million pairs), which the bodies pass through
//   as they do their dropped deep ones. A body of an ordinary scene has a deep pair only where
//   it is pressed hard (deep_overlap.hpp), never a crowd's.
// A world with a user pair filter skips the sieve (the filter must see every pair; the budget
// still applies), as does a sensor's pair (its inner ball is 0: sensors report overlaps).
//
// Which pairs are deep: core/base/deep_overlap.hpp (kDeepFraction, inner_ball_radius), the test
// the collide stage shares: in a step where a crowd was found
// (a body with at least kDeepPairBudget deep partners) or this budget dropped pairs, it gives the
// kept deep pairs a contact of constant cost (narrowphase/deep_contact.hpp). A body with at most
// kCandidates deep partners keeps them all through the sieve, so only the budget cuts there; no
// body of an ordinary scene has more deep pairs than the budget, so its pair list and its contacts
// are never changed.
#pragma once

#include <cstdint>

#include <cstddef>

#include "broadphase/deep_sieve.hpp"
#include "core/base/deep_overlap.hpp"
#include "elan/math.hpp"

namespace elan::detail {

struct WorldState;

// Deep pairs a dynamic body keeps in one step: more than the face neighbours of a box in a
// grid (6), so that a body packed in harder than any ordinary load presses it keeps its
// neighbours.
inline constexpr uint32_t kDeepPairBudget = 8;
// The sieve's runs give each body its budget of partners within its run (deep_sieve.hpp).
static_assert(DeepSieve::kRun == kDeepPairBudget + 1);

// Stage (before the broadphase): the bodies' inner balls (w.deep_balls), and the sieve the
// broadphase is to use, or null when the world has a pair filter.
DeepSieve* prepare_deep_sieve(WorldState& w);

// Stage (after the broadphase): the sieve's candidates merged into the sorted pair list.
void add_deep_candidates(WorldState& w);

// Stage (after the pair filters, before the collide stage): drops from w.pairs, in key order,
// each deep pair one of whose bodies already keeps kDeepPairBudget deep pairs, and likewise a
// crowd's near pairs against their own budget. Parallel over
// blocks of pairs for the test (a flag per pair, rule 1); the budget is counted serially in pair
// order, and only when some block found a deep pair (skipped outright when the sieve took none).
// Returns the number of pairs dropped.
std::size_t limit_deep_pairs(WorldState& w);

}  // namespace elan::detail
