// SPDX-License-Identifier: MIT
// A static heightfield: a grid of heights, the triangles implied (no tree: the cells under a box
// are a range of the grid).
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/mesh_triangle.hpp"
#include "elan/math.hpp"

namespace elan::detail {

// Sample (i, j) is the point (i spacing_x, heights[j * columns + i], j spacing_z). Cell (i, j)
// spans samples i..i+1 and j..j+1 and is split along its diagonal from (i, j) to (i+1, j+1) into
// triangle 2 c (the corner (i+1, j)) and 2 c + 1 (the corner (i, j+1)), c = j (columns - 1) + i;
// both face up (+y). perf: 4 bytes a sample (float heights) and 3 bits a cell (the active edges
// the cell owns, as Jolt's HeightFieldShape keeps them): 4.375 bytes a sample in all.
//
// A NaN sample is a hole (Jolt's cNoCollisionValue): a triangle with a hole at one of its corners
// is not there, for contacts, casts and queries alike, and the edges of the triangles beside it
// are a border (active).
struct HeightField {
  uint32_t columns = 0, rows = 0;
  Real spacing_x = 1, spacing_z = 1;
  std::vector<float> heights;
  Real min_height = 0, max_height = 0;  // of the triangles' corners (holes left out)
  // Whether any sample is a hole. perf: a field without holes walks its cells without looking.
  bool has_holes = false;
  // Cell c's three bits from bit 3 c on: its diagonal, its side z = j (p00 to p10) and its side
  // x = i (p00 to p01), 1 where active (see triangle()). The other two sides are the neighbours'
  // (the grid's last row and column: the border, always active). Two spare bytes at the end, so
  // that a cell's bits are read with one 16-bit load. Derived from the heights (build_heightfield).
  std::vector<uint8_t> edge_bits;

  Real height(uint32_t i, uint32_t j) const { return Real(heights[std::size_t(j) * columns + i]); }
  Vec3 point(uint32_t i, uint32_t j) const {
    return Vec3(Real(i) * spacing_x, height(i, j), Real(j) * spacing_z);
  }
  // Triangle t (see above) with its active edges: an edge is active on the grid's border, or where
  // the neighbouring triangle meets it at a convex angle past kActiveEdgeCos.
  MeshTriangle triangle(uint32_t t) const;
  // Triangle t's corners and index alone (active_edges left at its default), and the active edges
  // of such a triangle: triangle(t) is the two together. perf: a query that rejects most
  // triangles on their corners looks up the edges only for the rest.
  MeshTriangle corners(uint32_t t) const;
  // corners(2 c) and corners(2 c + 1) of cell (i, j), c = j (columns - 1) + i. perf: a walk over
  // cells reads the four samples once for both, and needs no division to find the cell.
  void cell_corners(uint32_t i, uint32_t j, MeshTriangle (&pair)[2]) const;
  uint8_t active_edges_of(const MeshTriangle& m) const;
  // Which of cell (i, j)'s two triangles are there: bit 0 triangle 2 c, bit 1 triangle 2 c + 1
  // (see above: a hole at a corner takes a triangle away).
  uint32_t cell_triangles(uint32_t i, uint32_t j) const {
    if (!has_holes) return 3;
    const bool h00 = !std::isnan(height(i, j)), h11 = !std::isnan(height(i + 1, j + 1));
    const bool diagonal = h00 && h11;
    return uint32_t(diagonal && !std::isnan(height(i + 1, j))) |
           uint32_t(diagonal && !std::isnan(height(i, j + 1))) << 1;
  }
  bool has_triangle(uint32_t t) const {
    const uint32_t c = t / 2, cells_x = columns - 1;
    return (cell_triangles(c % cells_x, c / cells_x) >> (t & 1)) & 1u;
  }
  // The least and greatest height of the corners of cell (i, j)'s triangles `triangles` (its
  // cell_triangles, not 0): a hole's sample, a corner of neither, is left out.
  void triangle_heights(uint32_t i, uint32_t j, uint32_t triangles, Real& low, Real& high) const {
    const Real h00 = height(i, j), h11 = height(i + 1, j + 1);
    low = std::min(h00, h11), high = std::max(h00, h11);
    // The corner each triangle has alone: (i + 1, j) the lower's, (i, j + 1) the upper's.
    for (const uint32_t k : {0u, 1u}) {
      if (!((triangles >> k) & 1u)) continue;
      const Real h = k == 0 ? height(i + 1, j) : height(i, j + 1);
      low = std::min(low, h);
      high = std::max(high, h);
    }
  }
};

// Checks and builds; a NaN height is a hole. What it derives from the heights: has_holes, each
// edge's active flag, decided once from the unit normals of the two triangles that share it
// (edge_is_active) so both see it alike, or set where only one triangle has it (the grid's
// border, a hole's rim), and the bounds, of the corners of the triangles there. Throws elan::Error:
// "shape.heights" (fewer than 2 x 2, a row of another length, an infinite height or one past the
// supported coordinates, no triangle left by the holes), "shape.spacing" (zero, negative, not
// finite).
HeightField build_heightfield(std::span<const Real> heights, uint32_t columns, Real spacing_x,
                              Real spacing_z);

// Calls f(uint32_t i, uint32_t j, Real low, Real high, uint32_t triangles) for each cell (i, j)
// under [lo, hi] (x and z) with a triangle (`triangles`: cell_triangles) whose heights (low to
// high: the least and greatest of its triangles' corners) reach the box's y range, row by row,
// cell by cell.
template <class F>
void for_each_cell(const HeightField& field, const Vec3& lo, const Vec3& hi, F&& f) {
  if (lo.y() > field.max_height || hi.y() < field.min_height) return;
  const auto cell_range = [](Real a, Real b, Real spacing, uint32_t samples, uint32_t& first,
                             uint32_t& last) {
    const Real fa = std::floor(a / spacing), fb = std::floor(b / spacing);
    if (!(fb >= 0) || !(fa <= Real(samples - 2))) return false;
    first = fa <= 0 ? 0u : uint32_t(fa);
    last = fb >= Real(samples - 2) ? samples - 2 : uint32_t(fb);
    return first <= last;
  };
  uint32_t i0, i1, j0, j1;
  if (!cell_range(lo.x(), hi.x(), field.spacing_x, field.columns, i0, i1)) return;
  if (!cell_range(lo.z(), hi.z(), field.spacing_z, field.rows, j0, j1)) return;
  if (field.has_holes) {
    for (uint32_t j = j0; j <= j1; ++j) {
      for (uint32_t i = i0; i <= i1; ++i) {
        const uint32_t triangles = field.cell_triangles(i, j);
        if (triangles == 0) continue;
        Real low, high;
        field.triangle_heights(i, j, triangles, low, high);
        if (low > hi.y() || high < lo.y()) continue;
        f(i, j, low, high, triangles);
      }
    }
    return;
  }
  for (uint32_t j = j0; j <= j1; ++j) {
    for (uint32_t i = i0; i <= i1; ++i) {
      const Real h00 = field.height(i, j), h10 = field.height(i + 1, j);
      const Real h01 = field.height(i, j + 1), h11 = field.height(i + 1, j + 1);
      const Real low = std::min(std::min(h00, h10), std::min(h01, h11));
      const Real high = std::max(std::max(h00, h10), std::max(h01, h11));
      if (low > hi.y() || high < lo.y()) continue;
      f(i, j, low, high, 3u);
    }
  }
}

// Calls f(uint32_t t) for each triangle t of the cells under [lo, hi] (for_each_cell's), row by
// row, cell by cell, lower triangle first.
template <class F>
void for_each_triangle_index(const HeightField& field, const Vec3& lo, const Vec3& hi, F&& f) {
  for_each_cell(field, lo, hi, [&](uint32_t i, uint32_t j, Real, Real, uint32_t triangles) {
    const uint32_t c = j * (field.columns - 1) + i;
    if (triangles & 1u) f(2 * c);
    if (triangles & 2u) f(2 * c + 1);
  });
}

// Calls f(const MeshTriangle&) for the same triangles in the same order, active edges included.
template <class F>
void for_each_triangle(const HeightField& field, const Vec3& lo, const Vec3& hi, F&& f) {
  for_each_triangle_index(field, lo, hi, [&](uint32_t t) { f(field.triangle(t)); });
}

// The nearest hit of the ray (shape frame) with the surface, from above or below, walking the
// cells the ray crosses (a 2D DDA over the grid). Same contract as ray_cast_mesh.
bool ray_cast_heightfield(const HeightField& field, const Vec3& origin, const Vec3& dir, Real max_t,
                          SurfaceHit& hit);

std::size_t heightfield_bytes(const HeightField& field);

}  // namespace elan::detail
