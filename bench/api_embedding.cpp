// SPDX-License-Identifier: MIT
// The embedding API's costs: all poses of 1M bodies through bulk views vs per-body calls, ray
// casts into a settled pile10k, and 256 small worlds stepped with step_all vs one by one.
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "elan/elan.hpp"

namespace {

using namespace elan;

constexpr Real kDt = Real(1.0 / 60.0);

// 1M spheres on a lattice, built once (creation is not what is measured).
World& million() {
  static std::unique_ptr<World> w = [] {
    auto world = std::make_unique<World>(WorldDef{});
    ShapeDef s;
    s.type = ShapeType::Sphere;
    s.radius = Real(0.4);
    BodyDef d;
    d.shape = world->create_shape(s);
    for (int i = 0; i < 1000000; ++i) {
      d.position = Vec3(Real(i % 100), Real((i / 100) % 100), Real(i / 10000));
      world->create_body(d);
    }
    return world;
  }();
  return *w;
}

// Reads every centre of mass and orientation, shifts each position by 1 mm, writes it back.
void BM_PosesBulk(benchmark::State& state) {
  World& w = million();
  const std::size_t n = w.body_count();
  std::vector<Real> x(n), y(n), z(n);
  for (auto _ : state) {
    const World::BodyColumns c = w.body_columns();
    Real sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = c.px[i] + Real(0.001);
      y[i] = c.py[i];
      z[i] = c.pz[i];
      sum += c.qw[i] + c.qx[i] + c.qy[i] + c.qz[i];
    }
    benchmark::DoNotOptimize(sum);
    w.set_center_of_mass_positions(x, y, z);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(n));
}
BENCHMARK(BM_PosesBulk)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PosesPerBody(benchmark::State& state) {
  World& w = million();
  const std::span<const BodyId> ids = w.body_ids();
  const std::vector<BodyId> copy(ids.begin(), ids.end());
  for (auto _ : state) {
    Real sum = 0;
    for (const BodyId id : copy) {
      const Vec3 p = w.position(id);
      sum += w.orientation(id).w();
      w.set_position(id, p + Vec3(Real(0.001), 0, 0));
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(copy.size()));
}
BENCHMARK(BM_PosesPerBody)->Unit(benchmark::kMillisecond)->UseRealTime();

// pile10k after 300 steps, settled once per process.
World& settled_pile() {
  static std::unique_ptr<World> w = [] {
    const Scene scene = load_scene(std::string(ELAN_SCENE_DIR) + "/pile10k.json");
    WorldDef def = scene.world;
    def.threads = 2;
    auto world = std::make_unique<World>(def);
    load_into(scene, *world, "pile10k.json");
    for (int k = 0; k < 300; ++k) world->step(scene.timestep);
    return world;
  }();
  return *w;
}

// Vertical rays from above the pile at random spots of its footprint: closest hit.
void BM_RayCastPile10k(benchmark::State& state) {
  World& w = settled_pile();
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> u(-8, 8);
  std::vector<Vec3> origins(1024);
  for (Vec3& o : origins) o = Vec3(u(rng), 40, u(rng));
  std::size_t k = 0, hits = 0;
  for (auto _ : state) {
    const auto hit = w.cast_ray(origins[k++ % origins.size()], -Vec3::UnitY(), 100);
    hits += hit.has_value();
  }
  state.counters["hit_fraction"] = double(hits) / double(state.iterations());
  state.counters["bodies"] = double(w.body_count());
  state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_RayCastPile10k)->Unit(benchmark::kMicrosecond);

// 256 worlds of a floor and 49 falling boxes, each world's step run by `threads` workers.
std::vector<World> make_worlds(int threads) {
  std::vector<World> worlds;
  for (int k = 0; k < 256; ++k) {
    WorldDef def;
    def.threads = threads;
    World& w = worlds.emplace_back(def);
    ShapeDef ground, box;
    ground.type = box.type = ShapeType::Box;
    ground.half_extents = Vec3(10, 1, 10);
    box.half_extents = Vec3::Constant(Real(0.4));
    BodyDef floor;
    floor.motion = MotionType::Static;
    floor.shape = w.create_shape(ground);
    floor.position = Vec3(0, -1, 0);
    w.create_body(floor);
    BodyDef d;
    d.shape = w.create_shape(box);
    for (int i = 0; i < 49; ++i) {
      d.position = Vec3(Real(i % 4) - 1.5f, Real(0.5 + 0.9 * (i / 8)) + Real(k % 7) * 0.01f,
                        Real((i / 4) % 2) - 0.5f);
      w.create_body(d);
    }
    for (int s = 0; s < 30; ++s) w.step(kDt);  // into contact
  }
  return worlds;
}

void BM_ManyWorlds(benchmark::State& state) {
  const int threads = int(state.range(0));
  const bool together = state.range(1) != 0;
  std::vector<World> worlds = make_worlds(threads);
  std::vector<World*> ptrs;
  for (World& w : worlds) ptrs.push_back(&w);
  ThreadPool pool(threads);
  for (auto _ : state) {
    if (together) {
      step_all(ptrs, kDt, &pool);
    } else {
      for (World* w : ptrs) w->step(kDt);
    }
  }
  state.SetLabel(together ? "step_all" : "one_by_one");
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(worlds.size()));
}
BENCHMARK(BM_ManyWorlds)
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->ArgNames({"threads", "step_all"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
