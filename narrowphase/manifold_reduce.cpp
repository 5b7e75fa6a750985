// SPDX-License-Identifier: MIT
// Manifold reduction to four points: deepest, farthest, largest triangle, largest quadrilateral.
// The deepest point keeps the penetration; the area terms keep the support polygon wide so a
// resting body does not rock (the usual heuristic of Bullet's and Box2D's reducers).
#include "narrowphase/manifold_reduce.hpp"

#include <algorithm>
#include <cmath>

namespace elan::detail {

int reduce_to_four(std::span<const Vec3> positions, std::span<const Real> separations,
                   const Vec3& normal, int out_indices[kMaxManifoldPoints]) {
  const int n = static_cast<int>(positions.size());
  if (n <= kMaxManifoldPoints) {
    for (int i = 0; i < n; ++i) out_indices[i] = i;
    return n;
  }
  // determinism: every argmax uses a strict comparison, so ties keep the lower index.
  int i0 = 0;
  for (int i = 1; i < n; ++i) {
    if (separations[i] < separations[i0]) i0 = i;
  }
  const Vec3& p0 = positions[i0];
  auto planar = [&normal](const Vec3& v) { return v - normal * normal.dot(v); };
  int i1 = -1;
  Real best = 0;
  for (int i = 0; i < n; ++i) {
    const Real d = planar(positions[i] - p0).squaredNorm();
    if (d > best) best = d, i1 = i;
  }
  out_indices[0] = i0;
  if (i1 < 0) return 1;
  out_indices[1] = i1;
  const Vec3& p1 = positions[i1];
  // Twice the signed area of (p0, p1, q) seen along the normal.
  auto area = [&normal](const Vec3& a, const Vec3& b, const Vec3& q) {
    return (b - a).cross(q - a).dot(normal);
  };
  int i2 = -1;
  best = 0;
  for (int i = 0; i < n; ++i) {
    const Real s = std::abs(area(p0, p1, positions[i]));
    if (s > best) best = s, i2 = i;
  }
  if (i2 < 0) return 2;
  out_indices[2] = i2;
  // Orient the triangle counter-clockwise about the normal; a fourth point adds the area of the
  // triangle it forms with the edge it lies beyond (the negative signed area).
  int t[3] = {i0, i1, i2};
  if (area(p0, p1, positions[i2]) < 0) std::swap(t[1], t[2]);
  int i3 = -1;
  best = 0;
  for (int i = 0; i < n; ++i) {
    Real gain = 0;
    for (int e = 0; e < 3; ++e) {
      gain = std::max(gain, -area(positions[t[e]], positions[t[(e + 1) % 3]], positions[i]));
    }
    if (gain > best) best = gain, i3 = i;
  }
  if (i3 < 0) return 3;
  out_indices[3] = i3;
  return 4;
}

}  // namespace elan::detail
