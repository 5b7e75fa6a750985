// SPDX-License-Identifier: MIT
// The dynamic tree: through random inserts, moves, removals and renames it stays a valid,
// balanced tree, and its box and ray queries find exactly what testing every item finds.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "broadphase/dynamic_tree.hpp"

namespace elan::detail {
namespace broadphase_dynamic_tree_test {

Real uniform(std::mt19937& rng, Real lo, Real hi) {
  return std::uniform_real_distribution<Real>(lo, hi)(rng);
}

TreeBox random_box(std::mt19937& rng) {
  const Vec3 c{uniform(rng, -20, 20), uniform(rng, -20, 20), uniform(rng, -20, 20)};
  const Vec3 h{uniform(rng, 0.1f, 1.5f), uniform(rng, 0.1f, 1.5f), uniform(rng, 0.1f, 1.5f)};
  return {c - h, c + h};
}

TEST(DynamicTree, StaysValidAndQueriesMatchTestingEveryItem) {
  std::mt19937 rng(11);
  DynamicTree tree;
  const uint32_t n = 2000;
  tree.resize_items(n);
  std::vector<TreeBox> boxes(n);
  std::vector<bool> in(n, false);
  for (uint32_t i = 0; i < n; ++i) {
    boxes[i] = random_box(rng);
    tree.update(i, boxes[i], Real(0.1));
    in[i] = true;
  }
  ASSERT_TRUE(tree.valid());
  // The rotations keep the tree near balanced: within twice the height of a perfect tree.
  EXPECT_LE(tree.height(), 2 * int(std::ceil(std::log2(double(n)))));
  for (int round = 0; round < 20; ++round) {
    for (int k = 0; k < 300; ++k) {
      const uint32_t i = rng() % n;
      const int op = int(rng() % 4);
      if (op == 0) {
        tree.remove(i);
        in[i] = false;
      } else if (op == 1) {
        boxes[i].lo += Vec3::Constant(uniform(rng, -0.2f, 0.2f));
        boxes[i].hi = boxes[i].lo + Vec3::Constant(1);
        tree.update(i, boxes[i], Real(0.1));
        in[i] = true;
      } else {
        boxes[i] = random_box(rng);
        tree.update(i, boxes[i], Real(0.1));
        in[i] = true;
      }
    }
    if (round % 4 == 3) {
      // Compaction renumbers the nodes only: the walk meets the leaves in the same order.
      const auto order = [&] {
        std::vector<uint32_t> seen;
        for (int k = 0; k < 8; ++k) {
          const Vec3 o(-30, Real(k * 5 - 20), Real(k % 3 * 6 - 6));
          const Vec3 d = Vec3(1, Real(0.1 * (k % 2)), Real(-0.05 * k)).normalized();
          tree.ray(o, d, 80, [&](uint32_t i, Real l) {
            seen.push_back(i);
            return l;
          });
        }
        return seen;
      };
      const std::vector<uint32_t> before = order();
      tree.compact();
      EXPECT_EQ(tree.inserts_since_compact(), 0u);
      ASSERT_EQ(order(), before) << "round " << round;
      ASSERT_GT(before.size(), 10u);
    }
    ASSERT_TRUE(tree.valid()) << "round " << round;
    for (uint32_t i = 0; i < n; ++i) {
      ASSERT_EQ(tree.contains(i), bool(in[i]));
      if (in[i]) {
        ASSERT_TRUE(tree.fat_box(i).contains(boxes[i]));
      }
    }
    // Box queries: every item whose fat leaf overlaps, and at least every item whose own box does.
    for (int q = 0; q < 20; ++q) {
      const TreeBox probe = random_box(rng);
      std::vector<uint32_t> got, want;
      tree.query(probe, [&](uint32_t i) {
        got.push_back(i);
        return true;
      });
      for (uint32_t i = 0; i < n; ++i) {
        if (in[i] && tree.fat_box(i).overlaps(probe)) want.push_back(i);
      }
      std::sort(got.begin(), got.end());
      ASSERT_EQ(got, want);
    }
    // Rays: the leaves entered within the limit, each found once.
    for (int q = 0; q < 20; ++q) {
      const Vec3 o{uniform(rng, -25, 25), uniform(rng, -25, 25), uniform(rng, -25, 25)};
      Vec3 d{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
      if (q % 5 == 0) d.y() = 0;  // parallel to a slab
      d.normalize();
      std::vector<uint32_t> got, want;
      tree.ray(o, d, 30, [&](uint32_t i, Real limit) {
        got.push_back(i);
        return limit;
      });
      for (uint32_t i = 0; i < n; ++i) {
        Real t;
        if (in[i] && DynamicTree::enters(tree.fat_box(i), o, d.cwiseInverse(), 30, t)) {
          want.push_back(i);
        }
      }
      std::sort(got.begin(), got.end());
      ASSERT_EQ(got, want);
    }
    // Sweeps of a box: every leaf met by the moving box (the leaf grown by its half extents,
    // entered by its centre's ray), each once; rounding may differ from growing the leaf first
    // by an ulp of the coordinates, so the reference grows by 1e-4 less (must be found) and
    // 1e-4 more (may be found).
    for (int q = 0; q < 20; ++q) {
      const Vec3 o{uniform(rng, -25, 25), uniform(rng, -25, 25), uniform(rng, -25, 25)};
      Vec3 d{uniform(rng, -10, 10), uniform(rng, -10, 10), uniform(rng, -10, 10)};
      if (q % 5 == 0) d.x() = 0;
      const Vec3 g{uniform(rng, 0.1f, 2), uniform(rng, 0.1f, 2), uniform(rng, 0.1f, 2)};
      std::vector<uint32_t> got;
      tree.sweep(o, d, g, 1, [&](uint32_t i, Real limit) {
        got.push_back(i);
        return limit;
      });
      std::sort(got.begin(), got.end());
      ASSERT_TRUE(std::adjacent_find(got.begin(), got.end()) == got.end());
      const Vec3 e = Vec3::Constant(1e-4f);
      for (uint32_t i = 0; i < n; ++i) {
        if (!in[i]) continue;
        const TreeBox& f = tree.fat_box(i);
        Real t;
        const bool must =
            DynamicTree::enters({f.lo - g + e, f.hi + g - e}, o, d.cwiseInverse(), 1, t);
        const bool may =
            DynamicTree::enters({f.lo - g - e, f.hi + g + e}, o, d.cwiseInverse(), 1, t);
        const bool found = std::binary_search(got.begin(), got.end(), i);
        ASSERT_TRUE(found || !must) << "item " << i;
        ASSERT_TRUE(may || !found) << "item " << i;
      }
    }
    // Pruning: a walk that lowers its limit to each leaf's entry sees, first, the least entry.
    for (int q = 0; q < 20; ++q) {
      const Vec3 o{uniform(rng, -25, 25), uniform(rng, -25, 25), uniform(rng, -25, 25)};
      const Vec3 d =
          Vec3{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)}.normalized();
      const Vec3 inv = d.cwiseInverse();
      Real best = 60, want = 60;
      tree.ray(o, d, 60, [&](uint32_t i, Real limit) {
        Real t;
        EXPECT_TRUE(DynamicTree::enters(tree.fat_box(i), o, inv, limit, t));
        best = std::min(best, t);
        return best;
      });
      for (uint32_t i = 0; i < n; ++i) {
        Real t;
        if (in[i] && DynamicTree::enters(tree.fat_box(i), o, inv, 60, t)) want = std::min(want, t);
      }
      ASSERT_EQ(best, want);
    }
  }
  // Rename: the world's swap-remove.
  tree.remove(5);
  tree.rename(n - 1, 5);
  tree.resize_items(n - 1);
  EXPECT_TRUE(tree.valid());
}

// A falling item's leaf is stretched 4 displacements down: the item falls 0.1 a step, so the
// leaf (margin 0.05) holds it for four steps and is re-inserted on the fifth (its top, left
// behind, is within the slack of four margins and the stretch); once the item has stopped, the
// stretched leaf reaches 0.4 below it, past the tight leaf plus four margins, and is re-inserted
// tight on the next update.
TEST(DynamicTree, MovingLeafIsStretchedAlongTheMotionAndShrunkWhenItStops) {
  DynamicTree tree;
  tree.resize_items(2);
  tree.update(1, {Vec3(5, 0, 0), Vec3(6, 1, 1)}, Real(0.05));
  const Real margin = Real(0.05), step = Real(0.1);
  const Vec3 fall(0, -step, 0);
  TreeBox box{Vec3(0, 10, 0), Vec3(1, 11, 1)};
  ASSERT_TRUE(tree.update_moving(0, box, margin, fall));
  EXPECT_FLOAT_EQ(tree.fat_box(0).lo.y(), 10 - margin - 4 * step);
  EXPECT_FLOAT_EQ(tree.fat_box(0).hi.y(), 11 + margin);
  EXPECT_FLOAT_EQ(tree.fat_box(0).lo.x(), -margin);
  int reinserted = 0;
  for (int k = 1; k <= 5; ++k) {
    box.lo.y() -= step;
    box.hi.y() -= step;
    if (tree.update_moving(0, box, margin, fall)) {
      ++reinserted;
      EXPECT_EQ(k, 5);
    }
  }
  EXPECT_EQ(reinserted, 1);
  // Stopped: the leaf reaches 0.4 below the box, more than 0.05 + 4 * 0.05 = 0.25.
  EXPECT_TRUE(tree.update_moving(0, box, margin, Vec3::Zero()));
  EXPECT_FLOAT_EQ(tree.fat_box(0).lo.y(), box.lo.y() - margin);
  EXPECT_FALSE(tree.update_moving(0, box, margin, Vec3::Zero()));
  EXPECT_TRUE(tree.valid());
}

}  // namespace broadphase_dynamic_tree_test
}  // namespace elan::detail
