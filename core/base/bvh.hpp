// SPDX-License-Identifier: MIT
// A static bounding-volume hierarchy over item boxes (mesh triangles, compound children): built
// once by binned SAH, stored depth first in 32-byte nodes, walked in one fixed order.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "elan/math.hpp"

namespace elan::detail {

// An axis-aligned box, m.
struct Aabb {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
};

// perf: 32 bytes in float, two to a cache line. Depth first: an inner node's first child is the
// next node, its second at `index`; a leaf's items are order[index .. index + count).
struct BvhNode {
  float min[3];
  uint32_t index;
  float max[3];
  uint32_t count;  // 0: inner node

  bool leaf() const { return count != 0; }
};
static_assert(sizeof(BvhNode) == 32, "BvhNode: 32 bytes");

// The builder never goes deeper than this, so a walk's stack is a fixed array.
inline constexpr int kBvhMaxDepth = 64;

struct Bvh {
  std::vector<BvhNode> nodes;  // root first; empty for no items
};

// Builds the tree of `boxes` with at most `leaf_size` items a leaf (binned SAH, 16 bins on the
// longest axis of the centroids' box; a node that no split improves, or at the depth limit,
// stays a leaf whatever its count). `order` receives the items in leaf order: a caller that owns
// its items (a mesh's triangles) stores them in that order, so a leaf is one contiguous range.
// Deterministic: a function of the boxes alone. Node boxes are rounded outward to float.
Bvh build_bvh(std::span<const Aabb> boxes, int leaf_size, std::vector<uint32_t>& order);

// Whether node `n` overlaps the box [lo, hi].
inline bool node_overlaps(const BvhNode& n, const Vec3& lo, const Vec3& hi) {
  return !(float(lo.x()) > n.max[0] || float(hi.x()) < n.min[0] || float(lo.y()) > n.max[1] ||
           float(hi.y()) < n.min[1] || float(lo.z()) > n.max[2] || float(hi.z()) < n.min[2]);
}

// Calls leaf(first, count) for every leaf whose box overlaps [lo, hi], depth first, first child
// first: the same order every time, that of the leaves in `nodes` (a node's box holds its
// children's, so a leaf is reached exactly when its own box overlaps). The items of a leaf are
// order[first .. first + count). perf: an inner node's two children are tested together, before
// either is entered, so that their loads overlap (the walk of a large mesh waits on them), and
// the walk goes on into the first child without a trip through the stack.
template <class Leaf>
void bvh_query(const Bvh& tree, const Vec3& lo, const Vec3& hi, Leaf&& leaf) {
  if (tree.nodes.empty()) return;
  const BvhNode* nodes = tree.nodes.data();
  if (!node_overlaps(nodes[0], lo, hi)) return;
  std::array<uint32_t, kBvhMaxDepth + 1> stack;
  int top = 0;
  uint32_t i = 0;
  for (;;) {
    const BvhNode& n = nodes[i];
    if (n.leaf()) {
      leaf(n.index, n.count);
      if (top == 0) return;
      i = stack[--top];
      continue;
    }
    const uint32_t first = i + 1, second = n.index;
    const bool in_first = node_overlaps(nodes[first], lo, hi);
    const bool in_second = node_overlaps(nodes[second], lo, hi);
    if (in_first) {
      if (in_second) stack[top++] = second;  // after the first's subtree
      i = first;
    } else if (in_second) {
      i = second;
    } else {
      if (top == 0) return;
      i = stack[--top];
    }
  }
}

// 1 / dir per axis, infinite for a zero component: the slab test's inv_dir.
inline Vec3 inverse_direction(const Vec3& dir) {
  Vec3 inv;
  for (int k = 0; k < 3; ++k) {
    inv[k] = dir[k] != 0 ? Real(1) / dir[k] : std::numeric_limits<Real>::infinity();
  }
  return inv;
}

// Slab test of the ray origin + t dir, t in [0, max_t], against node `n`; inv_dir =
// inverse_direction(dir). Returns the entry t, or a negative value for a miss.
Real ray_enters_node(const BvhNode& n, const Vec3& origin, const Vec3& inv_dir, Real max_t);

// Calls leaf(first, count, max_t) for each leaf the ray reaches before `max_t`, nearer subtree
// first; leaf returns the new max_t (the nearest hit so far), which prunes the rest.
template <class Leaf>
void bvh_ray(const Bvh& tree, const Vec3& origin, const Vec3& dir, Real max_t, Leaf&& leaf) {
  if (tree.nodes.empty()) return;
  const Vec3 inv = inverse_direction(dir);
  std::array<uint32_t, kBvhMaxDepth + 1> stack;
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const uint32_t i = stack[--top];
    const BvhNode& n = tree.nodes[i];
    if (ray_enters_node(n, origin, inv, max_t) < 0) continue;
    if (n.leaf()) {
      max_t = leaf(n.index, n.count, max_t);
      continue;
    }
    const uint32_t first = i + 1, second = n.index;
    const Real t1 = ray_enters_node(tree.nodes[first], origin, inv, max_t);
    const Real t2 = ray_enters_node(tree.nodes[second], origin, inv, max_t);
    // The nearer child is walked first (pushed last); ties keep the first child first.
    if (t2 >= 0 && t1 >= 0 && t2 < t1) {
      stack[top++] = first;
      stack[top++] = second;
    } else {
      if (t2 >= 0) stack[top++] = second;
      if (t1 >= 0) stack[top++] = first;
    }
  }
}

// Bytes the tree holds.
inline std::size_t bvh_bytes(const Bvh& tree) {
  return tree.nodes.capacity() * sizeof(BvhNode);
}

}  // namespace elan::detail
