// SPDX-License-Identifier: MIT
// One triangle of a mesh or a heightfield as the narrowphase sees it: its corners in the
// surface's frame, a stable index, and which of its edges are active (Jolt's active edges).
#pragma once

#include <cstdint>

#include "elan/math.hpp"

namespace elan::detail {

// Edge k runs from v[k] to v[(k + 1) % 3]. An edge is active when a contact on it may push along
// a normal other than the face's: a boundary edge, or a convex edge whose two faces meet at more
// than kActiveEdgeAngle. An inactive edge (the two faces nearly coplanar, or the edge concave)
// lies inside a smooth surface: a contact there takes the face normal, so a body sliding across
// it does not catch on it (no ghost collisions).
inline constexpr Real kActiveEdgeCos = Real(0.996194698);  // cos(5 degrees), Jolt's default

struct MeshTriangle {
  Vec3 v[3];                 // m, the surface's shape frame; counter-clockwise seen from the front
  uint32_t index = 0;        // the triangle's index in the surface (tree order for a mesh)
  uint8_t active_edges = 7;  // bit k: edge k is active
  bool two_sided = true;     // a mesh's triangles; a heightfield's are one-sided (front = up)

  Vec3 normal() const { return (v[1] - v[0]).cross(v[2] - v[0]).normalized(); }
};

// A ray's hit with a surface: t along the ray, the triangle's unit normal facing the ray
// (dot(normal, dir) <= 0), and the triangle's index.
struct SurfaceHit {
  Real t = 0;
  Vec3 normal = Vec3::UnitY();
  uint32_t triangle = 0;
};

// Whether the edge shared by two triangles of unit normals n1 and n2, running along `edge` as
// triangle 1 walks it (counter-clockwise seen from n1's side), is active: triangles back to back
// (normals opposite) share an active edge; a concave edge is inactive; a convex one is active past
// the angle above.
inline bool edge_is_active(const Vec3& n1, const Vec3& n2, const Vec3& edge) {
  const Real cos_normals = n1.dot(n2);
  if (cos_normals < -kActiveEdgeCos) return true;
  if (n1.cross(n2).dot(edge) < 0) return false;
  return cos_normals < kActiveEdgeCos;
}

}  // namespace elan::detail
