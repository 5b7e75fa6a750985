// SPDX-License-Identifier: MIT
// Ray casts against one shape, in closed form per shape type: the kernel of World::cast_ray.
#pragma once

#include "core/base/shape.hpp"

namespace elan::detail {

struct ShapeRayHit {
  Real distance = 0;            // m along the unit direction
  Vec3 normal = Vec3::UnitY();  // unit, world, outward
};

// Where the ray origin + t * dir (dir unit, world) first enters `shape` at principal-frame pose
// `pose`, for t in [0, max_distance]. False when it misses or starts inside the shape.
bool ray_shape(const Shape& shape, const Transform& pose, const Vec3& origin, const Vec3& dir,
               Real max_distance, ShapeRayHit& out);

}  // namespace elan::detail
