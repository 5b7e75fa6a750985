// SPDX-License-Identifier: MIT
// Broadphase pair finding: sweep-and-prune and all-pairs give the brute-force oracle's list bit for
// bit on random box sets and moving scenes, under 1 and 2 worker threads.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "broadphase/find_pairs.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/simd_path.hpp"

namespace elan::detail {
namespace broadphase_pairs_test {

constexpr Real kInf = std::numeric_limits<Real>::infinity();

struct BoxSet {
  BoundsColumns bounds;
  std::vector<uint8_t> kind, is_plane;
  std::vector<uint32_t> category, mask;
  // What input() hands the broadphase: an entry of traits a body, holding its filter.
  mutable std::vector<BodyTraits> trait_table;
  mutable std::vector<uint32_t> traits;

  std::size_t size() const { return kind.size(); }
  void resize(std::size_t n) {
    bounds.resize(n);
    kind.resize(n, uint8_t(BroadKind::Awake));
    is_plane.resize(n, 0);
    category.resize(n, 1);
    mask.resize(n, ~0u);
  }
  void set_box(std::size_t i, const Vec3& lo, const Vec3& hi) {
    bounds.min_x[i] = lo.x();
    bounds.min_y[i] = lo.y();
    bounds.min_z[i] = lo.z();
    bounds.max_x[i] = hi.x();
    bounds.max_y[i] = hi.y();
    bounds.max_z[i] = hi.z();
  }
  BroadphaseInput input() const {
    trait_table.resize(size());
    traits.resize(size());
    for (std::size_t i = 0; i < size(); ++i) {
      trait_table[i].category = category[i];
      trait_table[i].mask = mask[i];
      traits[i] = uint32_t(i);
    }
    return {&bounds, kind, traits, trait_table, is_plane};
  }
};

enum class Layout {
  Uniform,
  Clustered,
  Elongated,
  AllOverlap,
  AllDisjoint,
  Duplicates,
  HugeTiny,
  TouchingGrid
};

Real uniform(std::mt19937& rng, Real lo, Real hi) {
  return lo + (hi - lo) * Real(std::uniform_real_distribution<double>(0, 1)(rng));
}

// Random kinds (all four), filter bits where roughly one pair in six is filtered out, and with
// `planes` the last bodies become planes: one infinite box, one half-space y <= 0.
void randomise_flags(BoxSet& s, std::mt19937& rng, int planes) {
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i) {
    s.kind[i] = uint8_t(rng() % 4);
    s.category[i] = 1u << (rng() % 3);
    s.mask[i] = (rng() % 4 == 0) ? ~s.category[i] : ~0u;
  }
  for (int p = 0; p < planes && std::size_t(p) < n; ++p) {
    const std::size_t i = n - 1 - std::size_t(p);
    s.is_plane[i] = 1;
    s.kind[i] = uint8_t(BroadKind::Static);
    if (p == 0) {
      s.set_box(i, Vec3::Constant(-kInf), Vec3::Constant(kInf));
    } else {
      s.set_box(i, Vec3::Constant(-kInf), Vec3(kInf, 0, kInf));
    }
  }
}

BoxSet make_boxes(Layout layout, std::size_t n, uint32_t seed, int planes) {
  std::mt19937 rng(seed);
  BoxSet s;
  s.resize(n);
  const Real side = Real(1.5) * std::cbrt(Real(n));  // about one box per 27 m^3
  std::vector<Vec3> clusters;
  for (int c = 0; c < 5; ++c) {
    clusters.push_back(
        Vec3{uniform(rng, -side, side), uniform(rng, -side, side), uniform(rng, -side, side)});
  }
  const int grid = int(std::ceil(std::cbrt(double(n))));
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 c{uniform(rng, -side, side), uniform(rng, -side, side), uniform(rng, -side, side)};
    Vec3 h = Vec3::Constant(uniform(rng, Real(0.2), Real(1.5)));
    switch (layout) {
      case Layout::Uniform:
        h = Vec3{uniform(rng, 0.2, 1.5), uniform(rng, 0.2, 1.5), uniform(rng, 0.2, 1.5)};
        break;
      case Layout::Clustered: {
        std::normal_distribution<double> g(0, 2);
        const Vec3& around = clusters[rng() % clusters.size()];
        c = around + Vec3{Real(g(rng)), Real(g(rng)), Real(g(rng))};
        break;
      }
      case Layout::Elongated:
        h = Vec3::Constant(Real(0.1));
        h[int(rng() % 3)] = uniform(rng, side / 4, side);
        break;
      case Layout::AllOverlap:
        c = Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
        h = Vec3::Constant(uniform(rng, Real(1), Real(3)));
        break;
      case Layout::AllDisjoint:
      case Layout::TouchingGrid: {
        const int g = int(i);
        c = Vec3(Real(g % grid), Real((g / grid) % grid), Real(g / (grid * grid)));
        h = Vec3::Constant(layout == Layout::AllDisjoint ? Real(0.45) : Real(0.5));
        break;
      }
      case Layout::Duplicates:
        c = Vec3(1, 2, 3);
        h = Vec3(Real(0.5), Real(0.25), Real(1));
        break;
      case Layout::HugeTiny:
        h = (i % 50 == 0) ? Vec3::Constant(side / 2) : Vec3::Constant(Real(0.01));
        break;
    }
    s.set_box(i, c - h, c + h);
  }
  randomise_flags(s, rng, planes);
  return s;
}

std::vector<uint64_t> run_in_arena(int threads, auto&& f) {
  std::vector<uint64_t> out;
  tbb::task_arena arena(threads);
  arena.execute([&] { f(out); });
  return out;
}

bool sorted_unique(const std::vector<uint64_t>& v) {
  return std::adjacent_find(v.begin(), v.end(), [](uint64_t a, uint64_t b) { return a >= b; }) ==
         v.end();
}

// Oracle once, then every method under 1 and 2 threads must reproduce it exactly.
// Returns the oracle's pair count.
std::size_t expect_all_methods_match(const BoxSet& s, const std::string& what) {
  const BroadphaseInput in = s.input();
  std::vector<uint64_t> oracle;
  find_pairs_brute_force(in, oracle);
  EXPECT_TRUE(sorted_unique(oracle)) << what;
  for (int threads : {1, 2}) {
    SweepAndPrune sap;
    AllPairs all;
    TreePairs tree;
    const auto sap_pairs = run_in_arena(threads, [&](auto& out) { sap.find_pairs(in, out); });
    const auto all_pairs = run_in_arena(threads, [&](auto& out) { all.find_pairs(in, out); });
    const auto tree_pairs = run_in_arena(threads, [&](auto& out) { tree.find_pairs(in, out); });
    EXPECT_TRUE(tree_pairs == oracle) << what << ", tree, threads " << threads << ": "
                                      << tree_pairs.size() << " vs " << oracle.size() << " pairs";
    EXPECT_TRUE(sap_pairs == oracle) << what << ", SAP, threads " << threads << ": "
                                     << sap_pairs.size() << " vs " << oracle.size() << " pairs";
    EXPECT_TRUE(all_pairs == oracle) << what << ", all-pairs, threads " << threads << ": "
                                     << all_pairs.size() << " vs " << oracle.size() << " pairs";
  }
  return oracle.size();
}

TEST(Broadphase, OracleAppliesKindAndFilterRules) {
  BoxSet s;
  s.resize(4);
  for (std::size_t i = 0; i < 4; ++i) s.set_box(i, Vec3::Zero(), Vec3::Ones());
  s.kind = {uint8_t(BroadKind::Static), uint8_t(BroadKind::Kinematic), uint8_t(BroadKind::Sleeping),
            uint8_t(BroadKind::Awake)};
  std::vector<uint64_t> pairs;
  find_pairs_brute_force(s.input(), pairs);
  // Static-kinematic, static-sleeping are dropped; kinematic-sleeping and all awake pairs stay.
  const std::vector<uint64_t> expected = {make_pair_key(0, 3), make_pair_key(1, 2),
                                          make_pair_key(1, 3), make_pair_key(2, 3)};
  EXPECT_EQ(pairs, expected);
  s.category[3] = 2;
  s.mask[1] = 1;  // body 1 ignores category 2: (1, 3) goes
  find_pairs_brute_force(s.input(), pairs);
  const std::vector<uint64_t> filtered = {make_pair_key(0, 3), make_pair_key(1, 2),
                                          make_pair_key(2, 3)};
  EXPECT_EQ(pairs, filtered);
}

TEST(Broadphase, TouchingBoxesOverlap) {
  BoxSet s;
  s.resize(3);
  s.set_box(0, Vec3(0, 0, 0), Vec3(1, 1, 1));
  s.set_box(1, Vec3(1, 0, 0), Vec3(2, 1, 1));                               // shares the face x = 1
  s.set_box(2, Vec3(2, 1, 1) + Vec3::Constant(Real(1e-3)), Vec3(3, 2, 2));  // a gap
  std::vector<uint64_t> pairs;
  find_pairs_brute_force(s.input(), pairs);
  EXPECT_EQ(pairs, std::vector<uint64_t>{make_pair_key(0, 1)});
  expect_all_methods_match(s, "touching");
}

TEST(SweepAndPrune, MatchesBruteForceOnRandomBoxes) {
  const struct {
    Layout layout;
    std::size_t n;
    const char* name;
  } cases[] = {
      {Layout::Uniform, 10, "uniform 10"},           {Layout::Uniform, 3000, "uniform 3000"},
      {Layout::Clustered, 2000, "clustered"},        {Layout::Elongated, 1500, "elongated"},
      {Layout::AllOverlap, 300, "all overlapping"},  {Layout::AllDisjoint, 2000, "all disjoint"},
      {Layout::Duplicates, 200, "duplicates"},       {Layout::HugeTiny, 2500, "huge and tiny"},
      {Layout::TouchingGrid, 1000, "touching grid"},
  };
  uint32_t seed = 1;
  for (const auto& c : cases) {
    for (int planes : {0, 2}) {
      const BoxSet s = make_boxes(c.layout, c.n, seed++, planes);
      expect_all_methods_match(s, std::string(c.name) + ", planes " + std::to_string(planes));
    }
  }
}

// The sweep's kernel is compiled once per SIMD path in a dispatching build (sweep_kernel.hpp):
// each path this CPU runs must give the oracle's list, whatever ELAN_SIMD picks for the others.
TEST(SweepAndPrune, EverySimdPathMatchesBruteForce) {
  int paths = 0;
  uint32_t seed = 500;
  for (const SimdPath path : {SimdPath::Sse2, SimdPath::Avx2, SimdPath::Avx512, SimdPath::Native}) {
    if (!cpu_runs(path)) continue;
    ++paths;
    for (const Layout layout : {Layout::Uniform, Layout::Clustered, Layout::TouchingGrid}) {
      const BoxSet s = make_boxes(layout, 2000, seed++, 2);
      BroadphaseInput in = s.input();
      in.simd = path;
      std::vector<uint64_t> oracle;
      find_pairs_brute_force(in, oracle);
      ASSERT_FALSE(oracle.empty());
      for (int threads : {1, 2}) {
        SweepAndPrune sap;
        const auto pairs = run_in_arena(threads, [&](auto& out) { sap.find_pairs(in, out); });
        EXPECT_TRUE(pairs == oracle)
            << "path " << int(path) << ", layout " << int(layout) << ", threads " << threads << ": "
            << pairs.size() << " vs " << oracle.size() << " pairs";
      }
    }
  }
  // A dispatching build runs SSE2 at least; a native build its one path.
  EXPECT_GE(paths, 1);
}

TEST(SweepAndPrune, MatchesBruteForceOnTwentyThousandBoxes) {
  const BoxSet s = make_boxes(Layout::Uniform, 20000, 99, 1);
  // Only meaningful with many pairs to get right.
  EXPECT_GT(expect_all_methods_match(s, "uniform 20000"), s.size() / 4);
}

// One SAP and one all-pairs instance kept across updates, so SAP's incremental order, its
// full-sort fallbacks (body count changed, large jump) and axis changes are all exercised.
TEST(SweepAndPrune, MatchesBruteForceEveryUpdateOfMovingScene) {
  std::mt19937 rng(7);
  std::size_t n = 1500;
  std::vector<Vec3> pos(n), vel(n), half(n);
  const Real side = 10;
  auto spawn = [&](std::size_t i) {
    pos[i] = Vec3{uniform(rng, -side, side), uniform(rng, -side, side), uniform(rng, -side, side)};
    vel[i] = Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)} * Real(0.2);
    half[i] = Vec3{uniform(rng, 0.2, 0.8), uniform(rng, 0.2, 0.8), uniform(rng, 0.2, 0.8)};
  };
  for (std::size_t i = 0; i < n; ++i) spawn(i);
  BoxSet s;
  s.resize(n);
  randomise_flags(s, rng, 1);

  SweepAndPrune sap1, sap2;
  AllPairs all;
  TreePairs tree1, tree2;
  std::vector<uint64_t> oracle, got;
  Vec3 stretch = Vec3::Ones();
  for (int update = 0; update < 80; ++update) {
    if (update == 30) {  // bodies added: count changes, planes move to the middle
      const std::size_t add = 200;
      pos.resize(n + add);
      vel.resize(n + add);
      half.resize(n + add);
      for (std::size_t i = n; i < n + add; ++i) spawn(i);
      n += add;
      s.resize(n);
      for (std::size_t i = n - add; i < n; ++i) s.kind[i] = uint8_t(rng() % 4);
    }
    if (update == 45) {  // a jump far beyond the insertion-sort budget
      std::shuffle(pos.begin(), pos.end(), rng);
    }
    if (update >= 50) stretch = Vec3(1, 1, Real(1) + Real(update - 49) * Real(0.2));  // axis -> z
    if (update % 10 == 5) {  // bodies go to sleep, wake, change filter
      for (int k = 0; k < 100; ++k) {
        const std::size_t i = rng() % n;
        if (s.is_plane[i]) continue;
        s.kind[i] = uint8_t(rng() % 4);
        s.category[i] = 1u << (rng() % 3);
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (s.is_plane[i]) continue;
      pos[i] += vel[i];
      for (int a = 0; a < 3; ++a) {
        if (std::abs(pos[i][a]) > side) vel[i][a] = -vel[i][a];
      }
      const Vec3 c = pos[i].cwiseProduct(stretch);
      s.set_box(i, c - half[i], c + half[i]);
    }
    const BroadphaseInput in = s.input();
    find_pairs_brute_force(in, oracle);
    ASSERT_GT(oracle.size(), n / 8);
    got = run_in_arena(1, [&](auto& out) { sap1.find_pairs(in, out); });
    ASSERT_TRUE(got == oracle) << "SAP 1 thread, update " << update;
    got = run_in_arena(2, [&](auto& out) { sap2.find_pairs(in, out); });
    ASSERT_TRUE(got == oracle) << "SAP 2 threads, update " << update;
    got = run_in_arena(2, [&](auto& out) { all.find_pairs(in, out); });
    ASSERT_TRUE(got == oracle) << "all-pairs 2 threads, update " << update;
    // The trees keep their leaves from update to update: refits, re-inserts, count changes.
    got = run_in_arena(1, [&](auto& out) { tree1.find_pairs(in, out); });
    ASSERT_TRUE(got == oracle) << "tree 1 thread, update " << update;
    got = run_in_arena(2, [&](auto& out) { tree2.find_pairs(in, out); });
    ASSERT_TRUE(got == oracle) << "tree 2 threads, update " << update;
    ASSERT_TRUE(tree1.tree().valid()) << "update " << update;
  }
}

TEST(SweepAndPrune, NonFiniteBoxesPairWithNothing) {
  BoxSet s = make_boxes(Layout::AllOverlap, 50, 3, 1);
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  s.bounds.min_x[4] = nan;
  s.bounds.max_y[9] = nan;
  s.bounds.min_z[17] = nan;
  // A box unbounded above on every axis reaches the NaN boxes in any sweep order.
  s.bounds.max_x[20] = s.bounds.max_y[20] = s.bounds.max_z[20] = kInf;
  std::vector<uint64_t> oracle;
  find_pairs_brute_force(s.input(), oracle);
  for (uint64_t key : oracle) {
    for (uint32_t bad : {4u, 9u, 17u}) {
      ASSERT_NE(pair_first(key), bad);
      ASSERT_NE(pair_second(key), bad);
    }
  }
  expect_all_methods_match(s, "NaN boxes");
}

}  // namespace broadphase_pairs_test
}  // namespace elan::detail
