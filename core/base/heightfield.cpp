// SPDX-License-Identifier: MIT
// The static heightfield: validation, its implied triangles with their active edges, and the ray
// walked cell by cell over the grid.
#include "core/base/heightfield.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/base/range_checks.hpp"
#include "core/base/triangle_mesh.hpp"
#include "elan/error.hpp"

namespace elan::detail {
namespace {

// More cells than this are refused: triangle 2 c + 1 is numbered in 32 bits.
constexpr std::size_t kMaxCells = std::size_t(1) << 31;

void check_spacing(Real s, const char* axis) {
  if (!std::isfinite(s) || !(s > 0)) {
    throw Error("shape.spacing",
                std::string("spacing_") + axis + " must be finite and > 0, got " + show_value(s));
  }
  check_range(s, limits::kMinSize, limits::kMaxSize, "shape.spacing", "m");
}

// Derives field.has_holes and field.edge_bits from its heights (see build_heightfield).
void set_active_edges(HeightField& field);

// Derives field.min_height and max_height: of the corners of the triangles there. Throws
// elan::Error "shape.heights" when the holes leave none.
void set_bounds(HeightField& f) {
  // The stored (float) heights are the surface; the bounds are theirs.
  Real lo = std::numeric_limits<Real>::max(), hi = -lo;
  if (!f.has_holes) {
    for (const float h : f.heights) {
      lo = std::min(lo, Real(h));
      hi = std::max(hi, Real(h));
    }
  } else {
    for (uint32_t j = 0; j + 1 < f.rows; ++j) {
      for (uint32_t i = 0; i + 1 < f.columns; ++i) {
        const uint32_t there = f.cell_triangles(i, j);
        if (there == 0) continue;
        Real low, high;
        f.triangle_heights(i, j, there, low, high);
        lo = std::min(lo, low);
        hi = std::max(hi, high);
      }
    }
    // A field the holes leave no triangle has no surface (and no bounds) to collide with.
    if (!(lo <= hi)) {
      throw Error("shape.heights",
                  "the holes (NaN heights) leave no triangle: every cell has a hole at a corner of "
                  "both its triangles");
    }
  }
  f.min_height = lo;
  f.max_height = hi;
}

}  // namespace

HeightField build_heightfield(std::span<const Real> heights, uint32_t columns, Real spacing_x,
                              Real spacing_z) {
  const std::size_t n = heights.size();
  if (columns < 2 || n < 2 * std::size_t(columns)) {
    throw Error("shape.heights", "must have at least 2 rows of 2 samples, got " +
                                     std::to_string(n) + " heights in rows of " +
                                     std::to_string(columns));
  }
  if (n % columns != 0) {
    throw Error("shape.heights", "heights.size() " + std::to_string(n) +
                                     " is not a multiple of columns " + std::to_string(columns));
  }
  const std::size_t rows = n / columns;
  if (rows > UINT32_MAX || (columns - 1) * (rows - 1) > kMaxCells) {
    throw Error("shape.heights", "more than " + std::to_string(kMaxCells) + " cells");
  }
  check_spacing(spacing_x, "x");
  check_spacing(spacing_z, "z");
  // The grid's extent is a position in the shape frame.
  if (!(double(columns - 1) * spacing_x <= 2 * limits::kMaxPosition) ||
      !(double(rows - 1) * spacing_z <= 2 * limits::kMaxPosition)) {
    throw Error("shape.spacing",
                "the grid spans more than " + show_value(2 * limits::kMaxPosition) + " m");
  }
  HeightField f;
  f.columns = columns;
  f.rows = uint32_t(rows);
  f.spacing_x = spacing_x;
  f.spacing_z = spacing_z;
  f.heights.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double h = heights[k];
    if (std::isnan(h)) {
      f.heights[k] = std::numeric_limits<float>::quiet_NaN();  // a hole
      continue;
    }
    if (!std::isfinite(h) || !(std::fabs(h) <= limits::kMaxPosition)) {
      throw Error("shape.heights",
                  "height " + std::to_string(k) + " (row " + std::to_string(k / columns) +
                      ", column " + std::to_string(k % columns) + ") must be finite and in [" +
                      show_value(-limits::kMaxPosition) + ", " + show_value(limits::kMaxPosition) +
                      "] m (or NaN for a hole), got " + show_value(h));
    }
    f.heights[k] = float(heights[k]);
  }
  set_active_edges(f);
  set_bounds(f);
  return f;
}

MeshTriangle HeightField::corners(uint32_t t) const {
  const uint32_t c = t / 2, cells_x = columns - 1;
  const uint32_t i = c % cells_x, j = c / cells_x;
  MeshTriangle m;
  m.index = t;
  m.two_sided = false;
  // Lower (2 c): p00, p11, p10; upper (2 c + 1): p00, p01, p11; both counter-clockwise from +y.
  m.v[0] = point(i, j);
  if ((t & 1) == 0) {
    m.v[1] = point(i + 1, j + 1), m.v[2] = point(i + 1, j);
  } else {
    m.v[1] = point(i, j + 1), m.v[2] = point(i + 1, j + 1);
  }
  return m;
}

void HeightField::cell_corners(uint32_t i, uint32_t j, MeshTriangle (&pair)[2]) const {
  const uint32_t c = j * (columns - 1) + i;
  const Vec3 p00 = point(i, j), p10 = point(i + 1, j);
  const Vec3 p01 = point(i, j + 1), p11 = point(i + 1, j + 1);
  pair[0].index = 2 * c;
  pair[0].two_sided = false;
  pair[0].v[0] = p00, pair[0].v[1] = p11, pair[0].v[2] = p10;
  pair[1].index = 2 * c + 1;
  pair[1].two_sided = false;
  pair[1].v[0] = p00, pair[1].v[1] = p01, pair[1].v[2] = p11;
}

namespace {

// Bit k of cell c's three in `bits` (3 c + k from the start).
void set_edge_bit(std::vector<uint8_t>& bits, std::size_t c, int k) {
  const std::size_t b = 3 * c + std::size_t(k);
  bits[b / 8] = uint8_t(bits[b / 8] | (1u << (b % 8)));
}

void set_active_edges(HeightField& f) {
  f.has_holes =
      std::any_of(f.heights.begin(), f.heights.end(), [](float h) { return std::isnan(h); });
  const uint32_t cells_x = f.columns - 1, cells_z = f.rows - 1;
  const std::size_t cells = std::size_t(cells_x) * cells_z;
  f.edge_bits.assign((3 * cells + 7) / 8 + 2, 0);
  // An edge with a triangle on both sides is active where they meet at a convex angle; with one
  // on one side only (a hole's on the other), it is a border.
  const auto decide = [&f](std::size_t c, int k, bool one, bool other, const Vec3& n_one,
                           const Vec3& n_other, const Vec3& edge) {
    if (one != other || (one && edge_is_active(n_one, n_other, edge)))
      set_edge_bit(f.edge_bits, c, k);
  };
  for (uint32_t j = 0; j < cells_z; ++j) {
    for (uint32_t i = 0; i < cells_x; ++i) {
      const std::size_t c = std::size_t(j) * cells_x + i;
      MeshTriangle own[2];
      f.cell_corners(i, j, own);
      const uint32_t here = f.cell_triangles(i, j);
      const Vec3 lower = own[0].normal(), upper = own[1].normal();
      // The diagonal, as the lower triangle walks it (its edge 0, p00 to p11).
      decide(c, 0, here & 1u, here & 2u, lower, upper, own[0].v[1] - own[0].v[0]);
      // Side z = j, as the lower triangle walks it (its edge 2, p10 to p00), against the upper
      // triangle of cell (i, j - 1).
      if (j == 0) {
        set_edge_bit(f.edge_bits, c, 1);
      } else {
        MeshTriangle below[2];
        f.cell_corners(i, j - 1, below);
        decide(c, 1, here & 1u, f.cell_triangles(i, j - 1) & 2u, lower, below[1].normal(),
               own[0].v[0] - own[0].v[2]);
      }
      // Side x = i, as the upper triangle walks it (its edge 0, p00 to p01), against the lower
      // triangle of cell (i - 1, j).
      if (i == 0) {
        set_edge_bit(f.edge_bits, c, 2);
      } else {
        MeshTriangle left[2];
        f.cell_corners(i - 1, j, left);
        decide(c, 2, here & 2u, f.cell_triangles(i - 1, j) & 1u, upper, left[0].normal(),
               own[1].v[1] - own[1].v[0]);
      }
    }
  }
}

}  // namespace

uint8_t HeightField::active_edges_of(const MeshTriangle& m) const {
  const uint32_t t = m.index;
  const uint32_t c = t / 2, cells_x = columns - 1;
  const auto bits = [this](std::size_t cell) {
    const std::size_t b = 3 * cell;
    const uint32_t word = uint32_t(edge_bits[b / 8]) | uint32_t(edge_bits[b / 8 + 1]) << 8;
    return (word >> (b % 8)) & 7u;
  };
  const uint32_t own = bits(c);
  const uint32_t diagonal = own & 1u, side_z = (own >> 1) & 1u, side_x = (own >> 2) & 1u;
  if ((t & 1) == 0) {
    // Lower: edge 0 the diagonal, edge 1 side x = i + 1 (cell (i + 1, j)'s, or the border),
    // edge 2 side z = j.
    const bool last_column = c % cells_x + 1 == cells_x;
    const uint32_t right = last_column ? 1u : (bits(c + 1) >> 2) & 1u;
    return uint8_t(diagonal | right << 1 | side_z << 2);
  }
  // Upper: edge 0 side x = i, edge 1 side z = j + 1 (cell (i, j + 1)'s, or the border), edge 2
  // the diagonal.
  const bool last_row = c / cells_x + 1 == rows - 1;
  const uint32_t above = last_row ? 1u : (bits(c + cells_x) >> 1) & 1u;
  return uint8_t(side_x | above << 1 | diagonal << 2);
}

MeshTriangle HeightField::triangle(uint32_t t) const {
  MeshTriangle m = corners(t);
  m.active_edges = active_edges_of(m);
  return m;
}

bool ray_cast_heightfield(const HeightField& field, const Vec3& origin, const Vec3& dir, Real max_t,
                          SurfaceHit& hit) {
  using Vec3d = Eigen::Vector3d;
  const Vec3d o = origin.cast<double>(), d = dir.cast<double>();
  const Vec3d lo(0, double(field.min_height), 0);
  const Vec3d hi(double(Real(field.columns - 1) * field.spacing_x), double(field.max_height),
                 double(Real(field.rows - 1) * field.spacing_z));
  // Clip the ray to the field's box (slabs).
  double t0 = 0, t1 = double(max_t);
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  // determinism and robustness: the cell boundaries are the samples' own coordinates, Real(i)
  // spacing as point() rounds them, so the walk and the triangles agree on which cell a point is
  // in.
  const auto line_x = [&](int64_t i) { return double(Real(i) * field.spacing_x); };
  const auto line_z = [&](int64_t j) { return double(Real(j) * field.spacing_z); };
  const auto cell_of = [](double x, double spacing, int64_t cells, auto line) {
    const double c = std::floor(x / spacing);
    int64_t k = c <= 0 ? 0 : c >= double(cells - 1) ? cells - 1 : int64_t(c);
    while (k + 1 < cells && x >= line(k + 1)) ++k;
    while (k > 0 && x < line(k)) --k;
    return k;
  };
  const int64_t cells_x = int64_t(field.columns) - 1, cells_z = int64_t(field.rows) - 1;
  const Vec3d p = o + t0 * d;
  int64_t i = cell_of(p.x(), double(field.spacing_x), cells_x, line_x);
  int64_t j = cell_of(p.z(), double(field.spacing_z), cells_z, line_z);
  const int step_i = d.x() > 0 ? 1 : -1, step_j = d.z() > 0 ? 1 : -1;
  const auto next_x = [&](int64_t cell) {
    if (d.x() == 0) return std::numeric_limits<double>::infinity();
    return (line_x(cell + (d.x() > 0 ? 1 : 0)) - o.x()) / d.x();
  };
  const auto next_z = [&](int64_t cell) {
    if (d.z() == 0) return std::numeric_limits<double>::infinity();
    return (line_z(cell + (d.z() > 0 ? 1 : 0)) - o.z()) / d.z();
  };
  bool found = false;
  Real best = max_t;
  // A 2D DDA (Amanatides & Woo 1987) over the cells of the ray's xz projection, in order of t;
  // a cell's hit lies within its t range, so the walk stops at the first cell past the nearest
  // hit. The count bound guarantees the walk ends whatever the rounding.
  const int64_t max_cells = int64_t(field.columns) + int64_t(field.rows);
  for (int64_t walked = 0; walked <= max_cells; ++walked) {
    const uint32_t c = uint32_t(j) * (field.columns - 1) + uint32_t(i);
    const uint32_t there = field.cell_triangles(uint32_t(i), uint32_t(j));
    for (uint32_t t = 2 * c; t <= 2 * c + 1; ++t) {
      if (!((there >> (t & 1)) & 1u)) continue;
      const MeshTriangle tri = field.triangle(t);
      Real th;
      if (!ray_triangle(origin, dir, tri.v[0], tri.v[1], tri.v[2], best, th)) continue;
      if (found && !(th < best)) continue;
      found = true;
      best = th;
      hit.t = th;
      hit.triangle = t;
      hit.normal = tri.normal();
    }
    const double tx = next_x(i), tz = next_z(j);
    const double exit = std::min(tx, tz);
    // The clip's t1 may be the hit itself (a flat field's box has no height): a cell whose entry
    // rounds a hair past it is still walked.
    if (exit > t1 + 1e-9 * (1 + std::fabs(t1)) || (found && double(best) < exit)) break;
    if (tx <= tz) {
      i += step_i;
      if (i < 0 || i >= cells_x) break;
    } else {
      j += step_j;
      if (j < 0 || j >= cells_z) break;
    }
  }
  if (found && hit.normal.dot(dir) > 0) hit.normal = -hit.normal;
  return found;
}

std::size_t heightfield_bytes(const HeightField& field) {
  return sizeof(HeightField) + field.heights.capacity() * sizeof(float) +
         field.edge_bits.capacity();
}

}  // namespace elan::detail
