// SPDX-License-Identifier: MIT
// GJK distance between two convex shapes (core shapes: sphere and capsule radii are applied
// afterwards), using the support of the Minkowski difference without building it.
#pragma once

#include "core/base/shape.hpp"

namespace elan::detail {

struct GjkResult {
  Real distance = 0;            // m, between the core shapes (0 when they overlap)
  Vec3 point_a = Vec3::Zero();  // world: closest point on A's core
  Vec3 point_b = Vec3::Zero();  // world: closest point on B's core
  bool overlap = false;         // cores intersect: use EPA for depth
  // m: the shapes are at least this far apart (the gap along the last search direction, which
  // any axis bounds from below); 0 when they overlap. Within the relative tolerance of
  // `distance` when GJK converged.
  Real lower_bound = 0;
  int iterations = 0;
  // The search stopped early: the lower bound passed the distance the caller rejects beyond
  // (gjk_triangle's and gjk_contact's `reject_beyond`); distance and points are not set,
  // lower_bound is.
  bool beyond = false;
};

// `include_radius` false treats spheres as points and capsules as segments (their "core").
// `initial_direction`, if given, points from A towards B (e.g. last step's normal): the warm start.
GjkResult gjk_distance(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                       bool include_radius = true, const Vec3* initial_direction = nullptr);

struct EpaResult {
  Real depth = 0;               // m, positive
  Vec3 normal = Vec3::UnitY();  // world, from A towards B
  Vec3 point_a = Vec3::Zero();  // world: deepest point of A inside B
  Vec3 point_b = Vec3::Zero();
  bool ok = false;
};

// Penetration depth and normal of overlapping shapes (full shapes, radii included).
EpaResult epa_penetration(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb);

}  // namespace elan::detail
