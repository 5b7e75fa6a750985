// SPDX-License-Identifier: MIT
// limit_deep_pairs(): the deep-pair budget (see deep_pairs.hpp).
#include "core/world/deep_pairs.hpp"

#include <algorithm>
#include <span>

#include "core/base/grow.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"
#include "core/world/world_state.hpp"

namespace elan::detail {

namespace {

constexpr std::size_t kDeepGrain = 2048;
constexpr std::size_t kBallGrain = 4096;

// The inner ball's radius of a dynamic body (deep_overlap.hpp), m; 0 for a static or kinematic
// one or a sensor, which is never deep (sensors report overlaps).
Real deep_radius(const WorldState& w, uint32_t i) {
  if (!w.bodies.is_dynamic(i) || (w.bodies.traits_of(i).flags & kTraitSensor) != 0) return 0;
  return inner_ball_radius(w.shapes[w.bodies.shape[i]]);
}

}  // namespace

DeepSieve* prepare_deep_sieve(WorldState& w) {
  const std::size_t n = w.bodies.size();
  grow_to(w.deep_balls, n);
  // determinism: indexed writes (rule 1).
  for_blocks(n, kBallGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      const Vec3 p = w.bodies.position(i);
      w.deep_balls[i] = {p.x(), p.y(), p.z(), deep_radius(w, uint32_t(i)), 0};
    }
  });
  // The runs (deep_sieve.hpp): serial, a count and a division a body.
  uint32_t ordinal = 0;
  for (DeepBall& b : w.deep_balls) {
    b.run = ordinal / DeepSieve::kRun;
    ordinal += b.r > 0 ? 1 : 0;
  }
  // A user's pair filter runs after the broadphase and must see every pair.
  w.deep_sieved = !w.api.pair_filter;
  w.deep_taken = 0;
  w.deep_crowd = false;
  if (!w.deep_sieved) return nullptr;
  w.deep_sieve.begin(w.deep_balls);
  return &w.deep_sieve;
}

void add_deep_candidates(WorldState& w) {
  if (!w.deep_sieved) return;
  std::vector<uint64_t>& deep = w.deep_candidates;
  deep.clear();
  // As the sieve's sets (deep_sieve.cpp): reserved once, not grown at each new high.
  const std::size_t reserved =
      DeepSieve::kCandidates * std::min<std::size_t>(w.bodies.size(), 1024);
  if (deep.capacity() < reserved) deep.reserve(reserved);
  w.deep_taken = w.deep_sieve.collect(deep);
  const std::span<const uint8_t> crowded = w.deep_sieve.crowded();
  w.deep_crowd =
      w.deep_taken > 0 && std::find(crowded.begin(), crowded.end(), uint8_t{1}) != crowded.end();
  if (deep.empty()) return;
  std::sort(deep.begin(), deep.end());
  // Both sorted and disjoint (a pair is deep or not): one merge from the back, in place.
  std::size_t i = w.pairs.size(), j = deep.size(), k = i + j;
  w.pairs.resize(k);
  while (j > 0) {
    if (i > 0 && w.pairs[i - 1] > deep[j - 1]) {
      w.pairs[--k] = w.pairs[--i];
    } else {
      w.pairs[--k] = deep[--j];
    }
  }
}

std::size_t limit_deep_pairs(WorldState& w) {
  // perf: an ordinary scene's pairs went through the sieve, which found none deep.
  if (w.deep_sieved && w.deep_taken == 0) return 0;
  const std::size_t n = w.pairs.size();
  const std::size_t blocks = block_count(n, kDeepGrain);
  std::vector<uint8_t>& deep = w.deep_pair;
  std::vector<uint8_t>& block_deep = w.deep_block;
  grow_to(deep, n);
  grow_fill(block_deep, blocks, uint8_t{0});
  const std::span<const uint8_t> crowd = w.deep_sieve.crowded();
  const bool crowded = w.deep_sieved && crowd.size() == w.bodies.size();
  // determinism: a flag per pair and one per block, each written by its block (rule 1).
  for_blocks(n, kDeepGrain, [&](std::size_t begin, std::size_t end, std::size_t block) {
    uint8_t any = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const uint64_t key = w.pairs[k];
      const uint32_t a = pair_first(key), b = pair_second(key);
      const DeepBall &ba = w.deep_balls[a], &bb = w.deep_balls[b];
      uint8_t is_deep = deep_balls_inline(ba, bb) ? 1 : 0;
      // A crowd's near pair: not deep, but a body of it is in a crowd (the sieve's crowded()).
      if (!is_deep && crowded && ba.r > 0 && bb.r > 0 && (crowd[a] | crowd[b]) != 0) {
        is_deep = 2;
      }
      deep[k] = is_deep;
      any |= is_deep;
    }
    block_deep[block] = any;
  });
  if (std::find_if(block_deep.begin(), block_deep.end(), [](uint8_t f) { return f != 0; }) ==
      block_deep.end()) {
    return 0;
  }
  // The budget, in pair order: the pair list is sorted, so which deep pairs a body keeps does
  // not depend on how the pairs were found.
  // Deep pairs and a crowd's near pairs have a budget each (kept_deep[2 i], kept_deep[2 i + 1]).
  std::vector<uint32_t>& kept_deep = w.deep_kept;
  grow_fill(kept_deep, 2 * w.bodies.size(), uint32_t{0});
  std::size_t kept = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const uint64_t key = w.pairs[k];
    if (deep[k]) {
      const uint32_t a = pair_first(key), b = pair_second(key);
      uint32_t& ka = kept_deep[2 * std::size_t(a) + deep[k] - 1];
      uint32_t& kb = kept_deep[2 * std::size_t(b) + deep[k] - 1];
      if (ka >= kDeepPairBudget || kb >= kDeepPairBudget) continue;
      ++ka;
      ++kb;
    }
    w.pairs[kept++] = key;
  }
  const std::size_t dropped = n - kept;
  w.pairs.resize(kept);
  return dropped;
}

}  // namespace elan::detail
