// SPDX-License-Identifier: MIT
// One convex shape against one triangle of a mesh or heightfield: the contact normal and points,
// speculative like the shape pairs, with Jolt's active edges so that a body sliding over a smooth
// surface made of many triangles does not catch on their shared edges (no ghost collisions).
#pragma once

#include <cstdint>
#include <span>

#include "core/base/contact.hpp"
#include "core/base/mesh_triangle.hpp"
#include "core/base/shape.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase/supporting_feature.hpp"

namespace elan::detail {

struct HeightField;

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

// What collide_triangle derives from A, its pose and the distance alone. perf: made once per
// convex piece and surface, used for each of the triangles under the piece.
struct TriangleQuery {
  const Shape* shape = nullptr;
  Vec3 position = Vec3::Zero();  // A's centre of mass, surface frame
  Transform at_origin;           // A's rotation, at the working frame's origin (A's centre)
  PlacedShape full;              // A placed at the origin, radius included
  PlacedShape core;              // the same without the radius (the same as `full` for radius 0)
  Real radius = 0;               // core_radius(A)
  Real speculative = 0;          // m, without the motion
  // m, surface frame: A's displacement relative to the surface over the step; a triangle's
  // speculative distance is `speculative` plus its approach along the triangle's normal.
  Vec3 motion = Vec3::Zero();
  // Set: the triangles are this heightfield's, given without their active edges (corners()),
  // which are derived only where a contact needs them. Null: each triangle's own are read.
  const HeightField* field = nullptr;
  // A point of A (surface frame, from A's centre) that clear_of_box first measures its gap to:
  // the composite walk sets A's support along -y (a heightfield faces up, so under A the gap's
  // direction is about -y); A's centre (zero) serves too, more loosely.
  Vec3 down = Vec3::Zero();
  // Scratch: the support reach_triangle or clear_of_box last took along a gap's direction (A's
  // centre before any), a point of A that the next gap is first measured to as well. perf: the
  // walk meets neighbouring triangles one after another, their gaps about along one direction.
  mutable Vec3 recent = Vec3::Zero();
  // Scratch: A's face the last contact clipped (supporting_feature's memo). perf: a body resting
  // over a surface meets its triangles with the same face down, made once instead of for each.
  mutable FeatureMemo kept_face;
};
TriangleQuery make_triangle_query(const Shape& a, const Transform& xa, Real speculative_distance);

// The triangle in A's working frame and its plane: collide_triangle's first and cheapest tests.
struct TriangleReach {
  Vec3 v[3];           // corners, from A's centre
  Vec3 geometric;      // unit normal of the corners' winding
  Vec3 face;           // unit normal toward A's centre's side
  Vec3 lowest;         // A's support along -face (not for a sphere)
  Real plane_gap{};    // lowest's height above the plane (not for a sphere)
  Real speculative{};  // m: q.speculative plus q.motion's approach along -face
  // The triangle's closest point to A's centre, from it (not for a sphere): GJK's first search
  // direction (zero: toward the triangle's centroid).
  Vec3 closest = Vec3::Zero();
};

// Whether the triangle of corners a, b, c (surface frame, counter-clockwise seen from the front)
// may give a contact: false where collide_triangle gives none. perf: a heightfield derives a
// triangle's active edges only when it is in reach; a mesh's walk passes the corners where the
// mesh keeps them and makes the MeshTriangle only for a triangle in reach.
bool reach_triangle(const TriangleQuery& q, const Vec3& a, const Vec3& b, const Vec3& c,
                    bool two_sided, TriangleReach& r);
// The same for triangle `t` (corners and two_sided read; not its active edges).
inline bool reach_triangle(const TriangleQuery& q, const MeshTriangle& t, TriangleReach& r) {
  return reach_triangle(q, t.v[0], t.v[1], t.v[2], t.two_sided, r);
}

// Whether no triangle of `in_box` (each inside the box [lo, hi], surface frame) gives a contact at
// any speculative distance up to `speculative`: A (q's shape at q.position) is farther than that
// from every point of the box, and no triangle faces toward A's centre along the direction of
// that bound (see the definition: the contact routine's face path reports A's points under a
// triangle at any depth). One support: A's gap along the direction from its centre to the box's
// closest point. perf: a heightfield cell's two triangles are rejected together.
bool clear_of_box(const TriangleQuery& q, const Vec3& lo, const Vec3& hi, Real speculative,
                  std::span<const MeshTriangle> in_box);

// collide_triangle for a triangle in reach (`r` from reach_triangle for the same triangle; its
// active edges read from it, or from q.field): the same result.
bool collide_reached_triangle(const TriangleQuery& q, const MeshTriangle& t, const TriangleReach& r,
                              TriangleContact& out);

}  // namespace elan::detail
