// SPDX-License-Identifier: MIT
// The find-pairs stage: which bodies' boxes overlap. Every method returns the same canonical list:
// keys make_pair_key(a, b) (a < b), sorted ascending, unique; with a deep sieve in the input, the
// same list less its deep pairs, and the same candidate sets in the sieve.
//
// Reads: bounds, per-body kind, filter bits, plane flags. Writes: the pair list.
// Parallel over tiles / sweep chunks; per-block outputs joined in block order, then sorted.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "broadphase/bounds.hpp"
#include "broadphase/broad_kind.hpp"
#include "broadphase/deep_sieve.hpp"
#include "broadphase/dynamic_tree.hpp"
#include "core/base/body_traits.hpp"
#include "core/base/grow.hpp"
#include "core/base/parallel.hpp"
#include "core/base/step_scratch.hpp"
#include "elan/defs.hpp"

namespace elan::detail {

// Static-static, kinematic-static, kinematic-kinematic, sleeping-sleeping and sleeping-static
// pairs are never reported. Awake bodies pair with anything; kinematic bodies also with sleeping
// ones (so a moving kinematic body wakes what it touches).
inline bool should_pair(BroadKind a, BroadKind b) {
  if (a == BroadKind::Awake || b == BroadKind::Awake) return true;
  return (a == BroadKind::Kinematic && b == BroadKind::Sleeping) ||
         (a == BroadKind::Sleeping && b == BroadKind::Kinematic);
}

struct BroadphaseInput {
  const BoundsColumns* bounds = nullptr;
  std::span<const uint8_t> kind;            // BroadKind per body
  std::span<const uint32_t> traits;         // per body: its entry of `trait_table`
  std::span<const BodyTraits> trait_table;  // the collision filters (BodyTraits::category, mask)
  std::span<const uint8_t> is_plane;        // 1 for plane shapes (infinite boxes)
  // The instruction set of the sweep's kernel (broadphase/sweep_kernel.hpp); every path gives the
  // same pairs. Best: core/base/simd_path.hpp's process_simd_path().
  SimdPath simd = SimdPath::Best;
  // When set, every pair found goes through it (deep_sieve.hpp): the deep ones are kept out of
  // the list, in its candidate sets, which the caller collects. Null: the full list.
  DeepSieve* deep = nullptr;
};

inline bool filter_pass(const BroadphaseInput& in, uint32_t a, uint32_t b) {
  const BodyTraits &ta = in.trait_table[in.traits[a]], &tb = in.trait_table[in.traits[b]];
  return (ta.category & tb.mask) != 0 && (tb.category & ta.mask) != 0;
}

// Serial O(n^2) reference: the test oracle.
void find_pairs_brute_force(const BroadphaseInput& in, std::vector<uint64_t>& out_pairs);

// All n(n-1)/2 pairs in parallel TBB tasks over tiles of the pair space. Keeps its scratch.
// The pair lists below are a std::vector or a ScratchVector of keys (the world's lives in the
// step's scratch): `Pairs`.
class AllPairs {
 public:
  template <class Pairs>
  void find_pairs(const BroadphaseInput& in, Pairs& out_pairs);
  std::size_t heap_bytes() const;  // scratch kept between steps (the memory report)

 private:
  std::vector<ScratchVector<uint64_t>> block_pairs_;  // one per tile
  KeySortScratch pair_sort_;
};

// Sweep-and-prune on the axis of largest spread, keeping last step's order so the re-sort is
// of nearly sorted input; the sweep is split into parallel chunks. The sorted list is dealt, in
// order, into strips along the axis of second spread, each swept alone: in a dense pile a single
// sweep meets every box of a whole slab, a strip only its neighbours.
class SweepAndPrune {
 public:
  // Sentinels after each strip's entries: the sweep tests candidates this many at a time.
  static constexpr std::size_t kStripPad = 8;

  // The buffers of one update (the boxes dealt into strips, the chunks' pairs, the sorts' copies)
  // are taken from `scratch` in its current phase and given back before returning. The two-argument
  // form uses a scratch of the sweep's own.
  template <class Pairs>
  void find_pairs(const BroadphaseInput& in, Pairs& out_pairs, StepScratch& scratch);
  template <class Pairs>
  void find_pairs(const BroadphaseInput& in, Pairs& out_pairs) {
    if (!own_scratch_) own_scratch_ = std::make_unique<StepScratch>();
    own_scratch_->begin_phase();
    find_pairs(in, out_pairs, *own_scratch_);
  }
  // Sorted boxes and the sort's scratch (the memory report); the own scratch, if used, too.
  std::size_t heap_bytes() const;

 private:
  bool choose_axis(const BroadphaseInput& in);
  void sort_full(const BroadphaseInput& in, StepScratch& scratch);
  bool sort_incremental();
  // Deals the sorted boxes into strips; takes the sweep's pair blocks, then the entries.
  void deal_strips(const BroadphaseInput& in, StepScratch& scratch);
  void take_pair_blocks(const BroadphaseInput& in, std::size_t entries, StepScratch& scratch);
  void release_entries();         // once swept
  void release_update_buffers();  // the rest, once the pairs are sorted
  // Monotonic in v, which the sweep's dedup rule relies on; NaN and v <= strip_lo_ give 0.
  uint32_t strip_of(Real v) const {
    if (!(v > strip_lo_)) return 0;
    const Real t = (v - strip_lo_) / strip_width_;
    return t < Real(strip_count_) ? uint32_t(t) : strip_count_ - 1;
  }

  std::vector<uint32_t> order_;   // body indices sorted by min on the sweep axis
  std::vector<Real> sorted_min_;  // min on the axis, in order_ (planes, NaN: +inf)
  // The rest of each box, in order_: max on the axis and the two other axes. These, the entries
  // and sorted_strips_ are rebuilt by every update and held only during it (scratch).
  ScratchVector<Real> sorted_max_, sorted_lo1_, sorted_hi1_, sorted_lo2_, sorted_hi2_;
  int axis_ = 0;
  int strip_axis_ = 1;  // 1 or 2: which of the other axes (lo1/lo2) the strips cut
  Real strip_lo_ = 0, strip_width_ = 1;
  uint32_t strip_count_ = 1;
  // Entries: one per (box, strip it overlaps), strip by strip, each strip in sweep order and
  // followed by kStripPad sentinels (min +inf, the rest NaN) so the sweep reads whole chunks.
  ScratchVector<Real> entry_min_, entry_max_, entry_lo1_, entry_hi1_, entry_lo2_, entry_hi2_;
  ScratchVector<uint32_t> entry_body_;
  ScratchVector<uint32_t> entry_first_;  // strip of the box's low end on the strip axis
  // The box's kind, filter category and mask, so the accept test runs in the sweep's lanes.
  ScratchVector<uint8_t> entry_kind_;
  ScratchVector<uint32_t> entry_category_, entry_mask_;
  // With a deep sieve: each body's closed level as a shift (closed_runs.hpp; body_order_ its
  // scratch); when some body is closed, the entries' inner balls, runs and shifts, for the kernel
  // to pass shut-out pairs by.
  ScratchVector<uint32_t> body_order_, body_shift_;
  std::size_t closed_count_ = 0;
  ScratchVector<Real> entry_ball_x_, entry_ball_y_, entry_ball_z_, entry_ball_r_;
  ScratchVector<uint32_t> entry_run_, entry_shift_;
  std::vector<uint32_t> strip_begin_;      // per strip: first entry; strip_begin_[s + 1] - pad: end
  ScratchVector<uint32_t> sorted_strips_;  // per sorted box: first and last strip (first > last:
                                           // no entry)
  std::vector<uint32_t> deal_counts_;      // per deal block and strip: entries, then offsets
  std::vector<double> axis_partials_;      // per block: statistics of box centres and sizes
  std::vector<uint32_t> planes_;
  std::vector<ScratchVector<uint64_t>> block_pairs_;  // sweep chunks, then plane blocks (scratch)
  std::vector<uint32_t> block_room_;  // per block: pairs last update, its buffer's next room
  std::size_t sweep_blocks_ = 0, plane_blocks_ = 0;  // this update's (take_pair_blocks)
  std::unique_ptr<StepScratch> own_scratch_;         // of the two-argument form
  std::vector<uint64_t> sort_keys_;
  std::vector<double> range_partials_;  // per block: smallest and largest finite sweep key
  KeySortScratch key_sort_, pair_sort_;
  uint32_t skip_incremental_ = 0;  // updates left before the insertion sort is tried again
};

// A dynamic tree over the boxes (dynamic_tree.hpp), kept from update to update: each body's
// leaf is the box grown by kFatMargin and is re-inserted only when the body's box leaves it, so
// a mostly static world costs a containment test per body. Each awake or kinematic body (the only
// ones that pair: should_pair) then queries the tree with its own box in parallel blocks, and
// tests the planes and other unbounded boxes, which are kept out of the tree. The candidates are
// tested on the exact boxes with the shared rule (pair_test.hpp), so the list is the canonical one.
class TreePairs {
 public:
  // m: how far a box may move within its leaf before the leaf is rebuilt. perf: Box2D's 0.1 m;
  // a pile's bodies move millimetres a step, a falling body a few centimetres.
  static constexpr Real kFatMargin = Real(0.1);
  template <class Pairs>
  void find_pairs(const BroadphaseInput& in, Pairs& out_pairs);
  std::size_t heap_bytes() const;
  const DynamicTree& tree() const { return tree_; }

 private:
  void refit(const BroadphaseInput& in);
  DynamicTree tree_;
  std::vector<uint32_t> outside_;  // unbounded boxes (planes), by index
  std::vector<ScratchVector<uint64_t>> block_pairs_;
  KeySortScratch pair_sort_;
};

}  // namespace elan::detail
