// Stage 3, collide: exact contact manifolds for the broadphase's pairs.
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

// A's polyhedron from the last box or hull pair, for a caller that tests one body against
// several in a row: the SAT works in a frame centred on A, so A's vertices and planes depend on
// its shape and rotation alone, and the next pair with the same A (bit for bit) reuses them.
// collide_pairs' pairs are sorted by their first body, and on pile4k three in four hull pairs
// follow one with the same A.
struct PolyhedronCache {
  const Shape* shape = nullptr;
  Quat rotation = Quat::Identity();
  Polyhedron polyhedron;
};
// As collide(), also telling what a rejection measured (`separation`, Unknown after a contact).
bool collide(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
             Real speculative_distance, Manifold& out, PolyhedronCache& cache,
             Separation& separation);

// Whether the SAT of the box or hull pair (a, b) would reject it on the axis of A's edge `edge_a`
// and B's edge `edge_b` (a Separation::Kind::EdgePair it reported before): the two edges still
// make a face of the Minkowski difference and its gap is above `speculative_distance`, computed
// as the SAT's edge query computes it. False when that is not so or the edges are not theirs.
bool edge_pair_separates(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                         int edge_a, int edge_b, Real speculative_distance, PolyhedronCache& cache);

struct CollideSettings {
  Real speculative_distance = Real(0.02);  // m: contacts kept this far apart, plus motion below
  Real dt = Real(1.0 / 60.0);              // s: for the motion allowance
};

// A pair the exact test found apart, what the rejection measured, and B's pose relative to A at
// that test: the reference the motion since is measured from. 24 bytes (a pile keeps about three
// of these a body): the rotation is packed into six bytes (PackedRotation's kept components), the
// position into 16-bit steps of the pair's size (position_step), and the separation's kind and
// the rotation's left-out component take the gap's four lowest bits. Each code rounds so that
// closing() still over-estimates the motion: the gap comes back a little smaller, and the
// position's and rotation's errors are added to the motion.
struct SeparatedPair {
  uint64_t key = 0;
  uint32_t gap_bits = 0;     // Separation::gap as a float, the lowest four bits replaced by tags
  int16_t position[3] = {};  // B's centre of mass minus A's, in A's frame: steps of position_step
  uint8_t rotation[6] = {};  // A's frame to B's (A^-1 B), PackedRotation's kept components

  // The step of the position code, m: 2 (r_a + r_b) / 32767 for the shapes' bounding radii, so
  // that the centres of any pair whose boxes overlap, and then some, are within range.
  static Real position_step(const Shape& a, const Shape& b) {
    return 2 * (a.bounding_radius + b.bounding_radius) / 32767;
  }
  // The entry, or false (`out` untouched) where the codes cannot hold it: an unknown kind, a gap
  // that is not positive and finite, a centre out of the position code's range, an edge index
  // past int16.
  static bool make(uint64_t key, const Separation& separation, const Vec3& position,
                   const Quat& rotation, Real step, SeparatedPair& out);

  // An EdgePair entry (the gap's sign bit set, which no kept gap has) holds the two edges in
  // position[0] and [1] and nothing else (no gap: gap() is -0).
  Separation::Kind kind() const {
    return gap_bits >> 31 ? Separation::Kind::EdgePair : Separation::Kind(gap_bits & 3u);
  }
  int edge_a() const { return position[0]; }
  int edge_b() const { return position[1]; }
  // m: at most the measured gap.
  Real gap() const;
  Vec3 position_at(Real step) const {
    return step * Vec3(Real(position[0]), Real(position[1]), Real(position[2]));
  }
  Quat rotation_value() const { return PackedRotation::unpack(rotation, int(gap_bits >> 2 & 3u)); }
  // Marks the entry as ended (kind Unknown).
  void end() { gap_bits = 0; }
};
static_assert(sizeof(Real) != 4 || sizeof(SeparatedPair) == 24, "SeparatedPair: 24 bytes in float");

// The pairs found apart, sorted by key, in two lists (see collide_pairs): those kept with their
// separation, and the others by key alone.
struct ApartPairs {
  std::vector<SeparatedPair> separated;
  std::vector<uint64_t> keys;

  void clear() {
    separated.clear();
    keys.clear();
  }
};

// Scratch of one list updated in place by collide_pairs (see there).
template <class T>
struct ListUpdate {
  struct Run {
    uint32_t thread = 0;
    std::size_t first = 0, count = 0;
  };
  // Per thread: entries of new keys, block by block. Each has room for a quarter more than the
  // largest held the step before.
  std::vector<ScratchVector<T>> added;
  std::size_t room = 0;
  // The rest, per block, are taken from the step's scratch for the stage too.
  ScratchVector<Run> added_run;        // per block: its new keys' run, in key order
  ScratchVector<std::size_t> start;    // per block + 1: its range of the list on entry
  ScratchVector<std::size_t> live;     // per block: entries of its range that stay
  ScratchVector<std::size_t> at;       // per block + 1: its range of the list on return
  ScratchVector<std::size_t> waiting;  // the join: blocks waiting for their right neighbour
  // The join: one block's entries on their way, with room for the largest block that moves.
  ScratchVector<T> bounce;

  std::size_t heap_bytes() const;
};

struct CollideScratch {
  ListUpdate<ManifoldHead> contacts;
  ListUpdate<ManifoldTail> tails;
  ListUpdate<SeparatedPair> separated;
  ListUpdate<uint64_t> apart_keys;
  ListUpdate<PairCache> cached;
  // Out: what changed in the contact list, each in key order. `ended`: the manifolds that were
  // in it and are not any more; `began`: the keys new to it. Every manifold the list holds has
  // points, so these are the pairs that stopped and started touching (the contact events).
  std::vector<ContactRecord> ended;
  std::vector<uint64_t> began;
  SpikeTrim ended_trim, began_trim;  // a new pile begins every pair at once
  std::unique_ptr<StepScratch> own;  // for the new-key buffers when the caller gives no scratch
};

// The stage. `contacts` holds last step's manifolds, sorted by key, and receives this step's, each
// as its head; `tails` holds, sorted by key too, the points past the first of those with more. For
// each pair of `pairs` (sorted keys): key, body_a and body_b (the static or kinematic body, if
// any, as B; otherwise the lower index as A), and the manifold from collide() with speculative
// distance settings.speculative_distance plus the pair's approach over the step (|relative
// velocity of the centres| * dt, so fast bodies get speculative points before they reach each
// other). Each new point takes the impulses of last step's point of the same key and feature id
// (warm start). A pair whose relative pose moved less than 1 mm and 2 degrees since its
// points were computed reuses them, carried with the bodies (the body pair cache of Jolt),
// without running collide(); `cached` holds those poses, sorted by key, for each manifold whose
// points may be reused (neither body round: see rolls()). On return `contacts` holds the touching
// manifolds and the carried ones, in key order, and `cached` the poses of those that may be
// reused.
//
// Separation cache: the pairs found apart are kept in `apart`, in one of its two lists. On return
// the two hold exactly the pairs of `pairs` without a touching manifold: the continuous stage's
// candidates. `apart.separated` has those whose rejection measured a separation that lasts
// (Separation), with B's pose relative to A at the test; while B's points have moved, relative to
// A, by less than that gap minus the pair's speculative distance and a tolerance, the exact test
// is skipped: it would reject the pair again, so the result is the same bits with or without the
// cache. `apart.keys` has the others' keys alone (8 bytes, not 24): those whose exact test is a
// closed form (two round shapes, a sphere and a box), which costs about as much as checking the
// cache, and those whose separation an entry cannot hold. Both belong to one set of bodies and
// shapes: clear them when bodies are removed or renumbered.
//
// Carrying: a manifold whose two bodies are both flagged in `idle` (per body; the world flags
// static and sleeping bodies) and whose key has no touching manifold this step is kept as it is,
// with its tail and poses, so a sleeping island keeps its contacts and wakes warm-started (the
// broadphase does not report pairs of two idle bodies). An empty `idle` carries nothing.
//
// The lists are updated in place, so no second copy of any is ever held (Box2D v3 and Jolt
// keep their contacts in place too). Parallel over fixed blocks of pairs: block b owns the keys
// from its first pair's up to the next block's first pair's. It rewrites the entries of its key
// range where they are, marks those that end, and collects entries of keys new to a list in its
// thread's buffer; a serial join then closes the gaps and merges the new ones in. Nothing depends
// on the thread count. The threads' buffers and the join's are taken from `step_scratch` in its
// current phase and given back before returning (none: from a scratch of `scratch`'s own).
//
// On return scratch.ended and scratch.began hold the contact list's changes (see CollideScratch).
void collide_pairs(std::span<const uint64_t> pairs, const BodyStore& bodies,
                   std::span<const Shape> shapes, const CollideSettings& settings,
                   std::span<const uint8_t> idle, CollideScratch& scratch,
                   std::vector<ManifoldHead>& contacts, std::vector<ManifoldTail>& tails,
                   ApartPairs& apart, std::vector<PairCache>& cached,
                   StepScratch* step_scratch = nullptr);

// Time of impact by conservative advancement on the GJK distance: the earliest t in [0, 1] at
// which A moving linearly from xa0 to xa1 (rotation slerped) comes within `target` of B moving
// from xb0 to xb1. Returns 1 if they do not. Used by the continuous-collision stage.
Real time_of_impact(const Shape& a, const Transform& xa0, const Transform& xa1, const Shape& b,
                    const Transform& xb0, const Transform& xb1, Real target);

}  // namespace elan::detail
