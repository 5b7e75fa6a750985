// SPDX-License-Identifier: MIT
// Shape creation from pile4k's hull clouds (quickhull + mass properties) and support-function
// throughput per shape type, at 1 and 2 threads; items = shapes built / support queries.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "core/base/parallel.hpp"
#include "core/base/shape.hpp"

namespace {

using elan::Real;
using elan::ShapeDef;
using elan::ShapeType;
using elan::Vec3;
using namespace elan::detail;

constexpr std::size_t kSupportGrain = 1024;
const char* const kShapeNames[] = {"sphere", "box", "capsule", "cylinder", "hull8"};

const std::vector<ShapeDef>& pile_hull_defs() {
  static const std::vector<ShapeDef> defs = [] {
    std::ifstream in(std::string(ELAN_SCENE_DIR) + "/pile4k.json");
    const nlohmann::json scene = nlohmann::json::parse(in);
    std::vector<ShapeDef> out;
    for (const auto& body : scene.at("bodies")) {
      const auto& s = body.at("shape");
      if (s.at("type") != "convex_hull") continue;
      ShapeDef d;
      d.type = ShapeType::ConvexHull;
      for (const auto& p : s.at("points")) {
        d.points.emplace_back(p[0].get<Real>(), p[1].get<Real>(), p[2].get<Real>());
      }
      out.push_back(std::move(d));
    }
    return out;
  }();
  return defs;
}

void BM_MakeShapePileHulls(benchmark::State& state) {
  const std::vector<ShapeDef>& defs = pile_hull_defs();
  std::vector<Shape> out(defs.size());
  tbb::task_arena arena(int(state.range(0)));
  for (auto _ : state) {
    arena.execute([&] {
      // determinism: each block writes only its own slots.
      for_blocks(defs.size(), 16, [&](std::size_t b, std::size_t e, std::size_t) {
        for (std::size_t i = b; i < e; ++i) out[i] = make_shape(defs[i]);
      });
    });
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(defs.size()));
}
BENCHMARK(BM_MakeShapePileHulls)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime();

Shape bench_shape(int type) {
  ShapeDef d;
  d.type = ShapeType(type);
  d.radius = Real(0.4);
  d.half_height = Real(0.5);
  d.half_extents = Vec3(0.3f, 0.5f, 0.4f);
  if (d.type == ShapeType::ConvexHull) d = pile_hull_defs().front();
  return make_shape(d);
}

void BM_Support(benchmark::State& state) {
  const Shape shape = bench_shape(int(state.range(0)));
  state.SetLabel(kShapeNames[state.range(0)]);
  std::mt19937 rng(1);
  std::normal_distribution<Real> g(0, 1);
  std::vector<Vec3> dirs(1 << 14), out(dirs.size());
  for (Vec3& d : dirs) d = Vec3(g(rng), g(rng), g(rng));
  tbb::task_arena arena(int(state.range(1)));
  for (auto _ : state) {
    arena.execute([&] {
      for_blocks(dirs.size(), kSupportGrain, [&](std::size_t b, std::size_t e, std::size_t) {
        for (std::size_t i = b; i < e; ++i) out[i] = support(shape, dirs[i]);
      });
    });
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(dirs.size()));
}
// Shape types: 0 sphere, 1 box, 2 capsule, 3 cylinder, 4 hull (8 vertices, from pile4k).
BENCHMARK(BM_Support)
    ->ArgNames({"type", "threads"})
    ->ArgsProduct({{0, 1, 2, 3, 4}, {1, 2}})
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
