// SPDX-License-Identifier: MIT
// Snapshots on pile10k after 60 steps (many contacts): save and restore time and bytes per body
// for full snapshots and compact rollback states, and the cost of recording (a state hash every
// step) as a ratio to a plain step on pile1k, at 1 and 2 threads. Items = bodies.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "core/world/world_access.hpp"
#include "elan/scene.hpp"
#include "elan/snapshot.hpp"
#include "elan/world.hpp"

namespace {

using elan::Real;
using elan::World;

constexpr Real kDt = Real(1.0 / 60.0);

World load(const char* name, int threads, int steps) {
  const std::string path = std::string(ELAN_SCENE_DIR) + "/" + name;
  const elan::Scene scene = elan::load_scene(path);
  elan::WorldDef def = scene.world;
  def.threads = threads;
  World world(def);
  elan::load_into(scene, world, path);
  for (int s = 0; s < steps; ++s) world.step(kDt);
  return world;
}

// pile10k after 60 steps, built once: loading and stepping it takes seconds.
World& pile10k() {
  static World world = load("pile10k.json", 2, 60);
  return world;
}

void report_size(benchmark::State& state, const World& world, std::size_t bytes) {
  const double bodies = double(world.body_count());
  state.counters["bytes"] = double(bytes);
  state.counters["bytes_per_body"] = double(bytes) / bodies;
  state.counters["manifolds"] = double(elan::detail::state_of(world).contacts.size());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(world.body_count()));
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(bytes));
}

void BM_SaveSnapshot(benchmark::State& state) {
  const World& world = pile10k();
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::vector<uint8_t> out = elan::save_snapshot(world);
    bytes = out.size();
    benchmark::DoNotOptimize(out.data());
  }
  report_size(state, world, bytes);
}

void BM_RestoreSnapshot(benchmark::State& state) {
  const std::vector<uint8_t> bytes = elan::save_snapshot(pile10k());
  World target;
  for (auto _ : state) elan::restore_snapshot(target, bytes);
  report_size(state, target, bytes.size());
}

void BM_SaveRollback(benchmark::State& state) {
  const World& world = pile10k();
  std::vector<uint8_t> out;
  for (auto _ : state) {
    elan::save_rollback(world, out);
    benchmark::DoNotOptimize(out.data());
  }
  report_size(state, world, out.size());
  // The bodies' share: 81 bytes per non-static body; the rest is contacts and framing.
  std::size_t moving = 0;
  for (std::size_t i = 0; i < world.body_count(); ++i) {
    moving += !elan::detail::state_of(world).bodies.is_static(i);
  }
  state.counters["body_bytes_per_moving_body"] = double(20 * sizeof(Real) + 1);
  state.counters["contact_bytes"] = double(out.size()) - double(moving * (20 * sizeof(Real) + 1));
}

void BM_RestoreRollback(benchmark::State& state) {
  World& world = pile10k();
  const std::vector<uint8_t> bytes = elan::save_rollback(world);
  for (auto _ : state) elan::restore_rollback(world, bytes);
  report_size(state, world, bytes.size());
}

// One step of pile1k (settling, 200 steps in), with or without the state hash a recording
// takes after every step; the world is rolled back every 50 steps so the work stays alike.
void step_pile1k(benchmark::State& state, bool hash) {
  World world = load("pile1k.json", int(state.range(0)), 200);
  std::vector<uint8_t> start;
  elan::save_rollback(world, start);
  uint64_t h = 0;
  int since = 0;
  double hash_seconds = 0;
  for (auto _ : state) {
    if (++since == 50) {
      state.PauseTiming();
      elan::restore_rollback(world, start);
      since = 0;
      state.ResumeTiming();
    }
    world.step(kDt);
    if (hash) {
      const auto t0 = std::chrono::steady_clock::now();
      h ^= world.state_hash();
      hash_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
  }
  benchmark::DoNotOptimize(h);
  if (hash) state.counters["hash_us_per_step"] = 1e6 * hash_seconds / double(state.iterations());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(world.body_count()));
}

void BM_StepPlain(benchmark::State& state) {
  step_pile1k(state, false);
}
void BM_StepRecording(benchmark::State& state) {
  step_pile1k(state, true);
}

}  // namespace

BENCHMARK(BM_SaveSnapshot)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RestoreSnapshot)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SaveRollback)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RestoreRollback)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_StepPlain)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_StepRecording)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
