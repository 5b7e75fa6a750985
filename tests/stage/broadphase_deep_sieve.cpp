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

#include "broadphase/closed_runs.hpp"
#include "broadphase/find_pairs.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/simd_path.hpp"

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
// With a clump, the first `clump` bodies are all at the origin instead, so that most of their
// runs are closed (closed_runs.hpp): all but those holding two sleeping bodies, never paired.
Crowd make_crowd(std::size_t n, uint32_t seed, std::size_t clump = 0) {
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
    if (i % 3 == 1) p = Vec3{Real(near(rng)), Real(near(rng)), Real(near(rng))};
    if (i % 3 == 2) p = Vec3{Real(far(rng)), Real(far(rng)), Real(far(rng))};
    if (i < clump) p = Vec3::Zero();
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

// Every finder under 1 and 2 threads (SAP on every SIMD path this CPU runs) against the oracle,
// each with a fresh sieve (cold) and with one that has collected the same crowd once (warm: its
// crowded bodies are then looked for closed at levels above their run's, closed_runs.hpp).
void expect_every_finder_matches(const Crowd& crowd, const std::vector<uint64_t>& stored,
                                 const std::vector<uint64_t>& candidates) {
  SweepAndPrune sap;
  AllPairs all;
  TreePairs tree;
  std::vector<SimdPath> paths;
  for (const SimdPath path : {SimdPath::Sse2, SimdPath::Avx2, SimdPath::Avx512, SimdPath::Native}) {
    if (cpu_runs(path)) paths.push_back(path);
  }
  for (const bool warm : {false, true}) {
    for (int threads = 1; threads <= 2; ++threads) {
      for (std::size_t method = 0; method < 2 + paths.size(); ++method) {
        const std::string what =
            std::string(method == 0   ? "all-pairs"
                        : method == 1 ? "tree"
                                      : "SAP path " + std::to_string(int(paths[method - 2]))) +
            ", threads " + std::to_string(threads) + (warm ? ", warm" : ", cold");
        std::vector<uint64_t> got, got_candidates;
        std::size_t taken = 0;
        DeepSieve sieve;
        tbb::task_arena arena(threads);
        arena.execute([&] {
          if (warm) {
            sieve.begin(crowd.balls);
            all.find_pairs(crowd.input(&sieve), got);
            sieve.collect(got_candidates);
            got.clear();
            got_candidates.clear();
          }
          sieve.begin(crowd.balls);
          BroadphaseInput in = crowd.input(&sieve);
          if (method == 0) all.find_pairs(in, got);
          if (method == 1) tree.find_pairs(in, got);
          if (method >= 2) {
            in.simd = paths[method - 2];
            sap.find_pairs(in, got);
          }
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
}

TEST(DeepSieve, EveryFinderKeepsTheSameCandidatesAndStoresTheRest) {
  const Crowd crowd = make_crowd(900, 7);
  std::vector<uint64_t> stored, candidates;
  expected(crowd, stored, candidates);
  // The crowd is one: a third of the bodies have hundreds of deep partners each, so the sets cut.
  ASSERT_GT(candidates.size(), 1000u);
  ASSERT_LT(candidates.size(), crowd.balls.size() * DeepSieve::kCandidates);
  ASSERT_GT(stored.size(), 100u);
  expect_every_finder_matches(crowd, stored, candidates);
}

// The closed levels (closed_runs.hpp) from their definition: a body is closed at the lowest level
// (up to 1 without a hint, kMaxClosedLevel with one) whose group holds kCandidates of its deep
// partners that the finders report; its shift is kLevelShift (level - 1).
std::vector<uint32_t> closed_by_definition(const Crowd& c, bool hinted) {
  const std::size_t n = c.balls.size();
  std::vector<uint32_t> shift(n, kOpenShift);
  std::vector<uint64_t> all;
  find_pairs_brute_force(c.input(nullptr), all);
  for (uint32_t i = 0; i < n; ++i) {
    if (!(c.balls[i].r > 0)) continue;
    for (uint32_t level = 1; level <= (hinted ? kMaxClosedLevel : 1u); ++level) {
      const uint32_t s = kLevelShift * (level - 1);
      uint32_t count = 0;
      for (uint32_t j = 0; j < n; ++j) {
        if (j == i || !(c.balls[j].r > 0) || (c.balls[j].run >> s) != (c.balls[i].run >> s)) {
          continue;
        }
        const bool paired = std::binary_search(all.begin(), all.end(), make_pair_key(i, j));
        count += paired && balls_deep(c.balls[i], c.balls[j]) ? 1 : 0;
      }
      if (count >= DeepSieve::kCandidates) {
        shift[i] = s;
        break;
      }
    }
  }
  return shift;
}

std::size_t closed_count(const std::vector<uint32_t>& shift, uint32_t above = 0) {
  return std::size_t(std::count_if(shift.begin(), shift.end(),
                                   [&](uint32_t s) { return s != kOpenShift && s >= above; }));
}

TEST(DeepSieve, ClosedLevelsFollowTheirDefinition) {
  for (const std::size_t clump : {std::size_t(0), std::size_t(300)}) {
    const Crowd crowd = make_crowd(900, 11, clump);
    for (const bool hinted : {false, true}) {
      const std::vector<uint32_t> want = closed_by_definition(crowd, hinted);
      const std::vector<uint8_t> hint(hinted ? crowd.balls.size() : 0, 1);
      std::vector<uint32_t> got(crowd.balls.size()), order(crowd.balls.size());
      const std::size_t count =
          find_closed_runs(crowd.input(nullptr), crowd.balls, hint, order, got);
      const std::string what = "clump " + std::to_string(clump) + (hinted ? ", hinted" : "");
      EXPECT_TRUE(got == want) << what;
      EXPECT_EQ(count, closed_count(want)) << what;
      // The clump's runs close but for those with two sleeping bodies (never paired); the scattered
      // crowd's runs mix bodies metres apart and close none. With the hint, the bodies at or near
      // the origin close in their groups of 8 runs.
      if (clump == 0 && !hinted) {
        EXPECT_EQ(count, 0u) << what;
      } else {
        EXPECT_GT(count, 200u) << what;
      }
      if (hinted) {
        EXPECT_GT(closed_count(want, kLevelShift), 100u) << what;
      }
    }
  }
  // Runs not as prepare_deep_sieve makes them (a run out of order) close nothing.
  Crowd crowd = make_crowd(90, 3, 90);
  std::vector<uint32_t> got(crowd.balls.size()), order(crowd.balls.size());
  ASSERT_GT(find_closed_runs(crowd.input(nullptr), crowd.balls, {}, order, got), 0u);
  std::swap(crowd.balls[1].run, crowd.balls[40].run);
  EXPECT_EQ(find_closed_runs(crowd.input(nullptr), crowd.balls, {}, order, got), 0u);
  EXPECT_EQ(closed_count(got), 0u);
}

// A crowd whose first 300 bodies are at one point: their runs are closed, and SAP passes the deep
// pairs between two of them by in its kernel (closed_runs.hpp); the list and the candidates are
// still the oracle's, with the bodies of the other runs, open, offering theirs to the sieve.
TEST(DeepSieve, ClosedBodiesPassedByInTheSweepChangeNothing) {
  const Crowd crowd = make_crowd(900, 13, 300);
  std::vector<uint32_t> closed(crowd.balls.size()), order(crowd.balls.size());
  ASSERT_GT(find_closed_runs(crowd.input(nullptr), crowd.balls, {}, order, closed), 200u);
  std::vector<uint64_t> stored, candidates;
  expected(crowd, stored, candidates);
  ASSERT_GT(candidates.size(), 1000u);
  ASSERT_GT(stored.size(), 100u);
  expect_every_finder_matches(crowd, stored, candidates);
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
