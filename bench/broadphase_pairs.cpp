// SPDX-License-Identifier: MIT
// Pair finding on a settled pile of boxes, N = 1k..256k, sweep-and-prune vs all-pairs vs the tree
// at 1 and 2 threads. Each update sees a small motion of every box, so SAP runs its incremental
// re-sort. "static_world": the same boxes, all static but one in a hundred (a large level with a
// few movers).
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "broadphase/find_pairs.hpp"

namespace {

using elan::Real;
using namespace elan::detail;

// A pile settled in a container: boxes of ~0.5 m on a jittered 0.5 m lattice, kPileLayers deep,
// on a square floor that grows with N; each box touches a handful of neighbours (margin 1 cm).
// Floor and four walls are planes with axis-aligned boxes, as a container in a scene would be.
constexpr int kPileLayers = 10;
constexpr Real kCell = Real(0.5);
constexpr Real kMargin = Real(0.01);

struct Pile {
  BoundsColumns bounds[2];  // two poses a few millimetres apart, alternated every update
  std::vector<uint8_t> kind, is_plane;
  std::vector<uint32_t> traits;            // every body: entry 0
  std::vector<BodyTraits> trait_table{1};  // category 1, mask all: every pair passes

  BroadphaseInput input(int pose) const {
    return {&bounds[pose], kind, traits, trait_table, is_plane};
  }
};

Pile make_pile(std::size_t n) {
  const int side = int(std::ceil(std::sqrt(double(n) / kPileLayers)));
  const Real wall = side * kCell;
  constexpr Real kInf = std::numeric_limits<Real>::infinity();
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02), size(0.23, 0.25),
      shake(-0.002, 0.002);
  Pile p;
  const std::size_t total = n + 5;
  for (auto& b : p.bounds) b.resize(total);
  p.kind.assign(total, uint8_t(BroadKind::Awake));
  p.is_plane.assign(total, 0);
  p.traits.assign(total, 0);
  p.trait_table[0].category = 1;
  p.trait_table[0].mask = ~0u;
  for (std::size_t i = 0; i < n; ++i) {
    const int col = int(i % std::size_t(side * side));
    const int layer = int(i / std::size_t(side * side));
    const Real c[3] = {(Real(col % side) + Real(0.5)) * kCell + Real(jitter(rng)),
                       (Real(layer) + Real(0.5)) * kCell + Real(jitter(rng)),
                       (Real(col / side) + Real(0.5)) * kCell + Real(jitter(rng))};
    const Real h = Real(size(rng)) + kMargin;
    for (auto& b : p.bounds) {
      Real d[3];
      for (Real& v : d) v = Real(shake(rng));
      b.min_x[i] = c[0] + d[0] - h;
      b.max_x[i] = c[0] + d[0] + h;
      b.min_y[i] = c[1] + d[1] - h;
      b.max_y[i] = c[1] + d[1] + h;
      b.min_z[i] = c[2] + d[2] - h;
      b.max_z[i] = c[2] + d[2] + h;
    }
  }
  // Floor y <= 0, walls x <= 0, x >= wall, z <= 0, z >= wall.
  const Real lo[5][3] = {{-kInf, -kInf, -kInf},
                         {-kInf, -kInf, -kInf},
                         {wall, -kInf, -kInf},
                         {-kInf, -kInf, -kInf},
                         {-kInf, -kInf, wall}};
  const Real hi[5][3] = {
      {kInf, 0, kInf}, {0, kInf, kInf}, {kInf, kInf, kInf}, {kInf, kInf, 0}, {kInf, kInf, kInf}};
  for (std::size_t k = 0; k < 5; ++k) {
    const std::size_t i = n + k;
    p.is_plane[i] = 1;
    p.kind[i] = uint8_t(BroadKind::Static);
    for (auto& b : p.bounds) {
      b.min_x[i] = lo[k][0] - kMargin;
      b.min_y[i] = lo[k][1] - kMargin;
      b.min_z[i] = lo[k][2] - kMargin;
      b.max_x[i] = hi[k][0] + kMargin;
      b.max_y[i] = hi[k][1] + kMargin;
      b.max_z[i] = hi[k][2] + kMargin;
    }
  }
  return p;
}

const Pile& pile(std::size_t n) {
  static std::size_t cached_n = 0;
  static Pile cached;
  if (cached_n != n) {
    cached = make_pile(n);
    cached_n = n;
  }
  return cached;
}

// The pile with every body static but one in a hundred.
const Pile& static_world(std::size_t n) {
  static std::size_t cached_n = 0;
  static Pile cached;
  if (cached_n != n) {
    cached = make_pile(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (i % 100 != 0) cached.kind[i] = uint8_t(BroadKind::Static);
    }
    cached_n = n;
  }
  return cached;
}

template <class Method, bool kStatic = false>
void run(benchmark::State& state) {
  const std::size_t n = std::size_t(state.range(0));
  const int threads = int(state.range(1));
  const Pile& p = kStatic ? static_world(n) : pile(n);
  Method method;
  std::vector<uint64_t> pairs;
  tbb::task_arena arena(threads);
  arena.execute([&] {
    method.find_pairs(p.input(0), pairs);  // warm-up: first sort, buffers reach their size
    int pose = 1;
    for (auto _ : state) {
      method.find_pairs(p.input(pose), pairs);
      benchmark::DoNotOptimize(pairs.data());
      pose ^= 1;
    }
  });
  state.counters["pairs"] = double(pairs.size());
  state.counters["pairs/body"] = double(pairs.size()) / double(n);
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(pairs.size()));
}

}  // namespace

// Registered per N, SAP and all-pairs side by side, so machine noise hits both alike. All-pairs
// stops at 64k: beyond, one update takes seconds.
int main(int argc, char** argv) {
  for (int64_t n : {1024, 4096, 16384, 65536, 262144}) {
    for (int64_t t : {1, 2}) {
      benchmark::RegisterBenchmark("sap", run<SweepAndPrune>)
          ->Args({n, t})
          ->ArgNames({"n", "threads"})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
    if (n > 65536) continue;
    for (int64_t t : {1, 2}) {
      benchmark::RegisterBenchmark("tree", run<TreePairs>)
          ->Args({n, t})
          ->ArgNames({"n", "threads"})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
      benchmark::RegisterBenchmark("static_world_sap", run<SweepAndPrune, true>)
          ->Args({n, t})
          ->ArgNames({"n", "threads"})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
      benchmark::RegisterBenchmark("static_world_tree", run<TreePairs, true>)
          ->Args({n, t})
          ->ArgNames({"n", "threads"})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
    for (int64_t t : {1, 2}) {
      benchmark::RegisterBenchmark("all_pairs", run<AllPairs>)
          ->Args({n, t})
          ->ArgNames({"n", "threads"})
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
