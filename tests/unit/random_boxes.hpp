// SPDX-License-Identifier: MIT
// Test helpers of the tree tests (bvh.cpp, bvh4.cpp): random item boxes, and the exact slab test
// of a ray against one box, the brute force's answer.
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "core/base/bvh.hpp"

namespace elan::detail::tree_test {

using RealDistribution = std::uniform_real_distribution<Real>;

// One box: each coordinate of its centre drawn from `pos`, each half size from `size`.
inline Aabb random_box(std::mt19937& rng, RealDistribution& pos, RealDistribution& size) {
  const Vec3 c{pos(rng), pos(rng), pos(rng)};
  const Vec3 h{size(rng), size(rng), size(rng)};
  return {c - h, c + h};
}

// n boxes, centres uniform in [-spread, spread]^3, half sizes in [0.01, 3].
inline std::vector<Aabb> random_boxes(std::size_t n, uint32_t seed, Real spread = 50) {
  std::mt19937 rng(seed);
  RealDistribution pos(-spread, spread), size(0.01f, 3);
  std::vector<Aabb> boxes(n);
  for (Aabb& b : boxes) b = random_box(rng, pos, size);
  return boxes;
}

// Slab test of a Real box, as the brute force's exact ray-box distance; -1 for a miss.
inline Real ray_box(const Aabb& b, const Vec3& o, const Vec3& d, Real max_t) {
  Real t0 = 0, t1 = max_t;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < b.min[a] || o[a] > b.max[a]) return -1;
      continue;
    }
    Real ta = (b.min[a] - o[a]) / d[a], tb = (b.max[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return -1;
  }
  return t0;
}

}  // namespace elan::detail::tree_test
