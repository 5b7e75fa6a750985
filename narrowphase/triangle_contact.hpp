// SPDX-License-Identifier: MIT
// One convex shape against one triangle of a mesh or heightfield: the contact normal and points,
// speculative like the shape pairs, with Jolt's active edges so that a body sliding over a smooth
// surface made of many triangles does not catch on their shared edges (no ghost collisions).
#pragma once

#include <cstdint>

#include "core/base/contact.hpp"
#include "core/base/mesh_triangle.hpp"
#include "core/base/shape.hpp"

namespace elan::detail {

// A triangle's contact: one normal, at most four points (more are reduced with reduce_to_four).
struct TriangleContact {
  Vec3 normal = Vec3::UnitY();  // unit, surface frame, from A towards the triangle
  int count = 0;
  Vec3 points[kMaxManifoldPoints];  // m, surface frame, from A's centre: midway between surfaces
  Real separation[kMaxManifoldPoints];   // m, along `normal`: negative = penetration
  uint32_t feature[kMaxManifoldPoints];  // local to the triangle: combine with its index
};

// Convex A (sphere, box, capsule, cylinder, hull; `xa` its principal pose in the surface's frame)
// against triangle `t`. Points farther apart than `speculative_distance` are not reported.
// Returns out.count > 0.
//
// The normal: the closest features' (sphere: the closed-form closest point; others: GJK between
// the cores when apart, EPA when they overlap), replaced by the face normal (toward A's side)
// when the triangle's feature there is its face, an inactive edge, a vertex whose two edges are
// inactive, or a vertex whose normal leans out past an inactive edge; the separation is then
// measured along the face normal. A one-sided triangle (a heightfield's) gives nothing when A's
// centre is behind its plane. The points: A's supporting feature clipped against the triangle
// (or the triangle against A's face when that face is the better aligned), else the one point
// midway between the closest points.
bool collide_triangle(const Shape& a, const Transform& xa, const MeshTriangle& t,
                      Real speculative_distance, TriangleContact& out);

}  // namespace elan::detail
