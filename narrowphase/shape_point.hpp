// SPDX-License-Identifier: MIT
// A point against one shape: the closest point of its surface, with the signed distance, and
// containment. The kernels of the scene queries' overlap_point and closest_point.
#pragma once

#include <limits>

#include "core/base/shape.hpp"

namespace elan::detail {

struct ShapePoint {
  Vec3 point = Vec3::Zero();  // world, on the surface
  // m: negative inside the solid (meshes and heightfields have none: >= 0). A compound's is the
  // least of its parts' (exact outside the union; inside, the depth in the deepest part).
  Real distance = 0;
  Vec3 normal = Vec3::UnitY();  // unit, world, outward at `point`
};

// The closest surface point of `shape` at principal-frame pose x to world point p. For a mesh or
// heightfield only the triangles within `max_distance` are looked at (infinite: all, by a search
// that widens until it finds one); false when none is that close.
bool closest_on_shape(const Shape& shape, const Transform& x, const Vec3& p, ShapePoint& out,
                      Real max_distance = std::numeric_limits<Real>::infinity());

// Whether world point p is in the solid (touching counts); meshes and heightfields contain none.
bool shape_contains(const Shape& shape, const Transform& x, const Vec3& p);

// The closest point of triangle abc to p: closest_on_triangle_to_origin (closest_on_triangle.hpp,
// Ericson's Voronoi regions) with the corners seen from p.
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace elan::detail
