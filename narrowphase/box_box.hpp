// SPDX-License-Identifier: MIT
// The contact of two boxes: the separating axis test over their 15 axes, measured from one
// rotation between them, then the incident face clipped against the reference face's rectangle
// in the reference box's own frame, or one point between two crossing edges.
#pragma once

#include "core/base/contact.hpp"
#include "core/base/shape.hpp"
#include "narrowphase/separation.hpp"

namespace elan::detail {

// Boxes a and b at poses xa and xb. Writes out.normal (A to B, world), point_count, and each
// point's anchor_a (offset from A's centre), separation and feature id, in the layout of sat.hpp:
// the same features as the polyhedron SAT of the same boxes, with the same ids. A rejection on a
// face of A or of B reports that face's gap to `separation`, one on an edge axis the two edges.
bool collide_box_box(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                     Real speculative_distance, Manifold& out, Separation* separation);

// The separation collide_box_box measures between A's edge `edge_a` and B's edge `edge_b` (the
// axis of their directions, edge / 4), bit for bit: what its rejection on that axis reported;
// the lowest Real when the two are nearly parallel or not edges of a box (0 to 11).
Real box_edge_pair_separation(const Shape& a, const Transform& xa, const Shape& b,
                              const Transform& xb, int edge_a, int edge_b);

}  // namespace elan::detail
