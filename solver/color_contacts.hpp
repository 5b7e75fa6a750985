// SPDX-License-Identifier: MIT
// The solver's constraint groups and their colourings: which contacts take part, in which group
// (a half's own or the cut's, solve.hpp), and each group's colours (coloring.hpp), laid out as
// the segments the bundles are built from.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include "core/base/body_store.hpp"
#include "core/base/contact.hpp"
#include "core/base/step_scratch.hpp"
#include "solver/solve.hpp"

namespace elan::detail {

struct ColorStats {
  std::size_t points = 0;    // contact points of all manifolds, counted in passing
  std::size_t colors = 0;    // most colours used by one group
  std::size_t overflow = 0;  // manifolds in the groups' overflows
};

// Stage: colour the contacts. The candidates are the touching contacts with at least one
// simulated dynamic body, group by group (half 0's, half 1's, then the cut's), in key order
// within each; a half's colouring sees its packets from the half's first, so its bitsets cover
// that half only. Each group is coloured apart (build_colors), then each of its segments (its
// colours, then its overflow) is ordered by point count, most first.
//
// Reads: contacts (bodies, point counts), body motion types, st.packet_of, st.half_start.
// Writes: each head's ManifoldHead::tail (the index of its tail in `tails`, in the same pass that
// groups the contacts), st.group_start, st.order (contact indices, segment by segment),
// st.segment_start. Parallel through st.executor: one block per group. Scratch: the candidates,
// the colourings' inputs and arrays, taken from `scratch` and given back, the last taken first,
// so the bundles laid out next start where they did.
//
// The push-out share, counted in the same pass: st.deep_count[p] gets the number of packet p's
// manifolds (dynamic sides only) whose first point lies deeper than `deep_separation`
// (deep_contact_separation(): where the push-out cap binds), st.most_deep the most of any.
// A manifold whose bodies have n > kPushShare of them (the larger count of the two) then pushes
// out at the cap times kPushShare / n (prepare_bundle). Why: the cap bounds the relative speed
// of one pair, and bodies spawned at one point, each overlapping all the others, were pushed
// apart through chains of pairs, each link adding the cap (100 boxes flew apart at 67 m/s).
// Shared among a body's n deep manifolds, a chain across n + 1 bodies adds up to kPushShare
// caps at most; the solver's passes do not reach that bound (the body is pushed from all
// sides), and kPushShare = 4 lets 100 boxes spawned at one point part at about the cap instead
// of a tenth of it (which kept them overlapping, at all-pairs cost, for seconds). A body of an
// ordinary scene has no deep manifold, or one where it landed hard, and keeps the whole cap.
ColorStats color_contacts(const BodyStore& bodies, std::span<ManifoldHead> contacts,
                          std::span<const ManifoldTail> tails, SolverState& st,
                          StepScratch& scratch, int participants,
                          Real deep_separation = -std::numeric_limits<Real>::infinity());

}  // namespace elan::detail
