// SPDX-License-Identifier: MIT
// A 4-wide bounding-volume hierarchy: the binary tree of bvh.hpp collapsed so that every node
// holds up to four children side by side (the multi-branching BVH of Wald, Benthin and Boulos
// 2008, "Getting rid of packets"; Embree's BVH4). A box query tests a node's four boxes together,
// without a branch per box, down a path about half as deep as the binary tree's. The collapse
// keeps every node's children in order, so the leaves come in the binary tree's order: a walk
// meets the same leaves in the same order, and what it feeds gives the same bits.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "core/base/bvh.hpp"
#include "elan/math.hpp"

namespace elan::detail {

// A child slot's count when the slot is empty (a node of fewer than four children).
inline constexpr uint32_t kBvh4Empty = 0xFFFFFFFFu;

// perf: 128 bytes, two cache lines, each axis's four bounds contiguous so that one vector compare
// tests all four children. Depth first: a node's inner children follow it in order, each with its
// subtree. A child slot is an inner node (count 0, index its node), a leaf (count > 0, index its
// first item: order[index .. index + count)) or empty (count kBvh4Empty, its box inverted:
// min +inf, max -inf, which no finite box meets).
struct alignas(64) Bvh4Node {
  float min[3][4];  // [axis][child]
  float max[3][4];
  uint32_t index[4];
  uint32_t count[4];
};
static_assert(sizeof(Bvh4Node) == 128, "Bvh4Node: 128 bytes");

struct Bvh4 {
  std::vector<Bvh4Node> nodes;  // root first; empty for no items
};

// The binary tree collapsed: each node takes its binary node's two children, then, while it has
// fewer than four and one of them is an inner node, replaces the inner child of largest surface
// area by its two children in its place (so the children stay in order). Leaves stay as they are;
// no deeper than the binary tree.
Bvh4 collapse_to_bvh4(const Bvh& binary);

// Bit k set: child k of `n` overlaps [lo, hi] (node_overlaps' test, float for float: a child
// is missed when the box lies beyond one of its faces; a NaN compares false either way).
inline uint32_t bvh4_overlaps(const Bvh4Node& n, const Vec3& lo, const Vec3& hi) {
#if defined(__SSE2__)
  // perf: the four children in one compare per face; GCC leaves the scalar loop below scalar.
  __m128 miss = _mm_setzero_ps();
  for (int a = 0; a < 3; ++a) {
    miss = _mm_or_ps(miss, _mm_cmpgt_ps(_mm_set1_ps(float(lo[a])), _mm_load_ps(n.max[a])));
    miss = _mm_or_ps(miss, _mm_cmplt_ps(_mm_set1_ps(float(hi[a])), _mm_load_ps(n.min[a])));
  }
  return uint32_t(~_mm_movemask_ps(miss)) & 0xFu;
#else
  uint32_t mask = 0;
  for (int k = 0; k < 4; ++k) {
    bool miss = false;
    for (int a = 0; a < 3; ++a) {
      miss = miss || float(lo[a]) > n.max[a][k] || float(hi[a]) < n.min[a][k];
    }
    mask |= uint32_t(!miss) << k;
  }
  return mask;
#endif
}

// Calls leaf(first, count) for every leaf whose box overlaps [lo, hi], depth first, children in
// order: the binary tree's leaves in the binary tree's order (bvh_query's). Each node's children
// are tested together; the walk goes on into the first inner child that overlaps and keeps the
// node's remaining children on the stack.
template <class Leaf>
void bvh4_query(const Bvh4& tree, const Vec3& lo, const Vec3& hi, Leaf&& leaf) {
  if (tree.nodes.empty()) return;
  const Bvh4Node* nodes = tree.nodes.data();
  struct Pending {
    uint32_t node, mask;
  };
  std::array<Pending, kBvhMaxDepth + 1> stack;
  int top = 0;
  uint32_t node = 0;
  uint32_t mask = bvh4_overlaps(nodes[0], lo, hi);
  for (;;) {
    while (mask != 0) {
      const int k = std::countr_zero(mask);
      mask &= mask - 1;
      const Bvh4Node& n = nodes[node];
      const uint32_t count = n.count[k];
      if (count == 0) {
        if (mask != 0) stack[top++] = {node, mask};
        node = n.index[k];
        mask = bvh4_overlaps(nodes[node], lo, hi);
      } else if (count != kBvh4Empty) {
        leaf(n.index[k], count);
      }
    }
    if (top == 0) return;
    --top;
    node = stack[top].node;
    mask = stack[top].mask;
  }
}

// Slab test of the ray against child k of `n` (ray_enters_node's).
Real ray_enters_child(const Bvh4Node& n, int k, const Vec3& origin, const Vec3& inv_dir,
                      Real max_t);

// Calls leaf(first, count, max_t) for each leaf the ray reaches before `max_t`, nearer children
// first (ties: the earlier child first); leaf returns the new max_t (the nearest hit so far),
// which prunes the rest. A leaf entered exactly at max_t is still visited, so a caller that
// breaks ties between equal hits by item sees them all.
template <class Leaf>
void bvh4_ray(const Bvh4& tree, const Vec3& origin, const Vec3& dir, Real max_t, Leaf&& leaf) {
  if (tree.nodes.empty()) return;
  const Vec3 inv = inverse_direction(dir);
  struct Pending {
    uint32_t index, count;  // count 0: a node
    Real t;                 // where the ray enters it
  };
  // Each node visited replaces itself by at most four: three more entries a level.
  std::array<Pending, 3 * (kBvhMaxDepth + 1) + 1> stack;
  int top = 0;
  stack[top++] = {0, 0, 0};
  while (top > 0) {
    const Pending p = stack[--top];
    if (p.t > max_t) continue;
    if (p.count != 0) {
      max_t = leaf(p.index, p.count, max_t);
      continue;
    }
    const Bvh4Node& n = tree.nodes[p.index];
    Pending hit[4];
    int m = 0;
    for (int k = 0; k < 4; ++k) {
      if (n.count[k] == kBvh4Empty) continue;
      const Real t = ray_enters_child(n, k, origin, inv, max_t);
      if (t < 0) continue;
      // Insertion by entry, after the children entered as early (ties keep the child order).
      int at = m++;
      while (at > 0 && hit[at - 1].t > t) hit[at] = hit[at - 1], --at;
      hit[at] = {n.index[k], n.count[k], t};
    }
    // The nearest last, so that it is taken next.
    while (m > 0) stack[top++] = hit[--m];
  }
}

// Bytes the tree holds.
inline std::size_t bvh4_bytes(const Bvh4& tree) {
  return tree.nodes.capacity() * sizeof(Bvh4Node);
}

}  // namespace elan::detail
