// SPDX-License-Identifier: MIT
// GJK and EPA throughput per shape pair (sphere-sphere, box-box, hulls of 8/32/128 vertices,
// capsule-box), cold vs warm-started GJK side by side, at 1 and 2 threads; items = queries.
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <random>
#include <vector>

#include "narrowphase/gjk.hpp"

namespace {

using elan::Quat;
using elan::Real;
using elan::ShapeDef;
using elan::ShapeType;
using elan::Transform;
using elan::Vec3;
using namespace elan::detail;

constexpr int kPoses = 1024;
constexpr int kGrain = 64;

enum Pair { SphereSphere, BoxBox, Hull8, Hull32, Hull128, CapsuleBox };
const char* const kPairNames[] = {"sphere_sphere", "box_box",         "hull8_hull8",
                                  "hull32_hull32", "hull128_hull128", "capsule_box"};

Shape make_hull(int n, std::mt19937& rng) {
  std::normal_distribution<double> g(0, 1);
  ShapeDef d;
  d.type = ShapeType::ConvexHull;
  // Points on a sphere, so every one is a hull vertex.
  for (int i = 0; i < n; ++i) {
    d.points.push_back(Vec3(Real(g(rng)), Real(g(rng)), Real(g(rng))).normalized() * Real(0.5));
  }
  return make_shape(d);
}

struct Workload {
  Shape a, b;
  std::vector<Transform> xa, xb;
  std::vector<Vec3> last_normal;  // the previous query's normal, for the warm start
};

// kPoses random relative poses at a centre distance `spread` (gaps for GJK, overlaps for EPA).
Workload make_workload(Pair pair, Real spread) {
  std::mt19937 rng(7 + int(pair));
  auto shape = [&](ShapeType t) {
    ShapeDef d;
    d.type = t;
    d.radius = Real(0.25);
    d.half_height = Real(0.4);
    d.half_extents = Vec3(0.5, 0.3, 0.4);
    return make_shape(d);
  };
  Workload w;
  switch (pair) {
    case SphereSphere:
      w.a = w.b = shape(ShapeType::Sphere);
      break;
    case BoxBox:
      w.a = w.b = shape(ShapeType::Box);
      break;
    case Hull8:
      w.a = make_hull(8, rng), w.b = make_hull(8, rng);
      break;
    case Hull32:
      w.a = make_hull(32, rng), w.b = make_hull(32, rng);
      break;
    case Hull128:
      w.a = make_hull(128, rng), w.b = make_hull(128, rng);
      break;
    case CapsuleBox:
      w.a = shape(ShapeType::Capsule), w.b = shape(ShapeType::Box);
      break;
  }
  std::normal_distribution<double> g(0, 1);
  auto rotation = [&] {
    return Quat(Real(g(rng)), Real(g(rng)), Real(g(rng)), Real(g(rng))).normalized();
  };
  const Real reach = w.a.bounding_radius + w.b.bounding_radius;
  for (int i = 0; i < kPoses; ++i) {
    Transform a, b;
    a.rotation = rotation();
    b.rotation = rotation();
    b.position = Vec3(Real(g(rng)), Real(g(rng)), Real(g(rng))).normalized() * (spread * reach);
    w.xa.push_back(a);
    w.xb.push_back(b);
    const GjkResult r = gjk_distance(w.a, a, w.b, b);
    w.last_normal.push_back(r.overlap ? Vec3::UnitY() : Vec3(r.point_b - r.point_a).normalized());
  }
  return w;
}

enum Query { GjkCold, GjkWarm, Epa };

void run(benchmark::State& state, Query query) {
  const Pair pair = Pair(state.range(0));
  const int threads = int(state.range(1));
  // GJK: centres at 1.1 x the summed bounding radii (near misses); EPA: at 0.5 x (overlaps).
  const Workload w = make_workload(pair, query == Epa ? Real(0.5) : Real(1.1));
  std::vector<Real> out(kPoses);
  tbb::task_arena arena(threads);
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, kPoses, kGrain), [&](const auto& r) {
        for (int i = r.begin(); i < r.end(); ++i) {
          if (query == Epa) {
            out[i] = epa_penetration(w.a, w.xa[i], w.b, w.xb[i]).depth;
          } else {
            const Vec3* warm = query == GjkWarm ? &w.last_normal[i] : nullptr;
            out[i] = gjk_distance(w.a, w.xa[i], w.b, w.xb[i], true, warm).distance;
          }
        }
      });
    });
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * kPoses);
  state.SetLabel(kPairNames[pair]);
}

void args(benchmark::internal::Benchmark* b) {
  for (int p = SphereSphere; p <= CapsuleBox; ++p) {
    for (int t : {1, 2}) b->Args({p, t});
  }
  b->ArgNames({"pair", "threads"})->UseRealTime();
}

// Baseline: GJK from the centre line; then the same queries warm-started from the last normal.
BENCHMARK_CAPTURE(run, gjk_cold, GjkCold)->Apply(args);
BENCHMARK_CAPTURE(run, gjk_warm, GjkWarm)->Apply(args);
BENCHMARK_CAPTURE(run, epa, Epa)->Apply(args);

}  // namespace

BENCHMARK_MAIN();
