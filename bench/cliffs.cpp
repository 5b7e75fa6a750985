// SPDX-License-Identifier: MIT
// Performance cliffs of valid scenes (issue 42), each paired with an ordinary scene of the same
// size: bodies spawned at one point against the same bodies in a row or a pile, and hulls of 200
// points against hulls of 400 (GJK/EPA) and against boxes. The cliff is in the first steps, while
// the spawned bodies still overlap, so each case times the first kSteps steps of a fresh world
// (one thread), reported as ms per step; the piles whose bodies fall for a second before they
// touch are timed after 120 steps (240 for the cylinders, which roll longer), the settled pile
// of cylinders from its first step. Scene files: bench/cliffs/, and scenes/ for the piles.
//
// 10,000 boxes at one point (50 million pairs in the first step, more memory than this machine
// has) run only with ELAN_BENCH_CLIFF_10K=1 in the environment.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstdlib>
#include <string>

#include "elan/scene.hpp"
#include "elan/world.hpp"

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kSteps = 10;

std::string path_of(const std::string& name) {
  const std::string scenes = ELAN_SCENE_DIR;
  if (name.rfind("scenes/", 0) == 0) return scenes + "/" + name.substr(7) + ".json";
  return scenes + "/../bench/cliffs/" + name + ".json";
}

// One iteration: a fresh world from the file, then kSteps steps, timed.
void bm_first_steps(benchmark::State& state, const std::string& name, int warmup) {
  const elan::Scene scene = elan::load_scene(path_of(name));
  tbb::task_arena arena(1);
  for (auto _ : state) {
    double seconds = 0;
    arena.execute([&] {
      elan::WorldDef def = scene.world;
      def.threads = 1;
      elan::World world(def);
      elan::load_into(scene, world, name);
      for (int i = 0; i < warmup; ++i) world.step(scene.timestep);
      const auto t0 = Clock::now();
      for (int i = 0; i < kSteps; ++i) world.step(scene.timestep);
      seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      state.counters["contacts"] = double(world.last_step().contacts);
    });
    state.SetIterationTime(seconds / kSteps);
  }
}

void add(const std::string& name, int reps, int warmup = 0) {
  benchmark::RegisterBenchmark(("cliff/" + name).c_str(), bm_first_steps, name, warmup)
      ->UseManualTime()
      ->Iterations(1)
      ->Repetitions(reps)
      ->Unit(benchmark::kMillisecond);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  // Each cliff, then the ordinary scene it is paired with.
  add("cylinders500_one_point", 1);
  // The fair pair: 500 of the same cylinders in a settled pile (bench/make_cylinder_pile.py),
  // from a fresh world like the cliff (no warm start, no caches), and the pile they settled
  // from, after its 240 steps of falling and settling (warm); the row has 30 times fewer
  // contacts.
  add("cylinders500_pile", 3);
  add("cylinders500_pile_drop", 3, 240);
  add("cylinders500_row", 3);
  add("boxes100_one_point", 3);
  add("boxes100_grid", 3);
  add("boxes1000_one_point", 1);
  add("scenes/pile1k", 3, 120);
  add("hulls20_200pts", 3);
  add("hulls20_400pts", 3);
  add("boxes20", 3);
  const char* big = std::getenv("ELAN_BENCH_CLIFF_10K");
  if (big != nullptr && std::string(big) == "1") {
    add("boxes10k_one_point", 1);
    add("scenes/pile10k", 1, 120);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
