// SPDX-License-Identifier: MIT
// The solver's constraint groups and their colourings: which contacts take part, in which group
// (a half's own or the cut's, solve.hpp), and each group's colours (coloring.hpp), laid out as
// the segments the bundles are built from.
#pragma once

#include <cstddef>
#include <cstdint>
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
ColorStats color_contacts(const BodyStore& bodies, std::span<ManifoldHead> contacts,
                          std::span<const ManifoldTail> tails, SolverState& st,
                          StepScratch& scratch, int participants);

}  // namespace elan::detail
