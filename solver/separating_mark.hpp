// SPDX-License-Identifier: MIT
// The separating mark (kSeparating, body_store.hpp): which bodies are being pushed out of a
// spawn overlap, step after step, until they are out. The push-out cap (push_out_cap.hpp) slows
// only marked bodies, and their rows are not taken into the direct solve (prepare_bundle).
//
// Why a mark kept from step to step: bodies spawned at one point first form cliques, where some
// body has more than kPushShare deep manifolds (color_contacts.hpp), and the cap was applied only
// in those steps. Once the cloud had spread, the boxes lay in chains overlapping by about 0.1 m,
// too shallow to be deep (deep_contact_separation(): 0.22 m at 46 Hz and 4 substeps), each link
// pushing at bias_rate * 0.1 = 1.4 m/s; one relax pass per substep does not take a chain's pushes
// back (Gauss-Seidel carries a velocity change a few links per pass), so the pushes added up and
// the two end boxes of a chain of 50 left at 26 m/s, then more. Marked, they are capped until
// they are out of every overlap.
//
// The rule, per awake dynamic body, each step:
//  - marked when the body has a deep manifold (deep_count > 0) in a step that has a clique
//    (st.most_deep > kPushShare: the start of a spawn overlap) or a marked body (the pairs the
//    deep-pair budget dropped come back, still deep, once the cloud has thinned);
//  - kept, or passed on, while one of its manifolds lies deeper than kSeparatingDepth and one of
//    the manifold's two bodies carried the mark at the step's start: the mark spreads through
//    the overlapping cloud (bodies whose deep pairs the budget dropped, deep_pairs.hpp, are
//    marked through their neighbours) and ends with the overlap;
//  - cleared otherwise, and on every body the solver does not simulate (asleep, frozen, static).
// The separations are those of the collide stage (the step's start).
//
// Ordinary scenes: no body of theirs has more than kPushShare deep manifolds (a body at rest has
// none; one that landed hard, one or two), so no body is ever marked there and this stage does
// nothing (WorldState::bodies_separating stays false): their bits do not change.
#pragma once

#include <span>

#include "core/base/body_store.hpp"
#include "core/base/contact.hpp"
#include "solver/solve.hpp"

namespace elan::detail {

// A manifold deeper than this keeps its bodies marked. Twice kDirectDepth's landing overshoot
// (direct_solve.hpp): a body landing at 3 m/s (the cap) presses in v / omega = 1 cm, a tower of
// 20 cubes at rest 4.5 cm in all but a few mm per contact (solve.hpp); resting contacts lie well
// above it, so the mark ends when the overlap does. It pushes at bias_rate * 0.01 = 0.14 m/s at
// most per link once unmarked.
inline constexpr Real kSeparatingDepth = Real(0.01);  // m

// Stage (after the solve, before the push-out cap; serial, packets and manifolds in order).
// Runs only when `marked` (some body carried the mark at the step's start) or the step has a
// clique. Reads: st.deep_count, st.most_deep, st.packet_of, st.masses, the manifolds' bodies and
// first separations, the bodies' flags. Writes: kSeparating in bodies.flags (every body),
// st.separating (scratch, per packet). Returns whether some body carries the mark after it.
bool mark_separating(BodyStore& bodies, std::span<const ManifoldHead> contacts, bool marked,
                     SolverState& st);

}  // namespace elan::detail
