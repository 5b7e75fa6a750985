// Stage 3, collide: exact contact manifolds for the broadphase's pairs.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/base/body_store.hpp"
#include "core/base/contact.hpp"
#include "core/base/shape.hpp"

namespace elan::detail {

// One pair. `xa`, `xb` are the principal-frame poses (centre of mass, principal axes) of the two
// shapes. Fills out.normal (unit, A to B), out.point_count (0..4) and each point's anchors
// (world offsets from xa.position / xb.position), separation and feature id; leaves out.key,
// body_a, body_b and the impulses alone. Points farther apart than `speculative_distance` are
// not reported. Returns out.point_count > 0. Never produces NaN: degenerate input (touching,
// coincident centres, identical shapes at one pose) still gives a finite unit normal.
bool collide(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
             Real speculative_distance, Manifold& out);

struct CollideSettings {
  Real speculative_distance = Real(0.02);  // m: contacts kept this far apart, plus motion below
  Real dt = Real(1.0 / 60.0);              // s: for the motion allowance
};

// The stage. For pair i of `pairs` (sorted keys), writes slot i of out_manifolds: key, body_a and
// body_b (the static or kinematic body, if any, as B; otherwise the lower index as A), and the
// manifold from collide() with speculative distance settings.speculative_distance plus the
// pair's approach over the step (|relative velocity of the centres| * dt, so fast bodies get
// speculative points before they reach each other). Then matches each new point with the
// previous step's manifold of the same key and feature id and copies its impulses (warm start),
// and joins the touching manifolds, with the carried ones, into `out_contacts` in key order. A pair
// whose relative pose moved less than 0.2 mm and 0.5 degrees since its points were computed reuses
// them, carried with the bodies (the body pair cache of Jolt), without running collide().
// `previous` is last step's out_contacts, sorted by key.
//
// Carrying: a manifold of `previous` whose two bodies are both flagged in `idle` (per body; the
// world flags static and sleeping bodies) and whose key has no touching manifold this step is
// kept as it is, so a sleeping island keeps its contacts and wakes warm-started (the broadphase
// does not report pairs of two idle bodies). An empty `idle` carries nothing.
//
// Parallel over fixed blocks of pairs. Block b owns the keys from its first pair's up to the
// next block's first pair's and writes its manifolds, new and carried, in key order to its own
// buffer in `scratch`; the join copies each buffer to its offset (a prefix sum of the blocks'
// counts), in parallel too. Nothing depends on the thread count, and no memory is held for pairs
// that do not touch. `previous` is read in full before `out_contacts` is written, so the two may
// share storage (the world passes its one contact list as both: no second list is kept).
struct CollideScratch {
  std::vector<std::vector<Manifold>> blocks;  // per block of pairs: its touching manifolds
  std::vector<std::size_t> offsets;           // per block: where its output starts
};
void collide_pairs(std::span<const uint64_t> pairs, const BodyStore& bodies,
                   std::span<const Shape> shapes, const CollideSettings& settings,
                   std::span<const Manifold> previous, std::span<const uint8_t> idle,
                   CollideScratch& scratch, std::vector<Manifold>& out_contacts);

// Time of impact by conservative advancement on the GJK distance: the earliest t in [0, 1] at
// which A moving linearly from xa0 to xa1 (rotation slerped) comes within `target` of B moving
// from xb0 to xb1. Returns 1 if they do not. Used by the continuous-collision stage.
Real time_of_impact(const Shape& a, const Transform& xa0, const Transform& xa1, const Shape& b,
                    const Transform& xb0, const Transform& xb1, Real target);

}  // namespace elan::detail
