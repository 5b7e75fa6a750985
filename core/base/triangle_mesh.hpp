// SPDX-License-Identifier: MIT
// A static triangle mesh: vertices, triangles stored in the order of their bounding-volume tree
// (a leaf is one contiguous range), and each triangle's active edges from its neighbours.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/bvh4.hpp"
#include "core/base/mesh_triangle.hpp"
#include "elan/math.hpp"

namespace elan::detail {

// perf: under 32 bytes a triangle with its tree: 12 of indices, 1 of edge flags, ~6 of shared
// vertices on a grid, ~10 of nodes at up to 8 triangles a leaf (the 4-wide tree: 128-byte nodes,
// about one per twelve triangles).
struct TriangleMesh {
  std::vector<Vec3> vertices;                      // m, shape frame
  std::vector<std::array<uint32_t, 3>> triangles;  // tree order
  std::vector<uint8_t> active_edges;               // per triangle: bit k, edge v[k] -> v[k + 1]
  Bvh4 tree;                                       // leaves index `triangles` directly
  Vec3 min = Vec3::Zero(), max = Vec3::Zero();     // bounds of the vertices used

  std::size_t size() const { return triangles.size(); }
  MeshTriangle triangle(uint32_t t) const {
    MeshTriangle m;
    for (int k = 0; k < 3; ++k) m.v[k] = vertices[triangles[t][k]];
    m.index = t;
    m.active_edges = active_edges[t];
    m.two_sided = true;
    return m;
  }
};

// Builds the mesh: checks the input, finds each edge's neighbour (an edge shared by more than two
// triangles is active), builds the tree (binned SAH, leaves of at most 8 triangles, collapsed
// 4-wide) and reorders the triangles into its leaf order. Throws elan::Error with field
// "shape.triangles" ("triangle 12: index 40 out of range (30 vertices)", "... repeats vertex 3",
// "... has zero area") or "shape.vertices" (none, or not finite, or past the supported
// coordinates).
TriangleMesh build_triangle_mesh(std::span<const Vec3> vertices,
                                 std::span<const std::array<uint32_t, 3>> triangles);

// Calls f(uint32_t t, const Vec3& a, const Vec3& b, const Vec3& c) for every triangle t whose box
// overlaps [lo, hi] (shape frame), with its corners where the mesh keeps them, in tree order: the
// same order every time.
template <class F>
void for_each_triangle_in_place(const TriangleMesh& mesh, const Vec3& lo, const Vec3& hi, F&& f) {
  bvh4_query(mesh.tree, lo, hi, [&](uint32_t first, uint32_t count) {
    for (uint32_t t = first; t < first + count; ++t) {
      // The triangle's box misses [lo, hi] when all three corners lie beyond one of its faces.
      // perf: tested on the corners in place, axis by axis, stopping at the first that misses.
      const std::array<uint32_t, 3>& corner = mesh.triangles[t];
      const Vec3 &a = mesh.vertices[corner[0]], &b = mesh.vertices[corner[1]],
                 &c = mesh.vertices[corner[2]];
      bool misses = false;
      for (int k = 0; k < 3 && !misses; ++k) {
        misses = (a[k] > hi[k] && b[k] > hi[k] && c[k] > hi[k]) ||
                 (a[k] < lo[k] && b[k] < lo[k] && c[k] < lo[k]);
      }
      if (!misses) f(t, a, b, c);
    }
  });
}

// Calls f(const MeshTriangle&) for the same triangles in the same order: each copied out.
template <class F>
void for_each_triangle(const TriangleMesh& mesh, const Vec3& lo, const Vec3& hi, F&& f) {
  for_each_triangle_in_place(mesh, lo, hi, [&](uint32_t t, const Vec3&, const Vec3&, const Vec3&) {
    f(mesh.triangle(t));
  });
}

// The nearest hit of the ray origin + t dir, t in [0, max_t] (shape frame; dir need not be
// unit), with either side of a triangle, the lower triangle on a tie (a ray through a shared
// edge); false when it hits nothing.
bool ray_cast_mesh(const TriangleMesh& mesh, const Vec3& origin, const Vec3& dir, Real max_t,
                   SurfaceHit& hit);

// The ray against one triangle (Moller-Trumbore), either side; `t` only if it hits in [0, max_t].
bool ray_triangle(const Vec3& origin, const Vec3& dir, const Vec3& a, const Vec3& b, const Vec3& c,
                  Real max_t, Real& t);

// Bytes the mesh holds (its vectors' capacities).
std::size_t mesh_bytes(const TriangleMesh& mesh);

}  // namespace elan::detail
