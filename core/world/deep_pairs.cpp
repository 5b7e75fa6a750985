// SPDX-License-Identifier: MIT
// limit_deep_pairs(): the deep-pair budget (see deep_pairs.hpp).
#include "core/world/deep_pairs.hpp"

#include <algorithm>

#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"
#include "core/world/world_state.hpp"

namespace elan::detail {

namespace {

constexpr std::size_t kDeepGrain = 2048;

// The inner ball's radius of a dynamic body (deep_overlap.hpp), m; 0 for a static or kinematic
// one, which is never deep.
Real deep_radius(const WorldState& w, uint32_t i) {
  if (!w.bodies.is_dynamic(i)) return 0;
  return inner_ball_radius(w.shapes[w.bodies.shape[i]]);
}

}  // namespace

std::size_t limit_deep_pairs(WorldState& w) {
  const std::size_t n = w.pairs.size();
  const std::size_t blocks = block_count(n, kDeepGrain);
  std::vector<uint8_t>& deep = w.deep_pair;
  std::vector<uint8_t>& block_deep = w.deep_block;
  deep.resize(n);
  block_deep.assign(blocks, 0);
  // determinism: a flag per pair and one per block, each written by its block (rule 1).
  for_blocks(n, kDeepGrain, [&](std::size_t begin, std::size_t end, std::size_t block) {
    uint8_t any = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const uint64_t key = w.pairs[k];
      const uint32_t a = pair_first(key), b = pair_second(key);
      uint8_t is_deep = 0;
      const Real ra = deep_radius(w, a);
      if (ra > 0) {
        const Real rb = deep_radius(w, b);
        is_deep = rb > 0 && inner_balls_deep(w.bodies.position(a), ra, w.bodies.position(b), rb);
      }
      deep[k] = is_deep;
      any |= is_deep;
    }
    block_deep[block] = any;
  });
  if (std::find(block_deep.begin(), block_deep.end(), uint8_t{1}) == block_deep.end()) return 0;
  // The budget, in pair order: the pair list is sorted, so which deep pairs a body keeps does
  // not depend on how the pairs were found.
  std::vector<uint32_t>& kept_deep = w.deep_kept;
  kept_deep.assign(w.bodies.size(), 0);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const uint64_t key = w.pairs[k];
    if (deep[k]) {
      const uint32_t a = pair_first(key), b = pair_second(key);
      if (kept_deep[a] >= kDeepPairBudget || kept_deep[b] >= kDeepPairBudget) continue;
      ++kept_deep[a];
      ++kept_deep[b];
    }
    w.pairs[kept++] = key;
  }
  const std::size_t dropped = n - kept;
  w.pairs.resize(kept);
  return dropped;
}

}  // namespace elan::detail
