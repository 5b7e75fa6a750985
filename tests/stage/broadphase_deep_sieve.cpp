// SPDX-License-Identifier: MIT
// The deep sieve (broadphase/deep_sieve.hpp): on a crowd of boxes, some of them at one point, every
// finder under 1 and 2 threads stores exactly the brute-force list less its deep pairs, and
// keeps as candidates exactly each body's kCandidates best deep partners by the documented order
// (deep_pair_rank, then the partner's index), computed here from the oracle's list.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "broadphase/find_pairs.hpp"
#include "core/base/pair_key.hpp"

namespace elan::detail {
namespace broadphase_deep_sieve_test {

struct Crowd {
  BoundsColumns bounds;
  std::vector<uint8_t> kind, is_plane;
  std::vector<BodyTraits> trait_table;
  std::vector<uint32_t> traits;
  std::vector<DeepBall> balls;

  BroadphaseInput input(DeepSieve* sieve) const {
    BroadphaseInput in{&bounds, kind, traits, trait_table, is_plane};
    in.deep = sieve;
    return in;
  }
};

// n unit boxes: a third exactly at the origin, a third scattered within 0.3 m of it, a third
// spread over 12 m (few of them deep); some bodies sleep, some are static (no ball: never deep).
Crowd make_crowd(std::size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> near(-0.3, 0.3), far(-6, 6);
  Crowd c;
  c.trait_table.resize(1);
  c.trait_table[0].category = 1;  // one filter for all: every pair passes
  c.trait_table[0].mask = ~0u;
  c.bounds.resize(n);
  c.kind.assign(n, uint8_t(BroadKind::Awake));
  c.is_plane.assign(n, 0);
  c.traits.assign(n, 0);
  c.balls.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 p = Vec3::Zero();
    if (i % 3 == 1) p = Vec3(Real(near(rng)), Real(near(rng)), Real(near(rng)));
    if (i % 3 == 2) p = Vec3(Real(far(rng)), Real(far(rng)), Real(far(rng)));
    const Real h = Real(0.5);
    c.bounds.min_x[i] = p.x() - h;
    c.bounds.min_y[i] = p.y() - h;
    c.bounds.min_z[i] = p.z() - h;
    c.bounds.max_x[i] = p.x() + h;
    c.bounds.max_y[i] = p.y() + h;
    c.bounds.max_z[i] = p.z() + h;
    Real r = h;
    if (i % 17 == 0) {
      c.kind[i] = uint8_t(BroadKind::Static);
      r = 0;
    } else if (i % 11 == 0) {
      c.kind[i] = uint8_t(BroadKind::Sleeping);
    }
    c.balls[i] = {p.x(), p.y(), p.z(), r, 0};
  }
  uint32_t ordinal = 0;
  for (DeepBall& b : c.balls) {
    b.run = ordinal / DeepSieve::kRun;
    ordinal += b.r > 0 ? 1 : 0;
  }
  return c;
}

// The sieve's contract from the oracle's list: the stored pairs and the candidate pairs.
void expected(const Crowd& c, std::vector<uint64_t>& stored, std::vector<uint64_t>& candidates) {
  std::vector<uint64_t> all;
  find_pairs_brute_force(c.input(nullptr), all);
  const std::size_t n = c.balls.size();
  using Rank = std::pair<uint64_t, uint32_t>;
  std::vector<std::vector<Rank>> partners(n);
  stored.clear();
  for (const uint64_t key : all) {
    const uint32_t a = pair_first(key), b = pair_second(key);
    if (!balls_deep(c.balls[a], c.balls[b])) {
      stored.push_back(key);
      continue;
    }
    const uint64_t rank = deep_pair_rank(c.balls[a], c.balls[b], key);
    partners[a].emplace_back(rank, b);
    partners[b].emplace_back(rank, a);
  }
  candidates.clear();
  for (uint32_t i = 0; i < n; ++i) {
    std::vector<Rank>& p = partners[i];
    std::sort(p.begin(), p.end());
    for (std::size_t k = 0; k < std::min<std::size_t>(p.size(), DeepSieve::kCandidates); ++k) {
      candidates.push_back(make_pair_key(i, p[k].second));
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
}

TEST(DeepSieve, EveryFinderKeepsTheSameCandidatesAndStoresTheRest) {
  const Crowd crowd = make_crowd(900, 7);
  std::vector<uint64_t> stored, candidates;
  expected(crowd, stored, candidates);
  // The crowd is one: a third of the bodies have hundreds of deep partners each, so the sets cut.
  ASSERT_GT(candidates.size(), 1000u);
  ASSERT_LT(candidates.size(), crowd.balls.size() * DeepSieve::kCandidates);
  ASSERT_GT(stored.size(), 100u);

  SweepAndPrune sap;
  AllPairs all;
  TreePairs tree;
  DeepSieve sieve;
  for (int threads = 1; threads <= 2; ++threads) {
    for (int method = 0; method < 3; ++method) {
      const std::string what = std::string(method == 0   ? "SAP"
                                           : method == 1 ? "all-pairs"
                                                         : "tree") +
                               ", threads " + std::to_string(threads);
      std::vector<uint64_t> got, got_candidates;
      std::size_t taken = 0;
      tbb::task_arena arena(threads);
      arena.execute([&] {
        sieve.begin(crowd.balls);
        const BroadphaseInput in = crowd.input(&sieve);
        if (method == 0) sap.find_pairs(in, got);
        if (method == 1) all.find_pairs(in, got);
        if (method == 2) tree.find_pairs(in, got);
        taken = sieve.collect(got_candidates);
      });
      std::sort(got_candidates.begin(), got_candidates.end());
      EXPECT_TRUE(got == stored) << what << ": " << got.size() << " vs " << stored.size();
      EXPECT_TRUE(got_candidates == candidates)
          << what << ": " << got_candidates.size() << " vs " << candidates.size();
      EXPECT_GT(taken, got_candidates.size()) << what;
    }
  }
}

// A body with no more deep partners than its set holds keeps them all: the sieve changes nothing
// of a scene with few deep pairs.
TEST(DeepSieve, FewDeepPartnersAreAllKept) {
  Crowd crowd = make_crowd(12, 3);
  std::vector<uint64_t> stored, candidates, all;
  expected(crowd, stored, candidates);
  find_pairs_brute_force(crowd.input(nullptr), all);
  std::vector<uint64_t> joined = stored;
  joined.insert(joined.end(), candidates.begin(), candidates.end());
  std::sort(joined.begin(), joined.end());
  ASSERT_TRUE(joined == all);  // 12 bodies: at most 7 within reach, fewer than kCandidates

  DeepSieve sieve;
  SweepAndPrune sap;
  std::vector<uint64_t> got, got_candidates;
  tbb::task_arena arena(2);
  arena.execute([&] {
    sieve.begin(crowd.balls);
    sap.find_pairs(crowd.input(&sieve), got);
    sieve.collect(got_candidates);
  });
  got.insert(got.end(), got_candidates.begin(), got_candidates.end());
  std::sort(got.begin(), got.end());
  EXPECT_TRUE(got == all);
}

// begin() sizes every thread's sets: a worker that takes its first batch only when the scene is
// long warm must not allocate then (ragdolls at 2 threads did, in CI). A batch of deep pairs
// sieved after begin() leaves the sieve's heap as begin() left it.
TEST(DeepSieve, BeginSizesEveryThreadsSets) {
  const Crowd crowd = make_crowd(300, 5);
  std::vector<uint64_t> stored, candidates;
  expected(crowd, stored, candidates);
  ASSERT_GT(candidates.size(), 100u);
  DeepSieve sieve;
  tbb::task_arena arena(2);
  arena.execute([&] {
    sieve.begin(crowd.balls);
    const std::size_t sized = sieve.heap_bytes();
    std::vector<uint64_t> batch = candidates;
    // Every pair of the batch is deep, so each sieve() call offers them all to its thread's sets.
    EXPECT_EQ(sieve.sieve(batch.data(), batch.size()), 0u);
    EXPECT_EQ(sieve.heap_bytes(), sized);
    std::vector<uint64_t> out;
    out.reserve(candidates.size());
    sieve.collect(out);
    EXPECT_EQ(out.size(), candidates.size());
  });
}

}  // namespace broadphase_deep_sieve_test
}  // namespace elan::detail
