// SPDX-License-Identifier: MIT
// A capsule against a polyhedron (box, hull): the separating axis test of the capsule's core
// segment against the polyhedron's faces and edges, then the segment clipped to a face, or one
// point (Gregorius, GDC 2013 and 2015; Box2D's capsule manifold).
#pragma once

#include <limits>

#include "core/base/contact.hpp"
#include "narrowphase/polyhedron.hpp"
#include "narrowphase/sat.hpp"

namespace elan::detail {

// B's face of largest separation from the segment s0-s1 (the height of its nearer end above the
// face's plane) and whether the foot of that end lies on the face. When it does and the
// separation is positive, the separation is the segment's distance to B, `nearest` and its foot
// the closest points: B lies behind the face's plane, so nothing of B is nearer.
struct SegmentFaceQuery {
  int face = -1;
  Real separation = std::numeric_limits<Real>::lowest();
  Vec3 nearest = Vec3::Zero();  // the segment's end nearer the face's plane
  bool foot_on_face = false;
};
SegmentFaceQuery query_segment_faces(const Vec3& s0, const Vec3& s1, const Polyhedron& b);

// Capsule A (segment s0-s1 in the working frame, origin at its centre, `radius`) against
// polyhedron B; same output conventions.
bool collide_segment_polyhedron(const Vec3& s0, const Vec3& s1, Real radius, const Polyhedron& b,
                                Real speculative_distance, Manifold& out);

// Capsule A whose segment is apart from B (SAT is exact only for overlapping cores): `normal`
// (A to B, unit) and the closest points of the segment and B come from GJK. Clips the segment
// to B's face along the normal if it is aligned with one, else one point.
bool collide_segment_polyhedron_separated(const Vec3& s0, const Vec3& s1, Real radius,
                                          const Polyhedron& b, const Vec3& normal,
                                          const Vec3& point_a, const Vec3& point_b,
                                          Real speculative_distance, Manifold& out);

}  // namespace elan::detail
