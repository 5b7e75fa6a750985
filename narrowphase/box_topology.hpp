// SPDX-License-Identifier: MIT
// The unit box's topology, shared by the box polyhedron (polyhedron.cpp) and the box-box contact
// (box_box.cpp), so that both name a box's faces, edges and clipped points alike.
#pragma once

#include <array>
#include <cstdint>

namespace elan::detail {

// Vertex i has coordinate signs bit 0: x, bit 1: y, bit 2: z (set = +). Faces in the order +x,
// -x, +y, -y, +z, -z (the face ids of round_pairs.hpp: face 2k + 1 is face 2k's opposite), loops
// counter-clockwise seen from outside.
inline constexpr uint32_t kBoxLoops[24] = {1, 3, 7, 5, 0, 4, 6, 2, 2, 6, 7, 3,
                                           0, 1, 5, 4, 4, 5, 7, 6, 0, 2, 3, 1};
// Edges 4 i to 4 i + 3 run along axis i from the vertex with that sign clear; within them the
// lower of the other two axes' signs is bit 0. Each with the two faces that share it.
inline constexpr std::array<uint32_t, 2> kBoxEdges[12] = {
    {0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
inline constexpr std::array<uint32_t, 2> kBoxEdgeFaces[12] = {
    {3, 5}, {2, 5}, {3, 4}, {2, 4}, {1, 5}, {0, 5}, {1, 4}, {0, 4}, {1, 3}, {0, 3}, {1, 2}, {0, 2}};

// The edge along axis i whose other two coordinates have the signs bit_j (axis (i + 1) % 3) and
// bit_k (axis (i + 2) % 3), as numbered above.
inline constexpr int box_edge(int i, int bit_j, int bit_k) {
  const int j = (i + 1) % 3, k = (i + 2) % 3;
  return 4 * i + (j < k ? bit_j + 2 * bit_k : bit_k + 2 * bit_j);
}

}  // namespace elan::detail
