// SPDX-License-Identifier: MIT
// What the polyhedron SAT (sat.cpp) and the capsule-polyhedron contact (capsule_polyhedron.cpp)
// share: the axis queries' results, the hysteresis between axes, the closest points of two
// segments, and storing a manifold's points.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "core/base/contact.hpp"

namespace elan::detail {

inline constexpr Real kLowest = std::numeric_limits<Real>::lowest();
// Hysteresis so the manifold does not flicker between nearly equal axes: B's face must beat A's,
// and an edge pair must beat the best face, by a relative plus an absolute margin (m).
inline constexpr Real kFaceRelTol = Real(0.02);
inline constexpr Real kEdgeRelTol = Real(0.05);
inline constexpr Real kAbsTol = Real(2.5e-4);
// Edge pairs closer to parallel than this (sine of the angle) are left to the face axes.
inline constexpr Real kParallelSine = Real(0.005);

struct FaceQuery {
  int face = -1;
  Real separation = kLowest;
};

struct EdgeQuery {
  int edge_a = -1;
  int edge_b = -1;
  Real separation = kLowest;
  Vec3 normal = Vec3::UnitY();
};

inline bool beats(Real candidate, Real incumbent, Real rel_tol) {
  return candidate > incumbent + rel_tol * std::abs(incumbent) + kAbsTol;
}

// Closest points of segments p1 + s d1 and p2 + t d2, s, t in [0, 1] (Ericson, Real-Time
// Collision Detection, 5.1.9), degenerate segments included.
void closest_points_segments(const Vec3& p1, const Vec3& d1, const Vec3& p2, const Vec3& d2,
                             Vec3& c1, Vec3& c2);

// Point k of `out`: its anchor (offset from A's centre), separation and feature id.
inline void set_point(Manifold& out, int k, const Vec3& p, Real separation, uint32_t id) {
  ContactPoint& c = out.points[k];
  c.anchor_a = p;
  c.separation = separation;
  c.feature_id = id;
}

// Stores the candidates (midpoints between the surfaces), reduced to four.
bool emit_points(const Vec3* points, const Real* separations, const uint32_t* ids, int count,
                 const Vec3& normal, Manifold& out);

}  // namespace elan::detail
