// SPDX-License-Identifier: MIT
// The solver's contact bundles: each colour's constraints kLanes at a time (ContactBundle,
// contact_solver.hpp), their point rows, and their preparation for the step.
#pragma once

#include <span>

#include "core/base/body_store.hpp"
#include "core/base/contact.hpp"
#include "core/base/isa.hpp"
#include "core/base/step_scratch.hpp"
#include "solver/solve.hpp"

namespace elan::detail {

ELAN_ISA_BEGIN

// Stage: lay out the bundles. Each colour's constraints go kLanes at a time in colour order; an
// overflow's one per bundle (its constraints may share bodies, so they cannot be lanes of one
// bundle). Each bundle gets a point row for each point but the first of its first lane, which
// has the most points (color_contacts orders each segment so).
//
// Reads: st.segment_start, st.order, the contacts' point counts. Writes: st.bundle_start,
// st.row_start, st.lane_start. Serial. Scratch: takes st.bundles, st.rows and, when `bouncy`,
// st.restitution from `scratch`, sized and unset; prepare_contacts fills them, solve() reads
// them and release_bundles gives them back (run_step shows that lifetime).
void build_bundles(std::span<const ManifoldHead> contacts, bool bouncy, SolverState& st,
                   StepScratch& scratch);

// Stage: prepare the contact constraints (prepare_bundle) for the step.
//
// Reads: contacts and their tails (ManifoldHead::tail, set by color_contacts), the bodies' poses,
// st.packet_of, st.packets, st.masses, the bundle layout. Writes: st.bundles, st.rows,
// st.restitution. Parallel through st.executor: one block per group, which writes only its own
// bundles and their rows.
void prepare_contacts(const BodyStore& bodies, std::span<const ManifoldHead> contacts,
                      std::span<const ManifoldTail> tails, const SolveSettings& settings,
                      SolverState& st);

// Gives back what build_bundles took: the end of the bundles' life, after solve().
void release_bundles(SolverState& st);

ELAN_ISA_END

}  // namespace elan::detail
