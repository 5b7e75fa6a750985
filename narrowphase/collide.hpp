// SPDX-License-Identifier: MIT
// The collide stage: exact contact manifolds for the broadphase's pairs.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/base/body_store.hpp"
#include "core/base/contact.hpp"
#include "core/base/grow.hpp"
#include "core/base/packed_rotation.hpp"
#include "core/base/shape.hpp"
#include "core/base/step_scratch.hpp"
#include "narrowphase/composite.hpp"
#include "narrowphase/contact_store.hpp"
#include "narrowphase/polyhedron.hpp"
#include "narrowphase/separation.hpp"

namespace elan::detail {

// One pair. `xa`, `xb` are the principal-frame poses (centre of mass, principal axes) of the two
// shapes. Fills out.normal (unit, A to B), out.point_count (0..4) and each point's anchor_a
// (world offset from xa.position), separation and feature id; leaves the bodies, the impulses
// and the cache poses alone. Points farther apart than `speculative_distance` are
// not reported. Returns out.point_count > 0. Never produces NaN: degenerate input (touching,
// coincident centres, identical shapes at one pose) still gives a finite unit normal.
bool collide(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
             Real speculative_distance, Manifold& out);

// Whether collide() takes a closed form for this pair (two spheres or capsules, a sphere and a
// box), not SAT, GJK or a convex routine: the dispatch's own choice.
bool exact_test_is_closed_form(const Shape& a, const Shape& b);

// A's polyhedron from the last hull pair (or box against hull), for a caller that tests one body
// against several in a row: the SAT works in a frame centred on A, so A's vertices and planes
// depend on its shape and rotation alone, and the next pair with the same A (bit for bit) reuses
// them. collide_pairs' pairs are sorted by their first body, and in a pile most hull pairs follow
// one with the same A.
struct PolyhedronCache {
  const Shape* shape = nullptr;
  Quat rotation = Quat::Identity();
  Polyhedron polyhedron;
};
// As collide(), also telling what a rejection measured (`separation`, Unknown after a contact).
// `motion`: for a pair with a surface, the displacement over the step (collide_composite).
bool collide(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
             Real speculative_distance, Manifold& out, PolyhedronCache& cache,
             Separation& separation, const SurfaceMotion* motion = nullptr);

// Whether the SAT of the box or hull pair (a, b) would reject it on the axis of A's edge `edge_a`
// and B's edge `edge_b` (a Separation::Kind::EdgePair it reported before): the two edges still
// make a face of the Minkowski difference and its gap is above `speculative_distance`, computed
// as the SAT's edge query computes it (two boxes: as box_box.cpp's routine does). False when that
// is not so or the edges are not theirs.
bool edge_pair_separates(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                         int edge_a, int edge_b, Real speculative_distance, PolyhedronCache& cache);

struct CollideSettings {
  Real speculative_distance = Real(0.02);  // m: contacts kept this far apart, plus motion below
  Real dt = Real(1.0 / 60.0);              // s: for the motion allowance
  // Whether deep pairs (core/base/deep_overlap.hpp) take deep_contact() instead of the exact
  // test: set in a step where the deep-pair budget dropped pairs (core/world/deep_pairs.hpp), so
  // some bodies were spawned into a crowd of others. Only then: a pair of an ordinary scene can
  // be deep (a capsule landing hard across another, centres at 0.81 of the reach; a sphere
  // crushed into a box by the tumbler's paddle, 0.56), and keeps its exact test and its bits,
  // while no body of an ordinary scene has more deep pairs than the budget.
  bool deep_contacts = false;
};

// The stage: this step's manifolds for `pairs` (sorted keys) filed in `contacts`, which holds
// last step's. For each pair: key, body_a and body_b (the static or kinematic body, if any, as
// B; otherwise the lower index as A), and the manifold from collide() with speculative distance
// settings.speculative_distance plus the pair's approach over the step (|relative velocity of the
// centres| * dt, so fast bodies get speculative points before they reach each other). Each new
// point takes the impulses of last step's point of the same key and feature id (warm start). A
// pair whose relative pose moved less than 1 mm and 2 degrees since its points were computed
// reuses them, carried with the bodies (the body pair cache of Jolt), without running collide();
// the store keeps those poses for each manifold whose points may be reused (neither body round:
// see rolls()). On return the store holds the touching manifolds and the carried ones (see
// ContactStore::Block for `idle`), in key order, and the poses of those that may be reused.
//
// Separation cache: on return the store's two apart lists hold exactly the pairs of `pairs`
// without a touching manifold: the continuous stage's candidates. `separated` has those whose
// rejection measured a separation that lasts (Separation), with B's pose relative to A at the
// test; while B's points have moved, relative to A, by less than that gap minus the pair's
// speculative distance and a tolerance, the exact test is skipped: it would reject the pair
// again, so the result is the same bits with or without the cache. The apart keys are the
// others' keys alone (8 bytes, not 24): those whose exact test is a closed form (two round
// shapes, a sphere and a box), which costs about as much as checking the cache, and those whose
// separation an entry cannot hold.
//
// Parallel over fixed blocks of pairs, each a ContactStore::Block; nothing depends on the thread
// count. The merge's buffers are taken from `step_scratch` in its current phase and given back
// before returning (none: from a scratch of the store's own). On return contacts.began() and
// contacts.ended() hold the changes to the manifolds.
void collide_pairs(std::span<const uint64_t> pairs, const BodyStore& bodies,
                   std::span<const Shape> shapes, const CollideSettings& settings,
                   std::span<const uint8_t> idle, ContactStore& contacts,
                   StepScratch* step_scratch = nullptr);

// Time of impact by conservative advancement on the GJK distance: the earliest t in [0, 1] at
// which A moving linearly from xa0 to xa1 (rotation slerped) comes within `target` of B moving
// from xb0 to xb1. Returns 1 if they do not. Used by the continuous-collision stage.
Real time_of_impact(const Shape& a, const Transform& xa0, const Transform& xa1, const Shape& b,
                    const Transform& xb0, const Transform& xb1, Real target);

}  // namespace elan::detail
