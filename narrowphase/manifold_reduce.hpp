// SPDX-License-Identifier: MIT
// Manifold reduction: choose at most four contact candidates that keep the deepest point and
// span the largest area, so a stable support polygon survives with a fixed point budget.
#pragma once

#include <span>

#include "core/base/contact.hpp"
#include "elan/math.hpp"

namespace elan::detail {

// Chooses up to kMaxManifoldPoints of the candidates (world positions, separations; same length)
// and writes their indices to out_indices; returns how many. Order: the deepest point (smallest
// separation), then the farthest from it, then the one maximising the triangle area, then the
// one maximising the quadrilateral area; areas are measured in the plane normal to `normal`.
// Ties go to the lower index, so the choice depends on the input order alone.
int reduce_to_four(std::span<const Vec3> positions, std::span<const Real> separations,
                   const Vec3& normal, int out_indices[kMaxManifoldPoints]);

}  // namespace elan::detail
