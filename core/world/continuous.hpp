// SPDX-License-Identifier: MIT
// The continuous collision stage: a body that moved more than half its thinnest extent during the
// step is put back at its first time of impact, along the step's motion, with a static or
// kinematic body or a dynamic body that moved slowly (Box2D v3's b2SolveContinuous). Speculative
// contacts stop most fast bodies; this catches a path that the solve bent into a body which the
// contacts placed at the step's start did not cover. Its velocity is kept: next step's contact
// resolves the impact.
//
// Pairs that have a manifold are not candidates: their speculative contact was in the solve.
//
// The broadphase swept each body's box along its velocity at the step's start only, so a path
// the solve bent (a ball deflected down by a box) can cross a static body that was never a
// pair: a 1e4 m/s ball ended inside the floor. So each fast body's box from its start pose to
// its end pose is also looked up in the query tree (which holds every static body's box), and
// every static body found there that was no pair of it this step is a candidate too.
//
// Reads: the pairs the collide stage found apart (its two lists of them) and its manifolds' keys,
// the query tree, body columns (poses at the step's start), shapes, packets (the pose change of
// the step). Writes: dp and dq of fast
// packets. Parallel over blocks of pairs, each listing the impacts it found; a body's earliest
// time is a minimum, which does not depend on the order its pairs are visited in. The static
// bodies off the pair list are looked up serially, fast body by fast body, into the same
// minimum.
#pragma once

#include <cstdint>
#include <span>

#include "broadphase/dynamic_tree.hpp"
#include "core/base/body_store.hpp"
#include "core/base/shape.hpp"
#include "narrowphase/collide.hpp"
#include "solver/solve.hpp"

namespace elan::detail {

// Time of impact stops this far from touching (Box2D's linear slop), m.
inline constexpr Real kContinuousTarget = Real(0.005);
// m: under the broadphase's box margin (kBoundsMargin, 1.25 cm), so the path stays in the box.
inline constexpr Real kPathSlack = Real(0.01);

// Returns the number of bodies moved back.
// The candidates are the pairs the collide stage found apart this step (`separated` and
// `apart_keys`, see collide_pairs): a pair with a manifold (`touching`) had its speculative
// contact in the solve. `statics`: the query tree (query_tree.hpp), whose static leaves are
// current during a step. perf: a fast body whose displacement is within kPathSlack of its start
// velocity times `dt` took the path its broadphase box was swept along, so every static body
// along it was a pair already: it is not looked up (a pile's falling bodies).
std::size_t solve_continuous(const BodyStore& bodies, std::span<const Shape> shapes,
                             std::span<const SeparatedPair> separated,
                             std::span<const uint64_t> apart_keys,
                             std::span<const ManifoldHead> touching, const DynamicTree& statics,
                             SolverState& state, Real dt = 0);

}  // namespace elan::detail
