// SPDX-License-Identifier: MIT
// What recording a program costs per step (elan/recorder.hpp): a program drives pile4k between
// steps (impulses on eight bodies and a velocity every step, a body created and one destroyed
// every 30), stepped without recording, recording with keyframes every 60 steps (the default),
// and recording without keyframes. Each iteration is one step with the program's calls before
// it. BM_StateHash and BM_Keyframe time the recorder's own work per step and per keyframe.
// Run: bench_api_recording --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>
#include <vector>

#include "elan/recorder.hpp"
#include "elan/scene.hpp"
#include "elan/snapshot.hpp"

namespace {

using namespace elan;

constexpr Real kDt = Real(1.0 / 60.0);
constexpr int kWarmSteps = 30;

enum Mode : int64_t { kOff = 0, kKeyframes = 1, kNoKeyframes = 2 };

// The program's calls before step `step`: deterministic in the step number.
void drive(World& w, uint64_t step, ShapeId ball, std::vector<BodyId>& made) {
  const std::size_t n = w.body_count();
  for (uint64_t k = 0; k < 8; ++k) {
    const BodyId id = w.body_at(std::size_t((step * 131 + k * 977) % n));
    w.apply_impulse(id, Vec3(Real(0.01), Real(0.02), 0), w.position(id));
  }
  w.set_linear_velocity(w.body_at(std::size_t(step * 7919 % n)), Vec3(0, Real(0.1), 0));
  if (step % 30 == 0) {
    BodyDef d;
    d.shape = ball;
    d.position = Vec3(Real(step % 17), Real(30), Real(step % 13));
    made.push_back(w.create_body(d));
    if (made.size() > 4) {
      w.destroy_body(made.front());
      made.erase(made.begin());
    }
  }
}

void BM_ProgramStep(benchmark::State& state) {
  const Mode mode = Mode(state.range(0));
  const Scene scene = load_scene(std::string(ELAN_SCENE_DIR) + "/pile4k.json");
  WorldDef def = scene.world;
  def.threads = int(state.range(1));
  World w(def);
  load_into(scene, w, "pile4k.json");
  ShapeDef s;
  s.type = ShapeType::Sphere;
  s.radius = Real(0.3);
  const ShapeId ball = w.create_shape(s);
  std::vector<BodyId> made;
  uint64_t step = 0;
  for (; step < kWarmSteps; ++step) {
    drive(w, step, ball, made);
    w.step(kDt);
  }
  if (mode != kOff) {
    RecordOptions options;
    options.keyframe_every = mode == kKeyframes ? 60 : 0;
    start_recording(w, options);
  }
  for (auto _ : state) {
    drive(w, step, ball, made);
    w.step(kDt);
    ++step;
  }
  if (mode != kOff) {
    const std::vector<uint8_t> bytes = stop_recording(w);
    state.counters["recording_bytes_per_step"] = double(bytes.size()) / double(state.iterations());
  }
}
BENCHMARK(BM_ProgramStep)
    ->ArgNames({"mode", "threads"})
    ->ArgsProduct({{kOff, kKeyframes, kNoKeyframes}, {1, 2}})
    ->Iterations(240)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The recorder's own work per step, apart from the step: the state hash it stores after every
// step, and the snapshot it keeps as a keyframe (once every keyframe_every steps).
World settled_pile() {
  const Scene scene = load_scene(std::string(ELAN_SCENE_DIR) + "/pile4k.json");
  World w(scene.world);
  load_into(scene, w, "pile4k.json");
  for (int i = 0; i < kWarmSteps; ++i) w.step(kDt);
  return w;
}

void BM_StateHash(benchmark::State& state) {
  World w = settled_pile();
  for (auto _ : state) benchmark::DoNotOptimize(w.state_hash());
}
BENCHMARK(BM_StateHash)->Unit(benchmark::kMicrosecond);

void BM_Keyframe(benchmark::State& state) {
  World w = settled_pile();
  for (auto _ : state) benchmark::DoNotOptimize(save_snapshot(w));
}
BENCHMARK(BM_Keyframe)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
