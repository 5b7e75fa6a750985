// SPDX-License-Identifier: MIT
// Separating axis test with face clipping for polyhedron pairs (boxes, hulls) (Gregorius, "The
// Separating Axis Test between Convex Polyhedra", GDC 2013; "Robust Contact Creation for Physics
// Simulations", GDC 2015).
#pragma once

#include <limits>

#include "core/base/contact.hpp"
#include "narrowphase/polyhedron.hpp"
#include "narrowphase/sat_common.hpp"
#include "narrowphase/separation.hpp"

namespace elan::detail {

// Feature id layout: bits 30-31 the kind, the rest the touching features.
inline constexpr uint32_t kFeatureFaceA = 0u << 30;    // A's face is the reference face
inline constexpr uint32_t kFeatureFaceB = 1u << 30;    // B's face is the reference face
inline constexpr uint32_t kFeatureEdges = 2u << 30;    // edge of A against edge of B
inline constexpr uint32_t kFeatureSegment = 3u << 30;  // capsule segment or general path

// A and B in one working frame (positions relative to A's centre of mass). Writes out.normal
// (A to B, working = world rotation), point_count, and each point's anchor_a (offset from A's
// centre, which is the frame origin), separation and feature id.
// A rejection on a face of A or of B reports that face's gap to `separation` (collide.hpp), one
// on an edge axis the two edges.
bool collide_polyhedra(const Polyhedron& a, const Polyhedron& b, Real speculative_distance,
                       Manifold& out, Separation* separation = nullptr);

// The separation the edge query gives A's edge `edge_a` and B's edge `edge_b` when they build a
// face of the Minkowski difference (their Gauss-map arcs cross), bit for bit; the lowest Real when
// they do not, are nearly parallel, or are not edges of a and b. collide_polyhedra's rejection on
// an edge axis reports that pair.
Real edge_pair_separation(const Polyhedron& a, const Polyhedron& b, int edge_a, int edge_b);

}  // namespace elan::detail
