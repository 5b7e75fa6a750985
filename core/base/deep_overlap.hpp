// SPDX-License-Identifier: MIT
// The deep test, shared by the deep-pair budget (core/world/deep_pairs.hpp), which bounds how
// many deep pairs a body keeps, and the collide stage (narrowphase/deep_contact.hpp), which, in a
// step where the budget bit, gives the kept ones a contact of constant cost instead of the exact
// test.
//
// A pair is deep when both bodies are dynamic convex primitives (sphere, box, capsule, cylinder,
// hull) whose inner balls overlap by more than (1 - kDeepFraction) of the sum of their radii:
// centres closer than kDeepFraction (r_a + r_b). A body's inner ball is centred at its centre of
// mass, of radius the thinnest half-extent of its shape's local box (half that for a hull, whose
// box need not bound a ball inside it), so it lies inside the shape, and the inner balls of two
// convex bodies that only touch are disjoint (d >= r_a + r_b less the contact slop). Two unit
// boxes are deep with their centres within 0.9 m, 10 cm into each other face on. A pair of an
// ordinary scene can be deep where it is pressed hard (two round bodies landing on each other,
// a body crushed by a kinematic one), but no body of one has more than the budget's deep pairs.
#pragma once

#include "core/base/shape.hpp"
#include "elan/math.hpp"

namespace elan::detail {

inline constexpr Real kDeepFraction = Real(0.9);

// The inner ball's radius of a convex primitive, m; 0 for any other shape (a compound, whose
// centre need not lie inside it, a mesh, a heightfield, a plane), which is never deep. The
// caller also gives 0 for a body that is not dynamic.
inline Real inner_ball_radius(const Shape& s) {
  switch (s.type) {
    case ShapeType::Sphere:
    case ShapeType::Box:
    case ShapeType::Capsule:
    case ShapeType::Cylinder:
      return Real(0.5) * (s.local_max - s.local_min).minCoeff();
    case ShapeType::ConvexHull:
      return Real(0.25) * (s.local_max - s.local_min).minCoeff();
    default:
      return 0;
  }
}

// Whether two bodies with inner balls of radii ra, rb (both > 0) centred at ca, cb are deep.
inline bool inner_balls_deep(const Vec3& ca, Real ra, const Vec3& cb, Real rb) {
  const Real reach = kDeepFraction * (ra + rb);
  return (ca - cb).squaredNorm() < reach * reach;
}

}  // namespace elan::detail
