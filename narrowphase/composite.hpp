// SPDX-License-Identifier: MIT
// Pairs with a composite side (a mesh, a heightfield or a compound): walked piece by piece
// (compound parts, the triangles under a piece's box), every piece's contacts merged into the one
// manifold the contact store keeps per pair.
#pragma once

#include "core/base/compound.hpp"
#include "core/base/contact.hpp"
#include "core/base/shape.hpp"

namespace elan::detail {

// A static surface of triangles: a mesh or a heightfield.
inline bool is_surface(const Shape& s) {
  return s.type == ShapeType::Mesh || s.type == ShapeType::Heightfield;
}

// A shape made of pieces: a surface or a compound.
inline bool is_composite(const Shape& s) {
  return is_surface(s) || s.type == ShapeType::Compound;
}

// A's displacement relative to B over the coming step (world, m) and the speculative distance
// without it. Given to collide_composite, a surface's triangle keeps contacts within
// `base_speculative` plus the displacement's approach along the triangle's normal (the part of
// the motion that can close the gap to its plane), and the box a piece walks is grown by
// `base_speculative` and stretched along the displacement, rather than both grown all round by
// the whole motion (the speculative distance given): a body falling onto a surface meets the
// triangles below it, not those beside it. Box2D and Jolt keep a fixed speculative distance for
// every contact; this keeps the motion's allowance where the motion goes.
struct SurfaceMotion {
  Vec3 displacement = Vec3::Zero();
  Real base_speculative = 0;
};

// Same contract as collide() (collide.hpp), for a pair where either shape is composite. A
// compound is walked part by part (parts whose box meets the other side's box grown by the
// speculative distance); a convex piece against a surface walks the triangles under its box, in
// the surface's frame (collide_triangle); a convex piece against a convex piece or a plane takes
// collide(). Nothing for two surfaces or a surface and a plane (both static). All candidate
// points are merged into one manifold of at most four: the deepest candidate's normal, the
// candidates whose normal is within kSameNormalCos of it (their separation re-measured along it),
// reduced with reduce_to_four. Feature ids hash the part indices, the triangle's index and the
// piece's own id. Fixed stack buffers; the walk's order is fixed.
// `motion`, if given: see SurfaceMotion (its base at most `speculative_distance`, and the base plus
// the displacement's length at least it); without it every triangle keeps `speculative_distance`.
bool collide_composite(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                       Real speculative_distance, Manifold& out,
                       const SurfaceMotion* motion = nullptr);

// Whether a compound has a round part (sphere, capsule, cylinder): its manifold is not carried by
// the body pair cache (collide_pairs' rolls()).
inline bool has_round_part(const Shape& s) {
  return s.type == ShapeType::Compound && s.compound->round;
}

}  // namespace elan::detail
