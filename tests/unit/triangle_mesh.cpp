// SPDX-License-Identifier: MIT
// The triangle mesh: validation messages naming the triangle, active edges of flat, ridged and
// inconsistently wound surfaces, the ray against brute force, and the bytes a triangle.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/base/triangle_mesh.hpp"
#include "elan/error.hpp"

namespace elan::detail {
namespace triangle_mesh_test {

using Tri = std::array<uint32_t, 3>;

// A grid of n x n cells in the xz plane (y from `height`), two triangles a cell wound to face +y.
struct Grid {
  std::vector<Vec3> vertices;
  std::vector<Tri> triangles;
};
template <class H>
Grid make_grid(uint32_t n, H height) {
  Grid g;
  for (uint32_t j = 0; j <= n; ++j) {
    for (uint32_t i = 0; i <= n; ++i) g.vertices.emplace_back(Real(i), height(i, j), Real(j));
  }
  const auto v = [&](uint32_t i, uint32_t j) { return j * (n + 1) + i; };
  for (uint32_t j = 0; j < n; ++j) {
    for (uint32_t i = 0; i < n; ++i) {
      g.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i + 1, j)});
      g.triangles.push_back({v(i, j), v(i, j + 1), v(i + 1, j + 1)});
    }
  }
  return g;
}

std::string error_of(const std::vector<Vec3>& v, const std::vector<Tri>& t, std::string& field) {
  try {
    build_triangle_mesh(v, t);
  } catch (const Error& e) {
    field = e.field();
    return e.what();
  }
  return "";
}

TEST(TriangleMesh, ErrorsNameTheTriangleByItsGivenIndex) {
  const std::vector<Vec3> v{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(2, 0, 0)};
  std::string field;
  std::string m = error_of(v, {{0, 1, 2}, {0, 2, 1}, {0, 1, 7}}, field);
  EXPECT_EQ(field, "shape.triangles");
  EXPECT_NE(m.find("triangle 2: index 7 out of range (4 vertices)"), std::string::npos) << m;
  m = error_of(v, {{0, 1, 2}, {2, 2, 1}}, field);
  EXPECT_NE(m.find("triangle 1: repeats vertex 2"), std::string::npos) << m;
  m = error_of(v, {{0, 1, 2}, {0, 1, 2}, {0, 1, 3}}, field);  // collinear: 0, 1, 3 on x
  EXPECT_NE(m.find("triangle 2: has zero area"), std::string::npos) << m;
  m = error_of(v, {}, field);
  EXPECT_EQ(field, "shape.triangles");
  m = error_of({}, {{0, 1, 2}}, field);
  EXPECT_EQ(field, "shape.vertices");
  m = error_of({Vec3(0, 0, 0), Vec3(1, NAN, 0), Vec3(0, 0, 1)}, {{0, 1, 2}}, field);
  EXPECT_EQ(field, "shape.vertices");
  EXPECT_NE(m.find("vertex 1"), std::string::npos) << m;
  m = error_of({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 2e5f)}, {{0, 1, 2}}, field);
  EXPECT_EQ(field, "shape.vertices");
  EXPECT_NE(m.find("vertex 2"), std::string::npos) << m;
  // A thin but real triangle (1e-3 across 10 m) is kept.
  EXPECT_NO_THROW(
      build_triangle_mesh(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(5, 0, 1e-3f)},
                          std::vector<Tri>{{0, 1, 2}}));
}

// Active flags by the vertex pair of each edge.
bool edge_active(const TriangleMesh& m, uint32_t a, uint32_t b, int& seen) {
  bool active = false;
  seen = 0;
  for (uint32_t t = 0; t < m.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t p = m.triangles[t][k], q = m.triangles[t][(k + 1) % 3];
      if ((p == a && q == b) || (p == b && q == a)) {
        ++seen;
        active = (m.active_edges[t] >> k) & 1;
      }
    }
  }
  return active;
}

TEST(TriangleMesh, FlatGridInteriorEdgesInactiveBorderActive) {
  const uint32_t n = 6;
  const Grid g = make_grid(n, [](uint32_t, uint32_t) { return Real(0); });
  const TriangleMesh m = build_triangle_mesh(g.vertices, g.triangles);
  ASSERT_EQ(m.size(), 2u * n * n);
  int interior = 0, border = 0;
  for (uint32_t t = 0; t < m.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = m.vertices[m.triangles[t][k]], b = m.vertices[m.triangles[t][(k + 1) % 3]];
      const bool on_border = (a.x() == 0 && b.x() == 0) || (a.x() == n && b.x() == n) ||
                             (a.z() == 0 && b.z() == 0) || (a.z() == n && b.z() == n);
      EXPECT_EQ(bool((m.active_edges[t] >> k) & 1), on_border) << "triangle " << t << " edge " << k;
      (on_border ? border : interior)++;
    }
  }
  EXPECT_EQ(border, int(4 * n));
  EXPECT_EQ(interior, int(6 * n * n - 4 * n));
}

// Two triangles on the edge x = 0 (z from 0 to 1), the second tilted by `angle` about it (down
// for a negative angle). Triangle (0, 2, 1) faces +y; (0, 1, 3) continues it on the +x side with
// the same winding; reversing either faces it the other way.
TriangleMesh hinge(double angle, const Tri& first, const Tri& second) {
  const std::vector<Vec3> v{Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(-1, 0, Real(0.5)),
                            Vec3(Real(std::cos(angle)), Real(std::sin(angle)), Real(0.5))};
  return build_triangle_mesh(v, std::vector<Tri>{first, second});
}

// The flag of the edge (0, 1) on the triangle of the mesh that has vertex `corner`.
bool flag(const TriangleMesh& m, uint32_t corner) {
  for (uint32_t t = 0; t < m.size(); ++t) {
    const Tri& tri = m.triangles[t];
    if (tri[0] != corner && tri[1] != corner && tri[2] != corner) continue;
    for (int k = 0; k < 3; ++k) {
      if (std::min(tri[k], tri[(k + 1) % 3]) == 0 && std::max(tri[k], tri[(k + 1) % 3]) == 1) {
        return (m.active_edges[t] >> k) & 1;
      }
    }
  }
  ADD_FAILURE() << "no triangle with vertex " << corner;
  return false;
}

TEST(TriangleMesh, RidgeActiveValleyAndCoplanarInactive) {
  constexpr double deg = std::numbers::pi / 180;
  const Tri up0{0, 2, 1}, up1{0, 1, 3}, down0{0, 1, 2}, down1{0, 3, 1};
  int seen = 0;
  // Tilting the +x face down makes a ridge (convex seen from +y) of 30 degrees; up, a valley.
  EXPECT_TRUE(edge_active(hinge(-30 * deg, up0, up1), 0, 1, seen));
  EXPECT_EQ(seen, 2);
  EXPECT_TRUE(flag(hinge(-30 * deg, up0, up1), 2) && flag(hinge(-30 * deg, up0, up1), 3));
  EXPECT_FALSE(flag(hinge(30 * deg, up0, up1), 2) || flag(hinge(30 * deg, up0, up1), 3));
  EXPECT_FALSE(flag(hinge(0, up0, up1), 2) || flag(hinge(0, up0, up1), 3));
  EXPECT_FALSE(flag(hinge(-3 * deg, up0, up1), 2));  // below 5 degrees: smooth
  // Seen from below the ridge is a valley.
  EXPECT_FALSE(flag(hinge(-30 * deg, down0, down1), 2) || flag(hinge(-30 * deg, down0, down1), 3));
  EXPECT_TRUE(flag(hinge(30 * deg, down0, down1), 2) && flag(hinge(30 * deg, down0, down1), 3));
  // Inconsistent winding: each triangle's flag is what a consistently wound mesh facing its way
  // gives it (the neighbour taken as if turned to match); a flat pair stays smooth, not "back to
  // back".
  for (const double angle : {-30 * deg, 0.0, 30 * deg}) {
    const TriangleMesh mixed = hinge(angle, up0, down1);
    EXPECT_EQ(flag(mixed, 2), flag(hinge(angle, up0, up1), 2)) << angle;
    EXPECT_EQ(flag(mixed, 3), flag(hinge(angle, down0, down1), 3)) << angle;
  }
  EXPECT_FALSE(flag(hinge(0, up0, down1), 2) || flag(hinge(0, up0, down1), 3));
}

TEST(TriangleMesh, EdgeOfThreeTrianglesIsActive) {
  const std::vector<Vec3> v{Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(-1, 0, 0.5f), Vec3(1, 0, 0.5f),
                            Vec3(0, 1, 0.5f)};
  const TriangleMesh m = build_triangle_mesh(v, std::vector<Tri>{{0, 2, 1}, {0, 1, 3}, {0, 1, 4}});
  int seen = 0;
  for (uint32_t t = 0; t < 3; ++t) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t p = m.triangles[t][k], q = m.triangles[t][(k + 1) % 3];
      if (std::min(p, q) == 0 && std::max(p, q) == 1) {
        ++seen;
        EXPECT_TRUE((m.active_edges[t] >> k) & 1);
      }
    }
  }
  EXPECT_EQ(seen, 3);
}

TEST(TriangleMesh, RayNearestHitEqualsBruteForce) {
  const Grid g = make_grid(
      40, [](uint32_t i, uint32_t j) { return Real(2 * std::sin(0.3 * i) * std::cos(0.2 * j)); });
  const TriangleMesh m = build_triangle_mesh(g.vertices, g.triangles);
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> pos(-5, 45), unit(-1, 1);
  int hits = 0;
  for (int q = 0; q < 300; ++q) {
    const Vec3 o{pos(rng), 3 + unit(rng) * 4, pos(rng)};
    const Vec3 d{unit(rng), unit(rng), unit(rng)};
    Real best = -1;
    uint32_t best_tri = 0;
    for (uint32_t t = 0; t < m.size(); ++t) {
      const MeshTriangle tri = m.triangle(t);
      Real th;
      if (ray_triangle(o, d, tri.v[0], tri.v[1], tri.v[2], 100, th) && (best < 0 || th < best)) {
        best = th, best_tri = t;
      }
    }
    SurfaceHit hit;
    const bool found = ray_cast_mesh(m, o, d, 100, hit);
    ASSERT_EQ(found, best >= 0) << "ray " << q;
    if (!found) continue;
    ++hits;
    EXPECT_EQ(hit.t, best);
    const Vec3 n = m.triangle(hit.triangle).normal();
    EXPECT_LE(hit.normal.dot(d), 0);
    EXPECT_NEAR(std::abs(hit.normal.dot(n)), 1, 1e-5);
    if (hit.triangle != best_tri) {  // a tie on a shared edge: the same t
      EXPECT_EQ(hit.t, best);
    }
  }
  EXPECT_GT(hits, 50);
}

TEST(TriangleMesh, RayHitsFromBothSidesWithTheNormalFacingTheRay) {
  const Grid g = make_grid(4, [](uint32_t, uint32_t) { return Real(1); });
  const TriangleMesh m = build_triangle_mesh(g.vertices, g.triangles);
  SurfaceHit hit;
  ASSERT_TRUE(ray_cast_mesh(m, Vec3(1.3f, 5, 2.6f), Vec3(0, -2, 0), 10, hit));
  EXPECT_NEAR(hit.t, 2, 1e-6);
  EXPECT_NEAR(hit.normal.y(), 1, 1e-6);
  ASSERT_TRUE(ray_cast_mesh(m, Vec3(1.3f, -3, 2.6f), Vec3(0, 1, 0), 10, hit));
  EXPECT_NEAR(hit.t, 4, 1e-6);
  EXPECT_NEAR(hit.normal.y(), -1, 1e-6);
  EXPECT_FALSE(ray_cast_mesh(m, Vec3(1.3f, -3, 2.6f), Vec3(0, 1, 0), 3.9f, hit));
  EXPECT_FALSE(ray_cast_mesh(m, Vec3(5.5f, 5, 2), Vec3(0, -1, 0), 10, hit));
}

// Rays aimed at every vertex and every edge midpoint of a flat grid whose coordinates are not
// exact in binary (0.37 m apart): the triangles around the point, and their tree boxes (flat,
// with no thickness), must leave no crack of rounding for the ray to pass through.
TEST(TriangleMesh, RaysAtVerticesAndEdgesOfAFlatGridAlwaysHit) {
  const uint32_t n = 24;
  Grid g = make_grid(n, [](uint32_t, uint32_t) { return Real(1.3f); });
  for (Vec3& v : g.vertices) v = Vec3(v.x() * 0.37f, v.y(), v.z() * 0.37f);
  const TriangleMesh m = build_triangle_mesh(g.vertices, g.triangles);
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> unit(-1, 1);
  int misses = 0;
  for (uint32_t j = 1; j < n; ++j) {
    for (uint32_t i = 1; i < n; ++i) {
      for (int k = 0; k < 4; ++k) {
        Vec3 target(Real(i) * 0.37f, 1.3f, Real(j) * 0.37f);
        if (k >= 2) target.x() += 0.185f;
        const Vec3 d = k % 2 == 0 ? Vec3(0, -1, 0) : Vec3{unit(rng), -1, unit(rng)}.normalized();
        SurfaceHit hit;
        if (!ray_cast_mesh(m, target - 5 * d, d, 100, hit)) ++misses;
      }
    }
  }
  EXPECT_EQ(misses, 0);
}

TEST(TriangleMesh, GridMeshTakesAtMost32BytesATriangle) {
  const uint32_t n = 256;
  const Grid g =
      make_grid(n, [](uint32_t i, uint32_t j) { return Real((i * 7 + j * 3) % 5) * 0.1f; });
  const TriangleMesh m = build_triangle_mesh(g.vertices, g.triangles);
  const double per_triangle = double(mesh_bytes(m)) / double(m.size());
  // The budget is the float build's; a double build's vertices are twice as big.
  const double wider_vertices =
      double(sizeof(Vec3) - 12) * double(m.vertices.size()) / double(m.size());
  EXPECT_LE(per_triangle, 32.0 + wider_vertices);
  EXPECT_GT(per_triangle, 19.0);  // indices, flags and vertices alone: the count is real
}

TEST(TriangleMesh, TrianglesAreInLeafOrderAndQueriesFindThem) {
  const Grid g = make_grid(20, [](uint32_t i, uint32_t j) { return Real(i + j) * 0.05f; });
  const TriangleMesh m = build_triangle_mesh(g.vertices, g.triangles);
  // One box, then boxes of random size and place whose faces often lie on the grid's own
  // coordinates (a corner exactly on a face meets the box).
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> cell(-2, 42);
  int nonempty = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Vec3 lo(3.5f, -1, 7.5f), hi(6.5f, 5, 9.5f);
    if (trial > 0) {
      for (int k = 0; k < 3; ++k) {
        const Real a = Real(cell(rng)) * Real(0.5), b = Real(cell(rng)) * Real(0.5);
        lo[k] = std::min(a, b), hi[k] = std::max(a, b);
      }
      lo.y() *= Real(0.1), hi.y() *= Real(0.1);
    }
    std::vector<uint32_t> found;
    for_each_triangle(m, lo, hi, [&](const MeshTriangle& t) { found.push_back(t.index); });
    std::vector<uint32_t> expected;
    for (uint32_t t = 0; t < m.size(); ++t) {
      const MeshTriangle tri = m.triangle(t);
      const Vec3 tlo = tri.v[0].cwiseMin(tri.v[1]).cwiseMin(tri.v[2]);
      const Vec3 thi = tri.v[0].cwiseMax(tri.v[1]).cwiseMax(tri.v[2]);
      if (!((tlo.array() > hi.array()).any() || (thi.array() < lo.array()).any())) {
        expected.push_back(t);
      }
    }
    std::vector<uint32_t> sorted = found;
    std::sort(sorted.begin(), sorted.end());
    ASSERT_EQ(sorted, expected) << "trial " << trial;
    if (trial == 0) {
      EXPECT_FALSE(expected.empty());
    }
    nonempty += expected.empty() ? 0 : 1;
  }
  EXPECT_GT(nonempty, 100);
}

}  // namespace triangle_mesh_test
}  // namespace elan::detail
