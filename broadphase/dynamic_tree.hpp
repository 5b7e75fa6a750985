// SPDX-License-Identifier: MIT
// A dynamic bounding-volume tree over items with fattened leaf boxes (Box2D's b2DynamicTree
// design): a leaf's box encloses its item's box grown by a margin, so an item that moves a
// little keeps its leaf, and one that leaves it is removed and inserted again. Inserts choose
// the sibling by the surface-area cost of Goldsmith and Salmon (1987); every ancestor of a
// changed leaf is refitted and balanced by one AVL-style rotation (which, as Box2D's, bounds the
// skew of a node's children without making the tree strictly AVL).
//
// Items are dense indices (the world's body indices): leaf_of(item) is its node or kNull.
// Queries are const and may run from any number of threads at once; updates are serial.
// determinism: the tree's shape depends only on the sequence of inserts and removals, which
// callers make in index order, never on a thread count.
#pragma once

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "elan/math.hpp"

namespace elan::detail {

struct TreeBox {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
  bool contains(const TreeBox& b) const {
    return (lo.array() <= b.lo.array()).all() && (b.hi.array() <= hi.array()).all();
  }
  bool overlaps(const TreeBox& b) const {
    return (lo.array() <= b.hi.array()).all() && (b.lo.array() <= hi.array()).all();
  }
};

class DynamicTree {
 public:
  static constexpr uint32_t kNull = UINT32_MAX;
  // Stack depth of a traversal (at most the height plus one). The rotations keep the height near
  // log2(leaves): about 25 for a million; valid() checks it stays under half of this.
  static constexpr int kMaxStack = 256;

  struct Node {
    TreeBox box;
    uint32_t parent = kNull;  // the next free node when on the free list
    uint32_t child1 = kNull;  // kNull: a leaf
    uint32_t child2 = kNull;  // a leaf's item
    int32_t height = 0;       // leaf 0; -1 free
    bool leaf() const { return child1 == kNull; }
  };

  void clear();
  // Grows or shrinks the item range to [0, count); items past it must have been removed.
  void resize_items(std::size_t count);
  std::size_t item_count() const { return leaf_of_.size(); }
  bool contains(uint32_t item) const { return leaf_of_[item] != kNull; }
  const TreeBox& fat_box(uint32_t item) const { return nodes_[leaf_of_[item]].box; }
  // Inserts `item` (not in the tree) with the leaf box `fat`.
  void insert(uint32_t item, const TreeBox& fat);
  // Removes `item` if it is in the tree.
  void remove(uint32_t item);
  // Item `from`'s leaf becomes item `to`'s (the world's swap-remove: `to` must not be in the
  // tree).
  void rename(uint32_t from, uint32_t to);
  // Ensures item's leaf contains `box`; otherwise re-inserts it with `box` grown by `margin`.
  // Returns true when the leaf changed.
  bool update(uint32_t item, const TreeBox& box, Real margin);
  // As update(), for an item that moves by about `displacement` a step (Box2D's predicted fat
  // box): a new leaf is also stretched by kPredictSteps times the displacement along the motion,
  // so a body falling or sliding steadily is re-inserted every few steps rather than every step.
  // A leaf that still contains `box` but reaches more than kShrinkMargins margins and the stretch
  // past the leaf it would now get (a body that moved fast and has stopped) is re-inserted tight.
  bool update_moving(uint32_t item, const TreeBox& box, Real margin, const Vec3& displacement);
  static constexpr Real kPredictSteps = 4;
  static constexpr Real kShrinkMargins = 4;

  uint32_t root() const { return root_; }
  const Node& node(uint32_t n) const { return nodes_[n]; }
  int height() const { return root_ == kNull ? 0 : nodes_[root_].height; }
  std::size_t heap_bytes() const {
    return nodes_.capacity() * sizeof(Node) + leaf_of_.capacity() * sizeof(uint32_t);
  }

  // Calls f(item) for every leaf whose box overlaps `box`, depth first, child1 first; f returns
  // false to stop.
  template <class F>
  void query(const TreeBox& box, F&& f) const {
    if (root_ == kNull) return;
    uint32_t stack[kMaxStack];
    int top = 0;
    stack[top++] = root_;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (!n.box.overlaps(box)) continue;
      if (n.leaf()) {
        if (!f(n.child2)) return;
      } else {
        stack[top++] = n.child1;
        stack[top++] = n.child2;
      }
    }
  }

  // Ray o + t d, t in [0, max_t]: calls f(item, max_t) for every leaf whose box the ray enters
  // before the current max_t, nearer child first; f returns the new max_t (< 0 stops).
  template <class F>
  void ray(const Vec3& o, const Vec3& d, Real max_t, F&& f) const {
    if (root_ == kNull) return;
    const Vec3 inv = d.cwiseInverse();
    struct Entry {
      uint32_t node;
      Real t;
    };
    Entry stack[kMaxStack];
    int top = 0;
    Real t_root;
    if (!enters(nodes_[root_].box, o, inv, max_t, t_root)) return;
    stack[top++] = {root_, t_root};
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.t > max_t) continue;
      const Node& n = nodes_[e.node];
      if (n.leaf()) {
        max_t = f(n.child2, max_t);
        if (max_t < 0) return;
        continue;
      }
      Real t1, t2;
      const bool h1 = enters(nodes_[n.child1].box, o, inv, max_t, t1);
      const bool h2 = enters(nodes_[n.child2].box, o, inv, max_t, t2);
      // The nearer child is pushed last, so it is visited first.
      if (h1 && h2) {
        if (t1 <= t2) {
          stack[top++] = {n.child2, t2};
          stack[top++] = {n.child1, t1};
        } else {
          stack[top++] = {n.child1, t1};
          stack[top++] = {n.child2, t2};
        }
      } else if (h1) {
        stack[top++] = {n.child1, t1};
      } else if (h2) {
        stack[top++] = {n.child2, t2};
      }
    }
  }

  // Slab test: whether the ray enters `b` at some t in [0, max_t], and where (t_enter). An axis
  // the ray runs parallel to gives +-inf slabs, and 0 * inf = NaN fails the comparisons only when
  // the origin lies exactly on a slab face; the box is closed, so that case counts as inside.
  static bool enters(const TreeBox& b, const Vec3& o, const Vec3& inv, Real max_t, Real& t_enter) {
    Real t0 = 0, t1 = max_t;
    for (int a = 0; a < 3; ++a) {
      Real s0 = (b.lo[a] - o[a]) * inv[a], s1 = (b.hi[a] - o[a]) * inv[a];
      if (s0 != s0) s0 = -std::numeric_limits<Real>::infinity();
      if (s1 != s1) s1 = std::numeric_limits<Real>::infinity();
      if (s0 > s1) std::swap(s0, s1);
      t0 = s0 > t0 ? s0 : t0;
      t1 = s1 < t1 ? s1 : t1;
    }
    t_enter = t0;
    return t0 <= t1;
  }

  // Checks the parent links, heights, the boxes' nesting and leaf_of: the tests' oracle.
  bool valid() const;

 private:
  uint32_t allocate();
  void free_node(uint32_t n);
  void insert_leaf(uint32_t leaf);
  void remove_leaf(uint32_t leaf);
  uint32_t balance(uint32_t a);
  void refit_up(uint32_t n);

  std::vector<Node> nodes_;
  std::vector<uint32_t> leaf_of_;
  uint32_t root_ = kNull;
  uint32_t free_ = kNull;
};

}  // namespace elan::detail
