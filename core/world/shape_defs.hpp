// SPDX-License-Identifier: MIT
// The definition World::shape_def returns, derived from the built shape: what a drawer or an
// embedder needs to redraw or rebuild the shape, the same before and after a snapshot.
#pragma once

#include "core/base/shape.hpp"
#include "elan/defs.hpp"

namespace elan::detail {

// A definition that builds the same geometry as `shape`, in the shape's own (user) frame: a
// hull's extreme points (not the input cloud), a mesh's triangles in tree order, a normalised
// plane normal, a compound's children in definition order. user_data is left 0.
ShapeDef shape_def_of(const Shape& shape);

}  // namespace elan::detail
