// SPDX-License-Identifier: MIT
// Scene queries of the public API: ray casts and box overlaps against the world's bodies.
#pragma once

#include "elan/ids.hpp"
#include "elan/math.hpp"

namespace elan {

/// Where a ray enters a body's shape. A ray that starts inside a shape does not hit that shape.
struct RayHit {
  BodyId body;
  Real distance = 0;            ///< m along the (normalised) direction from the origin
  Vec3 point = Vec3::Zero();    ///< m, world: origin + distance * direction
  Vec3 normal = Vec3::UnitY();  ///< unit, world: the surface's outward normal at the point
};

}  // namespace elan
