// SPDX-License-Identifier: MIT
// The contact of a deep pair (core/base/deep_overlap.hpp: two dynamic convex primitives whose
// centres are closer than kDeepFraction of the sum of their inner balls' radii), at a constant
// cost instead of the exact test; the collide stage takes it in a step where the deep-pair
// budget bit (CollideSettings::deep_contacts).
//
// Why: bodies spawned into each other (issue 42) overlap by most of their size, where EPA needs
// many iterations to expand its polytope from the origin out to the far side (500 cylinders at
// one point make 2,000 such pairs), and the exact minimum-translation
// answer is worth little: such a pair is pushed apart over several steps at a capped speed
// (solver/push_out_cap.hpp), and its normal changes as it goes. So a deep pair takes a bounded
// separating-axis test on a few fixed candidate axes instead (like the SAT, but only over the
// line of centres and each body's three principal axes): for a unit normal n from A to B the
// overlap along n is h_A(n) + h_B(-n) - n.d, with h the support function about each centre of
// mass and d = c_B - c_A, and the least overlap over the candidates is the depth. Every
// candidate separates the pair if moved by its overlap, so the answer is an upper bound of the
// penetration depth, exact when the true normal is a candidate (two boxes face on, two
// spheres). Cost: 7 candidates, two support evaluations each (a hull's is a scan of its
// vertices), nothing iterative.
//
// The manifold has one point with a fixed feature id (kDeepFeatureId), so the warm start
// matches it from step to step while the normal turns less than the match cone: on the line
// between the centres, across it, and in the middle of the overlap slab along n, so its normal
// impulse turns neither body when n is the line of centres.
//
// Coincident centres (bodies created at one point): the line of centres is taken from virtual
// offsets, each body displaced by a point of a low-discrepancy sequence indexed by its body
// index (Roberts' R3 sequence, in fixed point), as if it had been created a hair off the common
// point; the direction depends on the two indices alone (deterministic) and reverses when A and
// B are swapped. It is the normal of two round bodies (spheres), and for others it picks which
// way along the chosen axis (for equal boxes or cylinders, A's x axis) each pair parts.
#pragma once

#include <cstdint>

#include "core/base/contact.hpp"
#include "core/base/shape.hpp"
#include "elan/math.hpp"

namespace elan::detail {

inline constexpr uint32_t kDeepFeatureId = 0xDEE90001u;

// The virtual direction from body index_a to body index_b used when their centres coincide:
// unit, non-zero for any two distinct indices, and minus itself with the indices swapped.
Vec3 spawn_direction(uint32_t index_a, uint32_t index_b);

// The deep pair's contact (see above): writes out.normal (unit, A to B) and one point with
// anchor_a, separation (negative: minus the depth) and feature id kDeepFeatureId; returns true.
// `xa`, `xb`: the principal-frame poses; index_a, index_b: the bodies' dense indices (for the
// direction of coincident centres). Does not check that the pair is deep; any two convex shapes
// give a finite contact.
bool deep_contact(const Shape& a, const Transform& xa, uint32_t index_a, const Shape& b,
                  const Transform& xb, uint32_t index_b, Manifold& out);

}  // namespace elan::detail
