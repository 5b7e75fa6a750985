// SPDX-License-Identifier: MIT
// The compound's memory count (its construction is make_shape's, beside the other shapes' mass
// properties, in shape.cpp).
#include "core/base/compound.hpp"

namespace elan::detail {

// The parts' own heap (a hull child's vertices) is shared with its definition's shape and is
// counted where the hulls are (memory_use.cpp), once each.
std::size_t compound_bytes(const Compound& c) {
  return sizeof(Compound) + c.parts.capacity() * sizeof(CompoundPart) +
         c.child_of.capacity() * sizeof(uint32_t) + bvh_bytes(c.tree);
}

}  // namespace elan::detail
