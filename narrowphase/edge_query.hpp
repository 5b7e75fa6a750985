// SPDX-License-Identifier: MIT
// The SAT's edge query (sat.cpp; two boxes take box_box.cpp instead): of the edge pairs whose
// Gauss-map arcs cross (they build a face of the Minkowski difference), the first of largest
// separation along ua x ub, oriented out of A, with that axis as the normal. Compiled once per
// instruction set in a dispatching build (core/base/isa.hpp); the lanes' arithmetic is the scalar
// expression's on every path (no fused multiply-add, sums in a fixed order), so every path gives
// the same bits.
#pragma once

#include "core/base/isa.hpp"
#include "narrowphase/polyhedron.hpp"
#include "narrowphase/sat_common.hpp"

namespace elan::detail {

ELAN_ISA_BEGIN
EdgeQuery query_gauss_edges(const Polyhedron& a, const Polyhedron& b);
ELAN_ISA_END

// query_gauss_edges of the process's SIMD path (core/base/simd_path.hpp: the CPU's widest, or
// the one ELAN_SIMD names). The narrowphase has no world to ask for WorldDef::simd; the bits are
// the same either way.
EdgeQuery query_hull_edges(const Polyhedron& a, const Polyhedron& b);

}  // namespace elan::detail
