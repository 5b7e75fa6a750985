// SPDX-License-Identifier: MIT
// The heightfield: the triangle layout the header fixes (a cell's pair read at once too), normals
// up, active edges of flat and bumpy grids, validation, the ray's cell walk against brute force,
// bytes a sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/base/heightfield.hpp"
#include "core/base/triangle_mesh.hpp"
#include "elan/error.hpp"

namespace elan::detail {
namespace heightfield_test {

HeightField bumpy(uint32_t columns, uint32_t rows, Real sx, Real sz) {
  std::vector<Real> h(std::size_t(columns) * rows);
  for (uint32_t j = 0; j < rows; ++j) {
    for (uint32_t i = 0; i < columns; ++i) {
      h[j * columns + i] = Real(1.5 * std::sin(0.7 * i) * std::cos(0.45 * j) + 0.1 * ((i * j) % 3));
    }
  }
  return build_heightfield(h, columns, sx, sz);
}

TEST(HeightField, TriangleLayoutAndNormalsUp) {
  const HeightField f = bumpy(5, 4, 0.5f, 2);
  EXPECT_EQ(f.columns, 5u);
  EXPECT_EQ(f.rows, 4u);
  // Cell (2, 1): c = 1 * 4 + 2 = 6; triangle 12 has the corner (3, 1), 13 the corner (2, 2).
  const MeshTriangle lower = f.triangle(12), upper = f.triangle(13);
  const auto has = [](const MeshTriangle& t, const Vec3& p) {
    return t.v[0] == p || t.v[1] == p || t.v[2] == p;
  };
  EXPECT_TRUE(has(lower, f.point(2, 1)) && has(lower, f.point(3, 2)) && has(lower, f.point(3, 1)));
  EXPECT_TRUE(has(upper, f.point(2, 1)) && has(upper, f.point(3, 2)) && has(upper, f.point(2, 2)));
  EXPECT_EQ(lower.index, 12u);
  EXPECT_FALSE(lower.two_sided);
  EXPECT_EQ(f.point(3, 2), Vec3(1.5f, f.height(3, 2), 4));
  for (uint32_t t = 0; t < 2 * 4 * 3; ++t) EXPECT_GT(f.triangle(t).normal().y(), 0) << t;
}

// A cell's two triangles read together are its triangles read one by one, bit for bit.
TEST(HeightField, CellCornersAreTheCornersOfTheCellsTriangles) {
  const HeightField f = bumpy(7, 6, 0.3f, 0.7f);
  for (uint32_t j = 0; j + 1 < f.rows; ++j) {
    for (uint32_t i = 0; i + 1 < f.columns; ++i) {
      MeshTriangle pair[2];
      f.cell_corners(i, j, pair);
      const uint32_t c = j * (f.columns - 1) + i;
      for (uint32_t k = 0; k < 2; ++k) {
        const MeshTriangle want = f.corners(2 * c + k);
        EXPECT_EQ(pair[k].index, want.index);
        EXPECT_EQ(pair[k].two_sided, want.two_sided);
        EXPECT_EQ(pair[k].active_edges, want.active_edges);
        for (int v = 0; v < 3; ++v) EXPECT_EQ(pair[k].v[v], want.v[v]) << i << " " << j;
      }
    }
  }
}

TEST(HeightField, FlatGridInteriorEdgesInactiveBorderActive) {
  const HeightField f = build_heightfield(std::vector<Real>(6 * 5, 2), 6, 1, 1);
  for (uint32_t t = 0; t < 2 * 5 * 4; ++t) {
    const MeshTriangle tri = f.triangle(t);
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = tri.v[k], b = tri.v[(k + 1) % 3];
      const bool border = (a.x() == 0 && b.x() == 0) || (a.x() == 5 && b.x() == 5) ||
                          (a.z() == 0 && b.z() == 0) || (a.z() == 4 && b.z() == 4);
      EXPECT_EQ(bool((tri.active_edges >> k) & 1), border) << t << " " << k;
    }
  }
}

// A mesh of the field's triangles: its active edges (from true adjacency) must match the field's.
TEST(HeightField, BumpyActiveEdgesMatchTheMeshOfTheSameTriangles) {
  const HeightField f = bumpy(9, 7, 1, 0.8f);
  std::vector<Vec3> v;
  for (uint32_t j = 0; j < f.rows; ++j) {
    for (uint32_t i = 0; i < f.columns; ++i) v.push_back(f.point(i, j));
  }
  const uint32_t cells = (f.columns - 1) * (f.rows - 1);
  std::vector<std::array<uint32_t, 3>> tris;
  const auto index_of = [&](const Vec3& p) {
    return uint32_t(std::lround(p.z() / f.spacing_z)) * f.columns +
           uint32_t(std::lround(p.x() / f.spacing_x));
  };
  for (uint32_t t = 0; t < 2 * cells; ++t) {
    const MeshTriangle tri = f.triangle(t);
    tris.push_back({index_of(tri.v[0]), index_of(tri.v[1]), index_of(tri.v[2])});
  }
  const TriangleMesh m = build_triangle_mesh(v, tris);
  int active = 0, inactive = 0;
  for (uint32_t t = 0; t < m.size(); ++t) {
    // Find this mesh triangle among the field's by its vertices.
    for (uint32_t u = 0; u < 2 * cells; ++u) {
      if (tris[u] != m.triangles[t]) continue;
      EXPECT_EQ(int(m.active_edges[t]), int(f.triangle(u).active_edges)) << u;
      for (int k = 0; k < 3; ++k) ((m.active_edges[t] >> k) & 1 ? active : inactive)++;
    }
  }
  EXPECT_GT(active, 0);
  EXPECT_GT(inactive, 0);
}

std::string error_field(const std::vector<Real>& h, uint32_t columns, Real sx, Real sz,
                        std::string& message) {
  try {
    build_heightfield(h, columns, sx, sz);
  } catch (const Error& e) {
    message = e.what();
    return e.field();
  }
  return "";
}

TEST(HeightField, Validation) {
  std::string m;
  EXPECT_EQ(error_field(std::vector<Real>(3, 0), 3, 1, 1, m), "shape.heights");
  EXPECT_EQ(error_field(std::vector<Real>(4, 0), 1, 1, 1, m), "shape.heights");
  EXPECT_EQ(error_field(std::vector<Real>(7, 0), 3, 1, 1, m), "shape.heights");
  EXPECT_NE(m.find("heights.size() 7 is not a multiple of columns 3"), std::string::npos) << m;
  std::vector<Real> h(6, 0);
  h[4] = INFINITY;
  EXPECT_EQ(error_field(h, 3, 1, 1, m), "shape.heights");
  EXPECT_NE(m.find("row 1, column 1"), std::string::npos) << m;
  // A NaN is a hole: here it leaves cell (1, 0)'s lower triangle, so the field is accepted.
  h[4] = NAN;
  EXPECT_EQ(error_field(h, 3, 1, 1, m), "") << m;
  // A hole on the diagonal of a field of one cell leaves no triangle.
  EXPECT_EQ(error_field(std::vector<Real>{NAN, 0, 0, 0}, 2, 1, 1, m), "shape.heights");
  EXPECT_NE(m.find("leave no triangle"), std::string::npos) << m;
  EXPECT_EQ(error_field(std::vector<Real>{0, 0, NAN, 0}, 2, 1, 1, m), "");
  h[4] = 2e5f;
  EXPECT_EQ(error_field(h, 3, 1, 1, m), "shape.heights");
  h[4] = 0;
  EXPECT_EQ(error_field(h, 3, 0, 1, m), "shape.spacing");
  EXPECT_EQ(error_field(h, 3, 1, -2, m), "shape.spacing");
  EXPECT_EQ(error_field(h, 3, INFINITY, 1, m), "shape.spacing");
  EXPECT_EQ(error_field(h, 3, 1, NAN, m), "shape.spacing");
  EXPECT_EQ(error_field(h, 3, 1, 1, m), "");
  const HeightField f = build_heightfield(std::vector<Real>{1, -2, 3, 0.5f}, 2, 1, 1);
  EXPECT_EQ(f.min_height, -2);
  EXPECT_EQ(f.max_height, 3);
  EXPECT_FALSE(f.has_holes);
  // The bounds are those of the triangles' corners: with a hole at (0, 1), cell (0, 0) keeps
  // its lower triangle (1, -2, 0.5) and cell (0, 1) has none, so (0, 2) = 4 bounds nothing.
  const HeightField g = build_heightfield(std::vector<Real>{1, -2, NAN, 0.5f, 4, 2}, 2, 1, 1);
  EXPECT_TRUE(g.has_holes);
  EXPECT_EQ(g.min_height, -2);
  EXPECT_EQ(g.max_height, 1);
}

// The ray's nearest hit t over every triangle of the field there (holes skipped), or -1.
Real nearest_hit_by_brute_force(const HeightField& f, const Vec3& o, const Vec3& d, Real max_t) {
  Real best = -1;
  for (uint32_t t = 0; t < 2 * (f.columns - 1) * (f.rows - 1); ++t) {
    if (!f.has_triangle(t)) continue;
    const MeshTriangle tri = f.triangle(t);
    Real th;
    if (ray_triangle(o, d, tri.v[0], tri.v[1], tri.v[2], max_t, th) && (best < 0 || th < best)) {
      best = th;
    }
  }
  return best;
}

// A flat 6 x 6 field (5 x 5 cells) with a hole at sample (2, 2) and one at (5, 0): the triangles
// with a hole at a corner are gone, every other is there, and each query walks the ones there.
HeightField holed() {
  std::vector<Real> h(36, Real(0.5));
  h[2 * 6 + 2] = NAN;
  h[0 * 6 + 5] = NAN;
  return build_heightfield(h, 6, 1, 1);
}

// Whether triangle t of `f` has a hole at a corner (its corners read as cell_corners makes them).
bool touches_hole(const HeightField& f, uint32_t t) {
  const MeshTriangle m = f.corners(t);
  return std::isnan(m.v[0].y()) || std::isnan(m.v[1].y()) || std::isnan(m.v[2].y());
}

TEST(HeightField, HolesTakeAwayTheTrianglesAtTheirCorners) {
  const HeightField f = holed();
  EXPECT_TRUE(f.has_holes);
  // Around (2, 2): cells (1, 1) and (2, 2) have it on their diagonal (both triangles gone), cell
  // (2, 1) at its upper triangle's corner, cell (1, 2) at its lower's. (5, 0) is cell (4, 0)'s
  // lower triangle's corner.
  EXPECT_EQ(f.cell_triangles(1, 1), 0u);
  EXPECT_EQ(f.cell_triangles(2, 2), 0u);
  EXPECT_EQ(f.cell_triangles(2, 1), 1u);
  EXPECT_EQ(f.cell_triangles(1, 2), 2u);
  EXPECT_EQ(f.cell_triangles(4, 0), 2u);
  EXPECT_EQ(f.cell_triangles(0, 0), 3u);
  uint32_t there = 0;
  for (uint32_t t = 0; t < 50; ++t) {
    EXPECT_EQ(f.has_triangle(t), !touches_hole(f, t)) << t;
    there += f.has_triangle(t);
  }
  EXPECT_EQ(there, 50u - 7u);
  // Every walk visits exactly the triangles there, in its order.
  std::vector<uint32_t> seen;
  for_each_triangle(f, Vec3(-1, -1, -1), Vec3(9, 1, 9), [&](const MeshTriangle& t) {
    EXPECT_FALSE(touches_hole(f, t.index)) << t.index;
    seen.push_back(t.index);
  });
  EXPECT_EQ(seen.size(), std::size_t(there));
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  // A box about the hole meets four cells: two with no triangle left, one each in the others.
  seen.clear();
  for_each_triangle_index(f, Vec3(1.6f, 0, 1.6f), Vec3(2.4f, 1, 2.4f),
                          [&](uint32_t t) { seen.push_back(t); });
  EXPECT_EQ(seen, (std::vector<uint32_t>{2 * (1 * 5 + 2), 2 * (2 * 5 + 1) + 1}));
  // Over cell (2, 1) alone, its lower triangle only.
  seen.clear();
  for_each_triangle_index(f, Vec3(2.2f, 0, 1.2f), Vec3(2.8f, 1, 1.8f),
                          [&](uint32_t t) { seen.push_back(t); });
  EXPECT_EQ(seen, std::vector<uint32_t>{2 * (1 * 5 + 2)});
}

// On a flat field an edge is active exactly where it is a border: of the grid, or of a hole (no
// triangle there on its other side). Counted from the corners: an edge two triangles there share
// is inside, one only one has is a border.
TEST(HeightField, TheEdgesAroundAHoleAreActive) {
  const HeightField f = holed();
  const auto key = [](const Vec3& a, const Vec3& b) {
    const auto id = [](const Vec3& p) {
      return int(std::lround(p.x())) * 100 + int(std::lround(p.z()));
    };
    const int ia = id(a), ib = id(b);
    return std::pair<int, int>(std::min(ia, ib), std::max(ia, ib));
  };
  std::map<std::pair<int, int>, int> sharing;
  for (uint32_t t = 0; t < 50; ++t) {
    if (!f.has_triangle(t)) continue;
    const MeshTriangle m = f.corners(t);
    for (int k = 0; k < 3; ++k) ++sharing[key(m.v[k], m.v[(k + 1) % 3])];
  }
  int borders = 0;
  for (uint32_t t = 0; t < 50; ++t) {
    if (!f.has_triangle(t)) continue;
    const MeshTriangle m = f.triangle(t);
    for (int k = 0; k < 3; ++k) {
      const bool border = sharing[key(m.v[k], m.v[(k + 1) % 3])] == 1;
      borders += border;
      EXPECT_EQ(bool((m.active_edges >> k) & 1), border) << t << " " << k;
    }
  }
  EXPECT_GT(borders, 20);  // the grid's 20 sides and the holes' rims
}

// Rays through the holes pass, as a brute force over the triangles there says.
TEST(HeightField, RaysPassThroughHoles) {
  std::vector<Real> h(std::size_t(30) * 25);
  std::mt19937 holes(5);
  for (uint32_t j = 0; j < 25; ++j) {
    for (uint32_t i = 0; i < 30; ++i) {
      h[j * 30 + i] =
          holes() % 6 == 0 ? Real(NAN) : Real(1.5 * std::sin(0.7 * i) * std::cos(0.45 * j));
    }
  }
  const HeightField f = build_heightfield(h, 30, 0.7f, 1.1f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> pos(-3, 30), unit(-1, 1);
  int hits = 0, misses = 0;
  for (int q = 0; q < 400; ++q) {
    const Vec3 o{pos(rng), 4 * unit(rng), pos(rng)};
    Vec3 d{unit(rng), unit(rng), unit(rng)};
    if (q % 3 == 0) d = Vec3(0, -1, 0);  // straight down: into holes or onto triangles
    const Real best = nearest_hit_by_brute_force(f, o, d, 60);
    SurfaceHit hit;
    const bool found = ray_cast_heightfield(f, o, d, 60, hit);
    ASSERT_EQ(found, best >= 0) << "ray " << q;
    if (!found) {
      misses += q % 3 == 0 && o.x() > 0 && o.x() < 20 && o.z() > 0 && o.z() < 26 && o.y() > 2;
      continue;
    }
    ++hits;
    EXPECT_EQ(hit.t, best) << "ray " << q;
    EXPECT_TRUE(f.has_triangle(hit.triangle));
  }
  EXPECT_GT(hits, 50);
  EXPECT_GT(misses, 5);  // downward rays over the field that went through a hole
}

TEST(HeightField, RayNearestHitEqualsBruteForce) {
  const HeightField f = bumpy(30, 25, 0.7f, 1.1f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> pos(-3, 30), unit(-1, 1);
  int hits = 0, below = 0;
  for (int q = 0; q < 400; ++q) {
    const Vec3 o{pos(rng), 4 * unit(rng), pos(rng)};
    Vec3 d{unit(rng), unit(rng), unit(rng)};
    if (q % 7 == 0) d = Vec3(0, q % 14 == 0 ? -1 : 1, 0);  // vertical rays
    if (q % 11 == 0) d.x() = 0;                            // rays in a z column
    const Real best = nearest_hit_by_brute_force(f, o, d, 60);
    SurfaceHit hit;
    const bool found = ray_cast_heightfield(f, o, d, 60, hit);
    ASSERT_EQ(found, best >= 0) << "ray " << q;
    if (!found) continue;
    ++hits;
    EXPECT_EQ(hit.t, best) << "ray " << q;
    EXPECT_LE(hit.normal.dot(d), 0);
    EXPECT_NEAR(std::abs(hit.normal.dot(f.triangle(hit.triangle).normal())), 1, 1e-5);
    below += hit.normal.y() < 0;  // hit from below: the normal faces the ray
  }
  EXPECT_GT(hits, 80);
  EXPECT_GT(below, 0);
}

// Rays aimed at every sample and every cell side's midpoint of a flat field 0.37 m apart (not
// exact in binary): the walk's cell boundaries must be the samples' own rounded coordinates, and
// the clip to a box of no height must not stop the walk at the hit.
TEST(HeightField, RaysAtSamplesAndEdgesOfAFlatFieldAlwaysHit) {
  const uint32_t n = 25;
  const HeightField f = build_heightfield(std::vector<Real>(n * n, 1.3f), n, 0.37f, 0.37f);
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> unit(-1, 1);
  int misses = 0;
  for (uint32_t j = 1; j + 1 < n; ++j) {
    for (uint32_t i = 1; i + 1 < n; ++i) {
      for (int k = 0; k < 4; ++k) {
        Vec3 target = f.point(i, j);
        if (k >= 2) target.x() += 0.185f;
        const Vec3 d = k % 2 == 0 ? Vec3(0, -1, 0) : Vec3{unit(rng), -1, unit(rng)}.normalized();
        SurfaceHit hit;
        if (!ray_cast_heightfield(f, target - 5 * d, d, 100, hit)) ++misses;
      }
    }
  }
  EXPECT_EQ(misses, 0);
}

// A float a sample and three bits a cell: 4 + 3/8 bytes a sample, less the last row and column.
TEST(HeightField, FourBytesASampleAndThreeBitsACell) {
  const uint32_t n = 257;
  const HeightField f = build_heightfield(std::vector<Real>(std::size_t(n) * n, 1), n, 1, 1);
  EXPECT_LE(double(heightfield_bytes(f)) / (double(n) * n), 4.4);
  EXPECT_GE(double(heightfield_bytes(f)) / (double(n) * n), 4.36);
}

TEST(HeightField, QueryVisitsTheCellsUnderTheBox) {
  const HeightField f = bumpy(10, 10, 1, 1);
  std::vector<uint32_t> seen;
  for_each_triangle(f, Vec3(2.5f, -10, 3.5f), Vec3(4.5f, 10, 4.2f),
                    [&](const MeshTriangle& t) { seen.push_back(t.index); });
  // Cells i 2..4, j 3..4: 6 cells, 12 triangles, row by row.
  ASSERT_EQ(seen.size(), 12u);
  EXPECT_EQ(seen.front(), 2 * (3 * 9 + 2));
  EXPECT_EQ(seen.back(), 2 * (4 * 9 + 4) + 1);
}

}  // namespace heightfield_test
}  // namespace elan::detail
