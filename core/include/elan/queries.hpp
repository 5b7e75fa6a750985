// SPDX-License-Identifier: MIT
// Scene queries of the public API: what a query hits and how it is filtered. The calls are
// World's const members (ray, shape cast, overlap, point, character mover); all may run from any
// number of threads at once between steps, and none changes the world.
#pragma once

#include <cstdint>
#include <functional>

#include "elan/ids.hpp"
#include "elan/math.hpp"

namespace elan {

/// An axis-aligned box, world frame, m.
struct Aabb {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
};

/// Which bodies a query sees. A body passes when
/// `(body.category_bits & mask_bits) != 0 && (body.mask_bits & category_bits) != 0`
/// (Box2D's b2QueryFilter rule), it is not a sensor (unless `include_sensors`), and `accept`,
/// when set, returns true for it. `accept` is called from the querying thread (batched casts:
/// from the pool's workers, concurrently), must be thread-safe and deterministic, and must not
/// call back into the world's non-const members.
struct QueryFilter {
  uint32_t category_bits = UINT32_MAX;  ///< what the query is
  uint32_t mask_bits = UINT32_MAX;      ///< what it hits
  bool include_sensors = false;
  std::function<bool(BodyId)> accept;
};

/// Where a ray enters a body's shape. A ray that starts inside a shape does not hit that shape.
/// In a batched cast, a ray that hit nothing has a null `body`.
struct RayHit {
  BodyId body;
  Real distance = 0;            ///< m along the (normalised) direction from the origin
  Vec3 point = Vec3::Zero();    ///< m, world: origin + distance * direction
  Vec3 normal = Vec3::UnitY();  ///< unit, world: the surface's outward normal at the point
};

/// One ray of a batched cast.
struct Ray {
  Vec3 origin = Vec3::Zero();       ///< m, world
  Vec3 direction = Vec3::UnitX();   ///< any non-zero length
  Real max_distance = Real(1e30f);  ///< m
};

/// First contact of a shape swept along a translation.
struct ShapeCastHit {
  BodyId body;
  /// In [0, 1]: the shape first touches the body at start + fraction * translation. 0 when it
  /// overlaps at the start (then point and normal are those of the deepest overlap).
  Real fraction = 0;
  Vec3 point = Vec3::Zero();    ///< m, world: the contact point at that time
  Vec3 normal = Vec3::UnitY();  ///< unit, world: from the body towards the cast shape
};

/// The closest point of a body's surface to a query point.
struct PointHit {
  BodyId body;
  Vec3 point = Vec3::Zero();  ///< m, world, on the body's surface
  /// m: distance from the query point to `point`, negative when the query point is inside the
  /// body's solid (meshes and heightfields have no inside: always >= 0 for them)
  Real distance = 0;
  Vec3 normal = Vec3::UnitY();  ///< unit, world: the surface's outward normal at `point`
};

/// Settings of World::move_character: a vertical capsule (axis along -gravity, or +y when
/// gravity is zero) moved by a desired displacement, sliding along what it meets (Box2D's
/// b2World_CastMover, Jolt's CharacterVirtual, simplified).
struct CharacterMoveDef {
  Real radius = Real(0.3);                   ///< m, > 0
  Real half_height = Real(0.6);              ///< m, >= 0: half the segment between the cap centres
  Real step_height = Real(0.3);              ///< m, >= 0: steps up to this high are climbed
  Real max_slope = Real(0.785398163397448);  ///< rad in [0, pi/2): steeper ground is a wall
  Real skin = Real(0.01);                    ///< m, > 0: gap kept to every surface
  int max_iterations = 4;                    ///< slide iterations, >= 1
  QueryFilter filter;  ///< what the capsule collides with (exclude the character)
};

/// Result of World::move_character.
struct CharacterMoveResult {
  Vec3 position = Vec3::Zero();  ///< m, world: the capsule's centre after the move
  bool on_ground = false;        ///< resting on ground no steeper than max_slope
  Vec3 ground_normal = Vec3::UnitY();
  BodyId ground_body;  ///< null when not on ground
};

}  // namespace elan
