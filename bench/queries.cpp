// SPDX-License-Identifier: MIT
// Scene queries on the query tree: closest-hit rays one at a time and batched (cast_rays on the
// world's pool at 1 and 2 threads), and sphere casts, into a packed pile and a sparse field of
// 1k, 10k and 100k bodies.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "elan/world.hpp"

namespace {

using namespace elan;

enum Layout { kPile = 0, kSparse = 1 };

// Pile: boxes and spheres of about 0.5 m on a jittered 0.5 m lattice, 10 layers deep over a
// square floor that grows with N, as a settled pile is. Sparse: the same bodies scattered at
// random through a cube holding about one body per 60 m^3. Both on a static floor box.
std::unique_ptr<World> make_world(int layout, int n, int threads) {
  WorldDef def;
  def.threads = threads;
  auto w = std::make_unique<World>(def);
  ShapeDef box, ball, floor;
  box.type = ShapeType::Box;
  box.half_extents = Vec3::Constant(0.24f);
  ball.radius = 0.25f;
  floor.type = ShapeType::Box;
  const ShapeId shapes[2] = {w->create_shape(box), w->create_shape(ball)};
  std::mt19937 rng(42);
  std::uniform_real_distribution<Real> jitter(-0.02f, 0.02f), unit(0, 1);
  const int side = int(std::ceil(std::sqrt(n / 10.0)));
  const Real extent = layout == kPile ? Real(side) * 0.5f : std::cbrt(Real(n) * 60);
  floor.half_extents = Vec3(extent / 2 + 1, 0.5f, extent / 2 + 1);
  BodyDef ground;
  ground.motion = MotionType::Static;
  ground.shape = w->create_shape(floor);
  ground.position = Vec3(0, -0.5f, 0);
  w->create_body(ground);
  BodyDef b;
  b.awake = false;
  for (int i = 0; i < n; ++i) {
    b.shape = shapes[i % 2];
    if (layout == kPile) {
      const int col = i % (side * side), layer = i / (side * side);
      b.position = Vec3((Real(col % side) + 0.5f) * 0.5f - extent / 2 + jitter(rng),
                        (Real(layer) + 0.5f) * 0.5f + jitter(rng),
                        (Real(col / side) + 0.5f) * 0.5f - extent / 2 + jitter(rng));
    } else {
      b.position =
          Vec3((unit(rng) - 0.5f) * extent, unit(rng) * extent, (unit(rng) - 0.5f) * extent);
    }
    w->create_body(b);
  }
  return w;
}

World& world(int layout, int n, int threads) {
  static std::map<std::tuple<int, int, int>, std::unique_ptr<World>> cache;
  auto& w = cache[{layout, n, threads}];
  if (!w) w = make_world(layout, n, threads);
  return *w;
}

// Pile: vertical rays from above at random spots of its footprint. Sparse: rays from random
// points in random directions, 20 m long.
std::vector<Ray> make_rays(int layout, int n, std::size_t count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> unit(0, 1), sym(-1, 1);
  const int side = int(std::ceil(std::sqrt(n / 10.0)));
  const Real extent = layout == kPile ? Real(side) * 0.5f : std::cbrt(Real(n) * 60);
  std::vector<Ray> rays(count);
  for (Ray& r : rays) {
    if (layout == kPile) {
      r = {Vec3((unit(rng) - 0.5f) * extent, 20, (unit(rng) - 0.5f) * extent), -Vec3::UnitY(), 100};
    } else {
      r = {Vec3((unit(rng) - 0.5f) * extent, unit(rng) * extent, (unit(rng) - 0.5f) * extent),
           Vec3(sym(rng), sym(rng), sym(rng)).normalized(), 20};
    }
  }
  return rays;
}

void BM_Ray(benchmark::State& state) {
  const int layout = int(state.range(0)), n = int(state.range(1));
  const World& w = world(layout, n, 1);
  const std::vector<Ray> rays = make_rays(layout, n, 4096);
  std::size_t k = 0, hits = 0;
  for (auto _ : state) {
    const Ray& r = rays[k++ & 4095];
    const auto hit = w.cast_ray(r.origin, r.direction, r.max_distance);
    hits += hit.has_value();
  }
  state.counters["hit_fraction"] = double(hits) / double(state.iterations());
  state.SetItemsProcessed(int64_t(state.iterations()));
}

void BM_RaysBatched(benchmark::State& state) {
  const int layout = int(state.range(0)), n = int(state.range(1)), threads = int(state.range(2));
  const World& w = world(layout, n, threads);
  const std::vector<Ray> rays = make_rays(layout, n, 4096);
  std::vector<RayHit> hits(rays.size());
  for (auto _ : state) {
    w.cast_rays(rays, hits);
    benchmark::DoNotOptimize(hits.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(rays.size()));
}

void BM_SphereCast(benchmark::State& state) {
  const int layout = int(state.range(0)), n = int(state.range(1));
  World& w = world(layout, n, 1);
  ShapeDef ball;
  ball.radius = 0.3f;
  static std::map<const World*, ShapeId> shape_of;
  if (!shape_of.count(&w)) shape_of[&w] = w.create_shape(ball);
  const ShapeId s = shape_of[&w];
  const std::vector<Ray> rays = make_rays(layout, n, 4096);
  std::size_t k = 0, hits = 0;
  for (auto _ : state) {
    const Ray& r = rays[k++ & 4095];
    const auto hit =
        w.cast_shape(s, {r.origin, Quat::Identity()}, r.direction * (r.max_distance / 4));
    hits += hit.has_value();
  }
  state.counters["hit_fraction"] = double(hits) / double(state.iterations());
  state.SetItemsProcessed(int64_t(state.iterations()));
}

}  // namespace

int main(int argc, char** argv) {
  for (int64_t layout : {kPile, kSparse}) {
    for (int64_t n : {1000, 10000, 100000}) {
      benchmark::RegisterBenchmark("ray", BM_Ray)
          ->Args({layout, n})
          ->ArgNames({"sparse", "n"})
          ->Unit(benchmark::kMicrosecond);
      for (int64_t t : {1, 2}) {
        benchmark::RegisterBenchmark("rays_batched_4096", BM_RaysBatched)
            ->Args({layout, n, t})
            ->ArgNames({"sparse", "n", "threads"})
            ->Unit(benchmark::kMicrosecond)
            ->UseRealTime();
      }
      benchmark::RegisterBenchmark("sphere_cast", BM_SphereCast)
          ->Args({layout, n})
          ->ArgNames({"sparse", "n"})
          ->Unit(benchmark::kMicrosecond);
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
