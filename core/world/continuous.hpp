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
// Reads: the pairs the collide stage found apart (its two lists of them), body columns (poses at
// the step's start), shapes, packets (the pose change of the step). Writes: dp and dq of fast
// packets. Parallel over blocks of pairs, each listing the impacts it found; a body's earliest
// time is a minimum, which does not depend on the order its pairs are visited in.
#pragma once

#include <cstdint>
#include <span>

#include "core/base/body_store.hpp"
#include "core/base/shape.hpp"
#include "narrowphase/collide.hpp"
#include "solver/solve.hpp"

namespace elan::detail {

// Time of impact stops this far from touching (Box2D's linear slop), m.
inline constexpr Real kContinuousTarget = Real(0.005);

// Returns the number of bodies moved back.
// The candidates are the pairs the collide stage found apart this step (`separated` and
// `apart_keys`, see collide_pairs): a pair with a manifold had its speculative contact in the
// solve.
std::size_t solve_continuous(const BodyStore& bodies, std::span<const Shape> shapes,
                             std::span<const SeparatedPair> separated,
                             std::span<const uint64_t> apart_keys, SolverState& state);

}  // namespace elan::detail
