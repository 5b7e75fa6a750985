// SPDX-License-Identifier: MIT
// Polyhedra for SAT and clipping: a box or convex hull placed in a shared working frame (world
// rotation, origin at A's centre of mass), with the face/edge adjacency the Gauss-map test needs.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "core/base/shape.hpp"

namespace elan::detail {

// perf: fixed stack buffers (no allocation per pair). A hull beyond these sizes takes the
// general GJK/EPA path instead (see collide.cpp).
inline constexpr int kMaxPolyVertices = 256;
inline constexpr int kMaxPolyFaces = 512;
inline constexpr int kMaxPolyLoop = 1536;  // sum of face loop lengths
inline constexpr int kMaxPolyEdges = 768;

// A polyhedron in the working frame. Face normals are unit and outward; a face's plane is
// dot(normal, x) == offset. edge_faces[e] are the two faces sharing edge e.
struct Polyhedron {
  int vertex_count = 0;
  int face_count = 0;
  int edge_count = 0;
  std::array<Vec3, kMaxPolyVertices> vertices;
  std::array<Vec3, kMaxPolyFaces> normals;
  std::array<Real, kMaxPolyFaces> offsets;
  std::array<uint32_t, kMaxPolyFaces> face_first;
  std::array<uint32_t, kMaxPolyFaces> face_count_of;
  const uint32_t* face_vertices = nullptr;  // loops, counter-clockwise seen from outside
  // Topology, the shape's own (a hull's, or the unit box's): not copied per placement.
  const std::array<uint32_t, 2>* edges = nullptr;
  const std::array<uint32_t, 2>* edge_faces = nullptr;
  Vec3 centre = Vec3::Zero();  // the centre of mass, inside the solid
  // A box's half axes (rotation columns times half extents); zero for a hull.
  Vec3 half_axes[3] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  bool is_box = false;
};

// Whether the foot of p on the plane of a face (unit outward normal n, vertex loop `loop` of
// `count` indices into `vertices`, counter-clockwise seen from outside) lies on the face: inside
// every side plane, as (v1 - v0) x n points out of the face.
template <class Vertices>
bool foot_on_face(const Vertices& vertices, const uint32_t* loop, uint32_t count, const Vec3& n,
                  const Vec3& p) {
  for (uint32_t k = 0; k < count; ++k) {
    const Vec3& v0 = vertices[loop[k]];
    const Vec3& v1 = vertices[loop[(k + 1) % count]];
    if ((v1 - v0).cross(n).dot(p - v0) > 0) return false;
  }
  return true;
}

// True when `shape` is a box or a hull that fits the buffers above.
bool is_sat_polyhedron(const Shape& shape);

// The SAT's edge query visits every pair of edges (E_a x E_b, each through the Gauss-map test,
// Gregorius GDC 2013), so its cost grows with the product; GJK/EPA's with the vertices visited
// by the support search, far fewer. Above this many edge pairs a polyhedron pair goes to
// GJK/EPA: 40,000 keeps two hulls of 64 vertices (about 186 edges each) and any box against any
// hull on the SAT, whose face clipping gives the better manifold, and sends two hulls of 200
// vertices (594 edges each, 353,000 pairs, about 20 times the GJK/EPA time) to GJK/EPA.
inline constexpr std::size_t kMaxSatEdgePairs = 40000;

// True when a and b both pass is_sat_polyhedron and their edge query is within
// kMaxSatEdgePairs.
bool sat_is_affordable(const Shape& a, const Shape& b);

// Fills `out` with the shape (box or hull) at rotation `rotation`, centre of mass at `centre`.
void make_polyhedron(const Shape& shape, const Quat& rotation, const Vec3& centre, Polyhedron& out);

}  // namespace elan::detail
