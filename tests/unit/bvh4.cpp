// SPDX-License-Identifier: MIT
// The 4-wide tree against the binary one it is collapsed from: box queries report the same leaves
// in the same order (what the mesh walk, and so the contact candidates' bits, depend on), rays
// the nearest hit, every tied item reached; the collapsed tree's shape.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "core/base/bvh4.hpp"
#include "unit/random_boxes.hpp"

namespace elan::detail {
namespace bvh4_test {

using tree_test::random_box;
using tree_test::random_boxes;
using tree_test::ray_box;

// Depth first with the inner children in order, every binary leaf once, no deeper than the
// binary tree, the empty slots last and inverted; returns the depth.
int check_shape(const Bvh4& t, const Bvh& binary) {
  std::size_t leaves = 0, binary_leaves = 0;
  for (const BvhNode& n : binary.nodes) binary_leaves += n.leaf();
  int deepest = 0;
  std::size_t next = 0;
  std::vector<std::pair<uint32_t, int>> stack{{0u, 0}};
  while (!stack.empty()) {
    const auto [i, depth] = stack.back();
    stack.pop_back();
    EXPECT_EQ(i, next++);
    deepest = std::max(deepest, depth);
    const Bvh4Node& n = t.nodes[i];
    for (int k = 3; k >= 0; --k) {
      if (n.count[k] == kBvh4Empty) {
        EXPECT_GT(n.min[0][k], n.max[0][k]);
        continue;
      }
      if (n.count[k] == 0) {
        stack.emplace_back(n.index[k], depth + 1);
      } else {
        ++leaves;
      }
    }
    // Filled slots first: an empty slot is never followed by a child.
    for (int k = 0; k + 1 < 4; ++k) {
      if (n.count[k] == kBvh4Empty) {
        EXPECT_EQ(n.count[k + 1], kBvh4Empty);
      }
    }
  }
  EXPECT_EQ(next, t.nodes.size());
  EXPECT_EQ(leaves, binary_leaves);
  return deepest;
}

TEST(Bvh4, CollapseKeepsTheLeavesInOrderAndShortensTheTree) {
  const auto boxes = random_boxes(5000, 11);
  std::vector<uint32_t> order;
  const Bvh binary = build_bvh(boxes, 4, order);
  const Bvh4 wide = collapse_to_bvh4(binary);
  const int depth = check_shape(wide, binary);
  // The binary tree's depth, for the comparison: about half of it here (5 against 13).
  int binary_depth = 0;
  std::vector<std::pair<uint32_t, int>> stack{{0u, 0}};
  while (!stack.empty()) {
    const auto [i, d] = stack.back();
    stack.pop_back();
    binary_depth = std::max(binary_depth, d);
    if (!binary.nodes[i].leaf()) {
      stack.emplace_back(i + 1, d + 1);
      stack.emplace_back(binary.nodes[i].index, d + 1);
    }
  }
  std::printf("depth %d binary %d nodes %zu binary %zu\n", depth, binary_depth, wide.nodes.size(),
              binary.nodes.size());
  EXPECT_LE(depth, (binary_depth + 1) / 2 + 1);
  // About a quarter of the binary tree's nodes (880 of 3,395 here), four times the size: the
  // same bytes.
  EXPECT_LT(wide.nodes.size(), binary.nodes.size() * 3 / 10);
}

// The property the mesh's bits rest on: for any box, the 4-wide walk reports exactly the binary
// walk's leaves, in the binary walk's order.
TEST(Bvh4, BoxQueriesReportTheBinaryTreesLeavesInItsOrder) {
  for (const uint32_t leaf_size : {1u, 4u, 8u}) {
    const auto boxes = random_boxes(4000, 20 + leaf_size);
    std::vector<uint32_t> order;
    const Bvh binary = build_bvh(boxes, int(leaf_size), order);
    const Bvh4 wide = collapse_to_bvh4(binary);
    std::mt19937 rng(21);
    std::uniform_real_distribution<Real> pos(-55, 55), size(0.05f, 20);
    int reported = 0;
    for (int q = 0; q < 400; ++q) {
      const Aabb query = random_box(rng, pos, size);
      // Some boxes with a face on an item's own bound, where the comparison's tie decides.
      Vec3 lo = query.min, hi = query.max;
      if (q % 7 == 0) lo.x() = boxes[q].max.x(), hi.x() = lo.x() + 1;
      std::vector<std::pair<uint32_t, uint32_t>> expected, found;
      bvh_query(binary, lo, hi,
                [&](uint32_t first, uint32_t count) { expected.emplace_back(first, count); });
      bvh4_query(wide, lo, hi,
                 [&](uint32_t first, uint32_t count) { found.emplace_back(first, count); });
      ASSERT_EQ(found, expected) << "leaf size " << leaf_size << " query " << q;
      reported += int(found.size());
    }
    EXPECT_GT(reported, 1000);
  }
}

// The nearest hit equals brute force's, and a caller breaking ties by item sees every tied item:
// boxes in identical pairs, so that every hit is a tie, and the lower item must win.
TEST(Bvh4, RayNearestHitEqualsBruteForceAndEveryTieIsReached) {
  auto boxes = random_boxes(1500, 30, 40);
  const std::size_t n = boxes.size();
  boxes.insert(boxes.end(), boxes.begin(), boxes.end());  // item k + n is item k again
  std::vector<uint32_t> order;
  const Bvh4 tree = collapse_to_bvh4(build_bvh(boxes, 4, order));
  std::mt19937 rng(31);
  std::uniform_real_distribution<Real> pos(-50, 50), unit(-1, 1);
  int hits = 0;
  for (int q = 0; q < 400; ++q) {
    const Vec3 o{pos(rng), pos(rng), pos(rng)};
    Vec3 d{unit(rng), unit(rng), unit(rng)};
    if (q % 10 == 0) d = Vec3(0, q % 20 == 0 ? 1 : -1, 0);  // axis-parallel rays too
    const Real max_t = 200;
    Real best = -1;
    uint32_t best_item = 0;
    for (uint32_t k = 0; k < boxes.size(); ++k) {
      const Real t = ray_box(boxes[k], o, d, max_t);
      if (t >= 0 && (best < 0 || t < best)) best = t, best_item = k;
    }
    Real found = -1;
    uint32_t found_item = 0;
    bvh4_ray(tree, o, d, max_t, [&](uint32_t first, uint32_t count, Real limit) {
      for (uint32_t k = first; k < first + count; ++k) {
        const uint32_t item = order[k];
        const Real t = ray_box(boxes[item], o, d, limit);
        if (t < 0) continue;
        if (found >= 0 && (t > found || (t == found && item > found_item))) continue;
        found = t, found_item = item, limit = t;
      }
      return limit;
    });
    ASSERT_EQ(found, best) << "ray " << q;
    if (best >= 0) {
      EXPECT_EQ(found_item, best_item) << "ray " << q;
      EXPECT_LT(found_item, n);
    }
    hits += best >= 0;
  }
  EXPECT_GT(hits, 30);
}

TEST(Bvh4, TinyTrees) {
  std::vector<uint32_t> order;
  EXPECT_TRUE(collapse_to_bvh4(build_bvh({}, 4, order)).nodes.empty());
  const auto boxes = random_boxes(3, 40);
  // One leaf: a root of one leaf child and three empty slots.
  const Bvh4 one = collapse_to_bvh4(build_bvh(boxes, 8, order));
  ASSERT_EQ(one.nodes.size(), 1u);
  EXPECT_EQ(one.nodes[0].index[0], 0u);
  EXPECT_EQ(one.nodes[0].count[0], 3u);
  for (int k = 1; k < 4; ++k) EXPECT_EQ(one.nodes[0].count[k], kBvh4Empty);
  std::vector<std::pair<uint32_t, uint32_t>> found;
  bvh4_query(one, Vec3::Constant(-100), Vec3::Constant(100),
             [&](uint32_t first, uint32_t count) { found.emplace_back(first, count); });
  EXPECT_EQ(found, (std::vector<std::pair<uint32_t, uint32_t>>{{0u, 3u}}));
  // Three leaves of one: a root of three leaf children.
  const Bvh4 three = collapse_to_bvh4(build_bvh(boxes, 1, order));
  ASSERT_EQ(three.nodes.size(), 1u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(three.nodes[0].count[k], 1u);
  EXPECT_EQ(three.nodes[0].count[3], kBvh4Empty);
}

}  // namespace bvh4_test
}  // namespace elan::detail
