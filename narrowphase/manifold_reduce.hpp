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
// Adds candidate x (any struct with a `separation`) to the first `count` of `c` (room for
// `capacity`); when full, x replaces the shallowest if it is deeper, so the deepest points always
// survive a bounded stack buffer. determinism: the first of equally shallow candidates goes.
template <class Candidate>
void push_keeping_deepest(Candidate* c, int& count, int capacity, const Candidate& x) {
  if (count < capacity) {
    c[count++] = x;
    return;
  }
  int worst = 0;
  for (int i = 1; i < count; ++i) {
    if (c[i].separation > c[worst].separation) worst = i;
  }
  if (x.separation < c[worst].separation) c[worst] = x;
}

int reduce_to_four(std::span<const Vec3> positions, std::span<const Real> separations,
                   const Vec3& normal, int out_indices[kMaxManifoldPoints]);

}  // namespace elan::detail
