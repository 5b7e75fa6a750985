// SPDX-License-Identifier: MIT
// Building the triangle mesh of a 1M-triangle terrain grid (validation, active edges, the tree and
// the leaf order) on one thread; items = triangles; the counter bytes/tri is the built mesh's.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/base/triangle_mesh.hpp"

namespace {

using elan::Real;
using elan::Vec3;
using namespace elan::detail;

// A terrain of n x n cells, 1 m apart, two triangles a cell: 2 n^2 triangles.
struct Terrain {
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
};

Terrain terrain(uint32_t n) {
  Terrain t;
  t.vertices.reserve(std::size_t(n + 1) * (n + 1));
  for (uint32_t j = 0; j <= n; ++j) {
    for (uint32_t i = 0; i <= n; ++i) {
      const double h = 3 * std::sin(0.05 * i) * std::cos(0.07 * j) + 0.2 * std::sin(0.9 * i + j);
      t.vertices.emplace_back(Real(i), Real(h), Real(j));
    }
  }
  t.triangles.reserve(2 * std::size_t(n) * n);
  for (uint32_t j = 0; j < n; ++j) {
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i;
      t.triangles.push_back({a, a + n + 2, a + 1});
      t.triangles.push_back({a, a + n + 1, a + n + 2});
    }
  }
  return t;
}

void BM_BuildTerrainMesh(benchmark::State& state) {
  const Terrain t = terrain(uint32_t(state.range(0)));
  double bytes = 0;
  for (auto _ : state) {
    const TriangleMesh mesh = build_triangle_mesh(t.vertices, t.triangles);
    bytes = double(mesh_bytes(mesh)) / double(mesh.size());
    benchmark::DoNotOptimize(mesh.tree.nodes.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(t.triangles.size()));
  state.counters["bytes/tri"] = bytes;
}
// 708 x 708 cells: 1,002,528 triangles.
BENCHMARK(BM_BuildTerrainMesh)->ArgName("cells")->Arg(708)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
