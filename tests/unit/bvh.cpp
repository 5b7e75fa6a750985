// SPDX-License-Identifier: MIT
// The bounding-volume hierarchy against brute force: box queries find exactly the overlapping
// items in one fixed order, rays the nearest hit; the tree's shape invariants.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "core/base/bvh.hpp"
#include "unit/random_boxes.hpp"

namespace elan::detail {
namespace bvh_test {

using tree_test::random_box;
using tree_test::random_boxes;
using tree_test::ray_box;

bool overlaps(const Aabb& b, const Vec3& lo, const Vec3& hi) {
  return !((b.min.array() > hi.array()).any() || (b.max.array() < lo.array()).any());
}

// Every node's box contains its items' (leaves) or its children's (inner) boxes; every item is
// in exactly one leaf; no leaf is deeper than the walk's stack allows.
void check_tree(const Bvh& tree, const std::vector<Aabb>& boxes, const std::vector<uint32_t>& order,
                uint32_t leaf_size) {
  std::vector<int> seen(boxes.size(), 0);
  const auto contains = [](const BvhNode& n, const Aabb& b) {
    for (int a = 0; a < 3; ++a) {
      if (!(n.min[a] <= b.min[a] && n.max[a] >= b.max[a])) return false;
    }
    return true;
  };
  struct Item {
    uint32_t node;
    int depth;
  };
  std::vector<Item> stack{{0, 0}};
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    const BvhNode& n = tree.nodes[it.node];
    ASSERT_LE(it.depth, kBvhMaxDepth);
    if (n.leaf()) {
      EXPECT_LE(n.count, leaf_size);  // random boxes: splits always pay
      for (uint32_t k = n.index; k < n.index + n.count; ++k) {
        ++seen[order[k]];
        EXPECT_TRUE(contains(n, boxes[order[k]]));
      }
    } else {
      const BvhNode& a = tree.nodes[it.node + 1];
      const BvhNode& b = tree.nodes[n.index];
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE(n.min[k], std::min(a.min[k], b.min[k]));
        EXPECT_GE(n.max[k], std::max(a.max[k], b.max[k]));
      }
      EXPECT_GT(n.index, it.node + 1);
      stack.push_back({n.index, it.depth + 1});
      stack.push_back({it.node + 1, it.depth + 1});
    }
  }
  for (int s : seen) EXPECT_EQ(s, 1);
}

TEST(Bvh, BoxQueriesFindExactlyTheOverlappingItemsInAFixedOrder) {
  const auto boxes = random_boxes(3000, 1);
  std::vector<uint32_t> order;
  const Bvh tree = build_bvh(boxes, 4, order);
  check_tree(tree, boxes, order, 4);
  std::mt19937 rng(2);
  std::uniform_real_distribution<Real> pos(-55, 55), size(0.1f, 10);
  for (int q = 0; q < 200; ++q) {
    const Aabb query = random_box(rng, pos, size);
    const Vec3 &lo = query.min, &hi = query.max;
    std::set<uint32_t> expected;
    for (uint32_t k = 0; k < boxes.size(); ++k) {
      if (overlaps(boxes[k], lo, hi)) expected.insert(k);
    }
    const auto run = [&] {
      std::vector<uint32_t> found;
      bvh_query(tree, lo, hi, [&](uint32_t first, uint32_t count) {
        for (uint32_t k = first; k < first + count; ++k) {
          if (overlaps(boxes[order[k]], lo, hi)) found.push_back(order[k]);
        }
      });
      return found;
    };
    const std::vector<uint32_t> first = run();
    EXPECT_EQ(std::set<uint32_t>(first.begin(), first.end()), expected);
    EXPECT_EQ(first.size(), expected.size());  // no item twice
    EXPECT_EQ(run(), first);
  }
}

// A query reports exactly the leaves whose own box overlaps the query box, in the order they are
// stored (depth first, first child first): the order the mesh and compound walks, and so the
// contact candidates, depend on.
TEST(Bvh, BoxQueriesReportTheOverlappingLeavesInStoredOrder) {
  const auto boxes = random_boxes(3000, 4);
  std::vector<uint32_t> order;
  const Bvh tree = build_bvh(boxes, 4, order);
  std::mt19937 rng(5);
  std::uniform_real_distribution<Real> pos(-55, 55), size(0.1f, 20);
  int reported = 0;
  for (int q = 0; q < 300; ++q) {
    const Aabb query = random_box(rng, pos, size);
    const Vec3 &lo = query.min, &hi = query.max;
    std::vector<std::pair<uint32_t, uint32_t>> expected, found;
    for (const BvhNode& n : tree.nodes) {
      if (n.leaf() && node_overlaps(n, lo, hi)) expected.emplace_back(n.index, n.count);
    }
    bvh_query(tree, lo, hi,
              [&](uint32_t first, uint32_t count) { found.emplace_back(first, count); });
    EXPECT_EQ(found, expected);
    reported += int(found.size());
  }
  EXPECT_GT(reported, 1000);
}

TEST(Bvh, SameBoxesSameTree) {
  const auto boxes = random_boxes(2000, 3);
  std::vector<uint32_t> o1, o2;
  const Bvh a = build_bvh(boxes, 4, o1);
  const Bvh b = build_bvh(boxes, 4, o2);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  EXPECT_EQ(0, std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(BvhNode)));
  EXPECT_EQ(o1, o2);
}

TEST(Bvh, RayNearestHitEqualsBruteForce) {
  const auto boxes = random_boxes(3000, 4);
  std::vector<uint32_t> order;
  const Bvh tree = build_bvh(boxes, 4, order);
  std::mt19937 rng(5);
  std::uniform_real_distribution<Real> pos(-60, 60), unit(-1, 1);
  int hits = 0;
  for (int q = 0; q < 300; ++q) {
    const Vec3 o{pos(rng), pos(rng), pos(rng)};
    Vec3 d{unit(rng), unit(rng), unit(rng)};
    if (q % 10 == 0) d = Vec3(0, 0, q % 20 == 0 ? 1 : -1);  // axis-parallel rays too
    const Real max_t = 200;
    Real best = -1;
    for (const Aabb& b : boxes) {
      const Real t = ray_box(b, o, d, max_t);
      if (t >= 0 && (best < 0 || t < best)) best = t;
    }
    Real found = -1;
    bvh_ray(tree, o, d, max_t, [&](uint32_t first, uint32_t count, Real limit) {
      for (uint32_t k = first; k < first + count; ++k) {
        const Real t = ray_box(boxes[order[k]], o, d, limit);
        if (t >= 0 && (found < 0 || t < found)) found = t, limit = t;
      }
      return limit;
    });
    EXPECT_EQ(found, best) << "ray " << q;
    hits += best >= 0;
  }
  EXPECT_GT(hits, 30);  // the test sees hits, not only misses
}

TEST(Bvh, CoincidentItemsSplitByMedianAndTinyInputs) {
  // All centroids at one point: a median split in index order, down to the leaf size.
  std::vector<Aabb> same(100);
  for (std::size_t k = 0; k < same.size(); ++k) {
    same[k].min = Vec3::Constant(-1 - Real(k) * 0.01f);
    same[k].max = Vec3::Constant(1 + Real(k) * 0.01f);
  }
  std::vector<uint32_t> order;
  const Bvh tree = build_bvh(same, 4, order);
  check_tree(tree, same, order, 4);
  for (uint32_t k = 0; k < order.size(); ++k) EXPECT_EQ(order[k], k);

  std::vector<uint32_t> none_order;
  EXPECT_TRUE(build_bvh({}, 4, none_order).nodes.empty());
  const Bvh one = build_bvh(std::span<const Aabb>(same.data(), 1), 4, order);
  ASSERT_EQ(one.nodes.size(), 1u);
  EXPECT_EQ(one.nodes[0].count, 1u);
}

TEST(Bvh, NodeBoxesContainDoubleBoxesWhenRoundedToFloat) {
  std::vector<Aabb> boxes(2);
  boxes[0].min = Vec3(Real(0.1), Real(0.2), Real(0.3));
  boxes[0].max = Vec3(Real(1.1), Real(1.2), Real(1.3));
  boxes[1].min = Vec3(Real(5.1), Real(0.2), Real(0.3));
  boxes[1].max = Vec3(Real(6.1), Real(1.7), Real(1.3));
  std::vector<uint32_t> order;
  const Bvh tree = build_bvh(boxes, 1, order);
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(double(tree.nodes[0].min[a]), double(std::min(boxes[0].min[a], boxes[1].min[a])));
    EXPECT_GE(double(tree.nodes[0].max[a]), double(std::max(boxes[0].max[a], boxes[1].max[a])));
  }
}

}  // namespace bvh_test
}  // namespace elan::detail
