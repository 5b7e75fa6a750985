// SPDX-License-Identifier: MIT
// Convex hull of a point cloud: vertices, merged planar faces with ordered loops, unique edges.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "elan/math.hpp"

namespace elan::detail {

struct HullFace {
  Vec3 normal;     // unit, outward
  Real offset;     // m: points x on the face satisfy dot(normal, x) == offset
  uint32_t first;  // into ConvexHull::face_vertices
  uint32_t count;  // vertex loop length (>= 3), counter-clockwise seen from outside
};

struct ConvexHull {
  std::vector<Vec3> vertices;                  // m, only the hull's extreme points
  std::vector<HullFace> faces;                 // coplanar triangles merged into one polygon
  std::vector<uint32_t> face_vertices;         // vertex indices of every face loop
  std::vector<std::array<uint32_t, 2>> edges;  // each undirected edge once, [0] < [1]
  // Per edge, the face whose loop runs edges[e][0] -> edges[e][1] and the face whose loop runs
  // back; topology only, so it is built once here rather than in every SAT edge query.
  std::vector<std::array<uint32_t, 2>> edge_faces;
};

// Builds the hull of `points` (quickhull with coplanar-face merging; interior and duplicate
// points dropped). Throws elan::Error with field "points" for fewer than 4 points, non-finite
// points, or a cloud that is coplanar, collinear or a single point (relative tolerance).
ConvexHull build_convex_hull(std::span<const Vec3> points);

// Fills hull.edge_faces from the face loops and edges (called by build_convex_hull; a reader
// of saved hulls calls it too, since the adjacency is derived, not stored).
void compute_edge_faces(ConvexHull& hull);

// Re-expresses a hull in another frame: x' = rotation * (x - origin). Faces and edges keep order.
ConvexHull transform_hull(const ConvexHull& hull, const Vec3& origin, const Mat3& rotation);

}  // namespace elan::detail
