// SPDX-License-Identifier: MIT
// Free-flight integration throughput: the substep kernels (velocities, then positions with the
// momentum-preserving rotation) over N bodies, at 1 and 2 threads, plus the store's bytes per
// body. Baseline in the same run: the same bodies with isotropic inertia (no gyroscopic work).
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <random>
#include <vector>

#include "core/base/body_store.hpp"
#include "core/base/parallel.hpp"
#include "solver/integrate.hpp"

namespace {

using namespace elan;
using namespace elan::detail;

struct Bodies {
  BodyStore store;
  std::vector<SolverBody> packets;
  std::vector<SolverBodyMass> masses;
};

// N tumbling boxes (half extents 0.1/0.3/0.6 when `anisotropic`, else cubes), packets 1..N.
Bodies make_bodies(std::size_t n, bool anisotropic) {
  Bodies b;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  b.packets.resize(n + 1);
  b.masses.resize(n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = b.store.push_back();
    Quat q(1, u(rng), u(rng), u(rng));
    q.normalize();
    b.store.set_orientation(k, q);
    SolverBodyMass& p = b.masses[k + 1];
    p.body = uint32_t(k);
    p.inv_mass = 1;
    const Vec3 moments =
        anisotropic ? Vec3(Real(0.15), Real(0.12), Real(0.03)) : Vec3::Constant(Real(0.1));
    b.store.inv_ix[k] = 1 / moments.x();
    b.store.inv_iy[k] = 1 / moments.y();
    b.store.inv_iz[k] = 1 / moments.z();
    p.gyroscopic = anisotropic;
    b.packets[k + 1].w = Vec3(u(rng), u(rng), u(rng)) * Real(5);
  }
  return b;
}

void integrate(benchmark::State& state, bool anisotropic) {
  const std::size_t n = std::size_t(state.range(0));
  const int threads = int(state.range(1));
  Bodies b = make_bodies(n, anisotropic);
  tbb::task_arena arena(threads);
  const Real h = Real(1.0 / 240.0);
  constexpr std::size_t kGrain = 1024;
  for (auto _ : state) {
    arena.execute([&] {
      for_blocks(n, kGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
        integrate_velocities(b.packets, b.masses, b.store, Vec3(0, Real(-9.81), 0), h,
                             uint32_t(begin + 1), uint32_t(end + 1));
        integrate_positions(b.packets, b.masses, b.store, h, uint32_t(begin + 1),
                            uint32_t(end + 1));
      });
    });
    benchmark::DoNotOptimize(b.packets.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(n));
  state.counters["bytes_per_body"] = double(b.store.bytes_per_body());
}

void BM_IntegrateAnisotropic(benchmark::State& s) {
  integrate(s, true);
}
void BM_IntegrateIsotropic(benchmark::State& s) {
  integrate(s, false);
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int n : {10'000, 100'000, 1'000'000}) {
    for (int t : {1, 2}) b->Args({n, t});
  }
  b->ArgNames({"bodies", "threads"})->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_IntegrateIsotropic)->Apply(sizes);
BENCHMARK(BM_IntegrateAnisotropic)->Apply(sizes);

}  // namespace

BENCHMARK_MAIN();
