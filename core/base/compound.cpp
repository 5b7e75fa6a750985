// SPDX-License-Identifier: MIT
// The compound's memory count (its construction is make_shape's, beside the other shapes' mass
// properties, in shape.cpp).
#include "core/base/compound.hpp"

#include <algorithm>
#include <limits>

namespace elan::detail {

void describe_parts(Compound& c) {
  c.round = false;
  c.thinnest = std::numeric_limits<Real>::max();
  for (const CompoundPart& p : c.parts) {
    const ShapeType t = p.shape.type;
    c.round =
        c.round || t == ShapeType::Sphere || t == ShapeType::Capsule || t == ShapeType::Cylinder;
    c.thinnest =
        std::min(c.thinnest, Real(0.5) * (p.shape.local_max - p.shape.local_min).minCoeff());
  }
}

// The parts' own heap (a hull child's vertices) is shared with its definition's shape and is
// counted where the hulls are (memory_use.cpp), once each.
std::size_t compound_bytes(const Compound& c) {
  return sizeof(Compound) + c.parts.capacity() * sizeof(CompoundPart) +
         c.child_of.capacity() * sizeof(uint32_t) + bvh_bytes(c.tree);
}

}  // namespace elan::detail
