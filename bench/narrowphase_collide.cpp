// SPDX-License-Identifier: MIT
// Narrowphase micro-benchmarks: collide() calls per second per shape pair type, and a whole
// collide_pairs() pass over a settled-pile-like layout at 1 and 2 threads.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <vector>

#include "core/base/pair_key.hpp"
#include "narrowphase/collide.hpp"

namespace elan::detail {
namespace {

Shape shape_of(ShapeType type, Real size) {
  ShapeDef d;
  d.type = type;
  d.radius = size;
  d.half_height = size;
  d.half_extents = Vec3::Constant(size);
  return make_shape(d);
}

Shape round_hull(int n, Real radius) {
  ShapeDef d;
  d.type = ShapeType::ConvexHull;
  for (int i = 0; i < n; ++i) {
    const double y = 1 - 2 * (i + 0.5) / n;
    const double r = std::sqrt(1 - y * y), t = 2.399963229728653 * i;
    d.points.emplace_back(Real(radius * r * std::cos(t)), Real(radius * y),
                          Real(radius * r * std::sin(t)));
  }
  return make_shape(d);
}

// A resting-like pose: B above A, slightly penetrating and tilted, so every routine does its
// full work (all axes, clipping, reduction).
void run_pair(benchmark::State& state, const Shape& a, const Shape& b) {
  const Transform xa{Vec3::Zero(), Quat::Identity()};
  const Real gap = a.local_max.y() - b.local_min.y() - Real(0.01);
  const Transform xb{Vec3(Real(0.05), gap, Real(-0.03)),
                     Quat(Eigen::AngleAxis<Real>(Real(0.02), Vec3(1, 0, 1).normalized()))};
  Manifold m;
  for (auto _ : state) {
    benchmark::DoNotOptimize(collide(a, xa, b, xb, Real(0.02), m));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
}

void BM_SphereSphere(benchmark::State& s) {
  const Shape a = shape_of(ShapeType::Sphere, Real(0.5));
  run_pair(s, a, a);
}
void BM_BoxBox(benchmark::State& s) {
  const Shape a = shape_of(ShapeType::Box, Real(0.5));
  run_pair(s, a, a);
}
void BM_CapsuleBox(benchmark::State& s) {
  const Shape box = shape_of(ShapeType::Box, Real(0.5));
  const Shape cap = shape_of(ShapeType::Capsule, Real(0.3));
  run_pair(s, box, cap);
}
void BM_CylinderBox(benchmark::State& s) {
  const Shape box = shape_of(ShapeType::Box, Real(0.5));
  const Shape cyl = shape_of(ShapeType::Cylinder, Real(0.4));
  run_pair(s, box, cyl);
}
void BM_HullHull(benchmark::State& s) {
  const Shape h = round_hull(int(s.range(0)), Real(0.5));
  run_pair(s, h, h);
}
BENCHMARK(BM_SphereSphere);
BENCHMARK(BM_BoxBox);
BENCHMARK(BM_CapsuleBox);
BENCHMARK(BM_CylinderBox);
BENCHMARK(BM_HullHull)->Arg(8)->Arg(32)->Arg(128);

// Settled-pile-like layout: a grid of mixed shapes (boxes, spheres, capsules, 32-vertex hulls)
// in layers, each touching its neighbours and the layer below, on a static ground box.
struct Layout {
  BodyStore bodies;
  std::vector<Shape> shapes;
  std::vector<uint64_t> pairs;
};

Layout make_layout(int side, int layers) {
  Layout l;
  l.shapes = {shape_of(ShapeType::Box, Real(100)), shape_of(ShapeType::Box, Real(0.5)),
              shape_of(ShapeType::Sphere, Real(0.5)), shape_of(ShapeType::Capsule, Real(0.3)),
              round_hull(32, Real(0.5))};
  const uint32_t g = uint32_t(l.bodies.push_back());
  l.bodies.motion[g] = uint8_t(MotionType::Static);
  l.bodies.set_position(g, Vec3(0, -100, 0));
  const Real pitch = Real(0.995);  // neighbours overlap by 5 mm
  for (int y = 0; y < layers; ++y) {
    for (int z = 0; z < side; ++z) {
      for (int x = 0; x < side; ++x) {
        const uint32_t b = uint32_t(l.bodies.push_back());
        l.bodies.motion[b] = uint8_t(MotionType::Dynamic);
        l.bodies.shape[b] = 1 + uint32_t((x + 2 * z + 3 * y) % 4);
        const Real tilt = Real(0.01) * Real((x * 7 + z * 3) % 5);
        l.bodies.set_position(
            b, Vec3(Real(x) * pitch, Real(0.495) + Real(y) * pitch, Real(z) * pitch));
        l.bodies.set_orientation(b, Quat(Eigen::AngleAxis<Real>(tilt, Vec3::UnitY())));
      }
    }
  }
  const auto index = [&](int x, int y, int z) { return uint32_t(1 + (y * side + z) * side + x); };
  for (int y = 0; y < layers; ++y) {
    for (int z = 0; z < side; ++z) {
      for (int x = 0; x < side; ++x) {
        const uint32_t i = index(x, y, z);
        if (y == 0) l.pairs.push_back(make_pair_key(0, i));
        for (int dz = -1; dz <= 1; ++dz) {
          for (int dx = -1; dx <= 1; ++dx) {
            for (int dy = 0; dy <= 1; ++dy) {
              const int nx = x + dx, ny = y + dy, nz = z + dz;
              if (nx < 0 || nz < 0 || nx >= side || nz >= side || ny >= layers) continue;
              const uint32_t j = index(nx, ny, nz);
              if (j > i) l.pairs.push_back(make_pair_key(i, j));
            }
          }
        }
      }
    }
  }
  std::sort(l.pairs.begin(), l.pairs.end());
  return l;
}

void BM_CollidePairsPile(benchmark::State& state) {
  const Layout l = make_layout(20, 10);  // 4000 bodies, like scenes/pile4k.json
  tbb::task_arena arena(int(state.range(0)));
  CollideSettings settings;
  ContactStore contacts;
  arena.execute([&] { collide_pairs(l.pairs, l.bodies, l.shapes, settings, {}, contacts); });
  for (auto _ : state) {
    // The poses stay, so each pass updates the list the pass before left, as a step would. The
    // separation cache starts empty each pass: with poses that stay it would skip every pair
    // apart, and this measures the exact tests.
    contacts.clear_apart();
    arena.execute([&] { collide_pairs(l.pairs, l.bodies, l.shapes, settings, {}, contacts); });
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(l.pairs.size()));
  state.counters["pairs"] = double(l.pairs.size());
  state.counters["contacts"] = double(contacts.size());
}
BENCHMARK(BM_CollidePairsPile)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace elan::detail

BENCHMARK_MAIN();
