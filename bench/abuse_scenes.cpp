// SPDX-License-Identifier: MIT
// Whole steps of the abuse scenes (scenes/abuse/, bench/make_abuse_scenes.py) at 1 and 2 threads:
// the mean and the worst step time of a run from the first step (the worst is usually an early
// one: overlapping spawns, the first impacts), to compare with reference_pile100, the normal pile
// of spawn100's size. tests/physics/abuse_scenes.cpp checks that they stay finite and bounded.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <string>

#include "elan/scene.hpp"
#include "elan/world.hpp"

namespace {

using Clock = std::chrono::steady_clock;

void bm_abuse(benchmark::State& state, const std::string& name, int threads, int steps) {
  const std::string path = std::string(ELAN_SCENE_DIR) + "/abuse/" + name + ".json";
  const elan::Scene scene = elan::load_scene(path);
  double worst = 0, total = 0;
  int timed = 0;
  for (auto _ : state) {
    state.PauseTiming();
    elan::WorldDef def = scene.world;
    def.threads = threads;
    elan::World world(def);
    elan::load_into(scene, world, path);
    state.ResumeTiming();
    for (int k = 0; k < steps; ++k) {
      const auto t0 = Clock::now();
      world.step(scene.timestep);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      worst = std::max(worst, ms);
      total += ms;
      ++timed;
    }
    benchmark::DoNotOptimize(world.state_hash());
  }
  state.counters["ms_per_step"] = timed ? total / timed : 0;
  state.counters["worst_step_ms"] = worst;
  state.counters["steps"] = steps;
}

}  // namespace

int main(int argc, char** argv) {
  const char* names[] = {"reference_pile100", "spawn100",    "tiny_on_huge",
                         "heavy_on_light",    "fast_bodies", "high_gravity"};
  for (const char* name : names) {
    for (int threads : {1, 2}) {
      benchmark::RegisterBenchmark(
          ("abuse/" + std::string(name) + "/threads:" + std::to_string(threads)).c_str(),
          [name, threads](benchmark::State& s) { bm_abuse(s, name, threads, 300); })
          ->Unit(benchmark::kMillisecond)
          ->Iterations(3);
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
