// SPDX-License-Identifier: MIT
// Separation: what an exact test that found no contact measured, so that the next steps can
// tell from the motion alone that it would find none again.
#pragma once

#include <cstdint>

#include "elan/math.hpp"

namespace elan::detail {

// What a test that found no contact measured. Every routine rejects a pair on one separation it
// computed against the speculative distance: a distance between the shapes (closed forms, GJK)
// or the SAT gap along a face normal of one of them. `gap` is a lower bound of that separation.
// A face of A is fixed in A's frame, so its gap shrinks by no more than B's points move in A's
// frame; a face of B's by no more than A's points move in B's; a distance by no more than either.
// While that motion stays below gap minus the speculative distance, the same routine rejects the
// pair again (collide_pairs' separation cache). An edge axis turns with both bodies, so no motion
// bound keeps it; EdgePair names the SAT's two edges instead (edge_a of A, edge_b of B), and the
// cache tests that one axis again with the SAT's own arithmetic (two boxes: the box-box
// routine's): while it still separates, the SAT rejects the pair again. Unknown: nothing that lasts
// (a near-parallel capsule pair measures two points).
struct Separation {
  enum class Kind : uint8_t { Unknown, Distance, FaceOfA, FaceOfB, EdgePair };
  Kind kind = Kind::Unknown;
  Real gap = 0;                  // m
  int edge_a = -1, edge_b = -1;  // EdgePair only
};
// The same separation with A and B swapped: a face of one is a face of the other side.
inline Separation::Kind swap_sides(Separation::Kind kind) {
  switch (kind) {
    case Separation::Kind::FaceOfA:
      return Separation::Kind::FaceOfB;
    case Separation::Kind::FaceOfB:
      return Separation::Kind::FaceOfA;
    case Separation::Kind::EdgePair:
      return Separation::Kind::Unknown;  // only the SAT reports one, and it has both orders
    default:
      return kind;
  }
}
inline void report_separation(Separation* s, Separation::Kind kind, Real gap) {
  if (s != nullptr) *s = {kind, gap, -1, -1};
}

}  // namespace elan::detail
