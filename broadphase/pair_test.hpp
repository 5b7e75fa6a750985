// SPDX-License-Identifier: MIT
// The one overlap-and-accept rule every broadphase method applies, so their lists agree bit for
// bit: closed boxes (touching counts), then kinds, then filter bits.
#pragma once

#include <cstdint>

#include "broadphase/find_pairs.hpp"

namespace elan::detail {

// Closed intervals: boxes that only touch (max == min) overlap. NaN bounds never overlap.
inline bool boxes_overlap(const BoundsColumns& b, uint32_t i, uint32_t j) {
  return b.min_x[i] <= b.max_x[j] && b.min_x[j] <= b.max_x[i] && b.min_y[i] <= b.max_y[j] &&
         b.min_y[j] <= b.max_y[i] && b.min_z[i] <= b.max_z[j] && b.min_z[j] <= b.max_z[i];
}

inline bool accept_pair(const BroadphaseInput& in, uint32_t i, uint32_t j) {
  return should_pair(BroadKind(in.kind[i]), BroadKind(in.kind[j])) && filter_pass(in, i, j);
}

}  // namespace elan::detail
