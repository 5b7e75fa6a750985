// SPDX-License-Identifier: MIT
// The tree broadphase: a dynamic tree of fattened boxes refitted serially in index order, then
// one box query per moving body in parallel blocks.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "broadphase/find_pairs.hpp"
#include "broadphase/pair_test.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"

namespace elan::detail {

namespace {

// determinism: a fixed grain (rule 2); each block's pairs are its own buffer (rule 1).
constexpr std::size_t kTreeGrain = 128;
constexpr std::size_t kSieveRun = 512;

TreeBox box_of(const BoundsColumns& b, std::size_t i) {
  return {Vec3(b.min_x[i], b.min_y[i], b.min_z[i]), Vec3(b.max_x[i], b.max_y[i], b.max_z[i])};
}

bool queries(BroadKind k) {
  return k == BroadKind::Awake || k == BroadKind::Kinematic;
}

}  // namespace

// determinism: serial, in index order; the tree's shape changes nothing of the pair list.
void TreePairs::refit(const BroadphaseInput& in) {
  const BoundsColumns& b = *in.bounds;
  const std::size_t n = b.size();
  for (std::size_t i = n; i < tree_.item_count(); ++i) tree_.remove(uint32_t(i));
  tree_.resize_items(n);
  outside_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const TreeBox box = box_of(b, i);
    if (box.lo.allFinite() && box.hi.allFinite() && !in.is_plane[i]) {
      tree_.update(uint32_t(i), box, kFatMargin);
      continue;
    }
    // Planes and other unbounded boxes are kept apart (an infinite leaf would make every
    // ancestor infinite); a NaN box (a quarantined body) overlaps nothing and is dropped.
    tree_.remove(uint32_t(i));
    if (!box.lo.hasNaN() && !box.hi.hasNaN()) outside_.push_back(uint32_t(i));
  }
}

template <class Pairs>
void TreePairs::find_pairs(const BroadphaseInput& in, Pairs& out_pairs) {
  refit(in);
  const BoundsColumns& b = *in.bounds;
  const std::size_t n = b.size();
  const std::size_t blocks = block_count(n, kTreeGrain);
  // perf: buffers only grow, so after warm-up an update allocates nothing.
  if (block_pairs_.size() < blocks) block_pairs_.resize(blocks);
  for (std::size_t k = blocks; k < block_pairs_.size(); ++k) block_pairs_[k].clear();
  for_blocks(n, kTreeGrain, [&](std::size_t begin, std::size_t end, std::size_t block) {
    ScratchVector<uint64_t>& out = block_pairs_[block];
    out.clear();
    std::size_t sieved = 0;  // out[0, sieved) went through the sieve
    const auto sieve = [&] {
      out.resize(sieved + in.deep->sieve(out.data() + sieved, out.size() - sieved));
      sieved = out.size();
    };
    const auto emit = [&](uint32_t i, uint32_t j) {
      if (boxes_overlap(b, i, j) && accept_pair(in, i, j)) {
        out.push_back(i < j ? make_pair_key(i, j) : make_pair_key(j, i));
        // The sieve takes the deep pairs every kSieveRun found: a crowd's are never all stored.
        if (in.deep != nullptr && out.size() - sieved >= kSieveRun) sieve();
      }
    };
    for (std::size_t ii = begin; ii < end; ++ii) {
      const uint32_t i = uint32_t(ii);
      if (!queries(BroadKind(in.kind[i]))) continue;
      if (!tree_.contains(i)) {
        // An unbounded box that moves: against every body (rare: no scene makes one). A pair
        // reported from both sides is removed by the final dedup.
        const TreeBox box = box_of(b, i);
        if (box.lo.hasNaN() || box.hi.hasNaN()) continue;
        for (uint32_t j = 0; j < uint32_t(n); ++j) {
          if (j != i) emit(i, j);
        }
        continue;
      }
      tree_.query(box_of(b, i), [&](uint32_t j) {
        // A pair of two querying bodies is reported by the lower index alone.
        if (j != i && !(j < i && queries(BroadKind(in.kind[j])))) emit(i, j);
        return true;
      });
      for (const uint32_t p : outside_) emit(i, p);
    }
    if (in.deep != nullptr) sieve();
  });
  const uint64_t max_key = n < 2 ? 0 : make_pair_key(uint32_t(n - 2), uint32_t(n - 1));
  sort_key_blocks(block_pairs_, max_key, out_pairs, pair_sort_);
  out_pairs.erase(std::unique(out_pairs.begin(), out_pairs.end()), out_pairs.end());
}
template void TreePairs::find_pairs(const BroadphaseInput&, std::vector<uint64_t>&);
template void TreePairs::find_pairs(const BroadphaseInput&, ScratchVector<uint64_t>&);

std::size_t TreePairs::heap_bytes() const {
  return tree_.heap_bytes() + detail::heap_bytes(outside_) + detail::heap_bytes(block_pairs_) +
         detail::heap_bytes(pair_sort_);
}

}  // namespace elan::detail
