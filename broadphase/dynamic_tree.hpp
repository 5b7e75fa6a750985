// SPDX-License-Identifier: MIT
// A dynamic bounding-volume tree over items with fattened leaf boxes (Box2D's b2DynamicTree
// design): a leaf's box encloses its item's box grown by a margin, so an item that moves a
// little keeps its leaf, and one that leaves it is removed and inserted again. Inserts choose
// the sibling by the surface-area cost of Goldsmith and Salmon (1987); every ancestor of a
// changed leaf is refitted and balanced by one AVL-style rotation (which, as Box2D's, bounds the
// skew of a node's children without making the tree strictly AVL).
//
// Items are dense indices below 2^31 (the world's body indices): leaf_of(item) is its node or
// kNull.
// Queries are const and may run from any number of threads at once; updates are serial.
// determinism: the tree's shape depends only on the sequence of inserts and removals, which
// callers make in index order, never on a thread count.
#pragma once

#include <cmath>
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

  // A child reference of a WideNode: an internal node's index, or a leaf's item with this bit.
  static constexpr uint32_t kLeafBit = 0x80000000u;
  // An internal node's children side by side for the ray walk: box[axis][0 lo, 1 hi][child].
  struct alignas(64) WideNode {
    Real box[3][2][2] = {};
    uint32_t child[2] = {kNull, kNull};
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
  // Renumbers the nodes in depth-first order (child1 first) and drops the free list: the tree's
  // shape, its child order and every query's order stay as they were; only where the nodes lie
  // in memory changes. perf: a walk then reads a subtree from neighbouring cache lines and pages
  // instead of from wherever its nodes were allocated. Allocates only when the tree has grown
  // past its largest compacted size.
  void compact();
  // Inserts and re-inserts since the last compact() (clear() resets it): the caller's measure of
  // how scattered the nodes have become.
  std::size_t inserts_since_compact() const { return inserts_since_compact_; }
  std::size_t node_count() const { return nodes_.size(); }
  // As update(), for an item that moves by about `displacement` a step (Box2D's predicted fat
  // box): a new leaf is also stretched by kPredictSteps times the displacement along the motion,
  // so a body falling or sliding steadily is re-inserted every few steps rather than every step.
  // A leaf that still contains `box` but reaches more than kShrinkMargins margins and the stretch
  // past the leaf it would now get (a body that moved fast and has stopped) is re-inserted tight.
  bool update_moving(uint32_t item, const TreeBox& box, Real margin, const Vec3& displacement);
  // Gives item the leaf box `fat` exactly: kept if its leaf has it, else re-inserted. A leaf so
  // set is a function of `fat` alone, not of the item's earlier boxes. Returns true when the leaf
  // changed.
  bool set_exact(uint32_t item, const TreeBox& fat);
  static constexpr Real kPredictSteps = 4;
  static constexpr Real kShrinkMargins = 4;

  uint32_t root() const { return root_; }
  const Node& node(uint32_t n) const { return nodes_[n]; }
  int height() const { return root_ == kNull ? 0 : nodes_[root_].height; }
  std::size_t heap_bytes() const {
    return (nodes_.capacity() + scratch_nodes_.capacity()) * sizeof(Node) +
           wide_.capacity() * sizeof(WideNode) +
           (leaf_of_.capacity() + scratch_index_.capacity()) * sizeof(uint32_t);
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
  // at some t <= the current max_t, nearer child first; f returns the new max_t (< 0 stops). A
  // leaf entered exactly at max_t is still visited (closest-hit ties are the caller's to break).
  template <class F>
  void ray(const Vec3& o, const Vec3& d, Real max_t, F&& f) const {
    sweep(o, d, Vec3::Zero(), max_t, std::forward<F>(f));
  }

  // The same for a box of half extents `grow` (>= 0) whose centre moves along o + t d: every
  // node's box is grown by `grow` (the Minkowski sum of the node's box and the moving box), so a
  // leaf is visited when the moving box meets it at some t <= the current max_t.
  //
  // perf: the walk reads one 64-byte WideNode per internal node (both children's boxes and
  // indices, a leaf's item inline), tests the two children in one 4-lane slab test, descends the
  // nearer child without a stack round trip and prunes every entry past the best so far.
  template <class F>
  void sweep(const Vec3& o, const Vec3& d, const Vec3& grow, Real max_t, F&& f) const {
    if (root_ == kNull) return;
    const SweepLanes lanes(o, d, grow);
    const Node& root = nodes_[root_];
    Real t_root;
    if (!enters_grown(root.box, lanes, max_t, t_root)) return;
    if (root.leaf()) {
      f(root.child2, max_t);
      return;
    }
    struct Entry {
      uint32_t child;
      Real t;
    };
    Entry stack[kMaxStack];
    int top = 0;
    uint32_t node = root_;
    for (;;) {
      Real t[2];
      const int hit = children_entered(wide_[node], lanes, max_t, t);
      uint32_t next = kNull;
      if (hit == 3) {
        const int nearer = t[1] < t[0] ? 1 : 0;
        stack[top++] = {wide_[node].child[1 - nearer], t[1 - nearer]};
        next = wide_[node].child[nearer];
      } else if (hit != 0) {
        next = wide_[node].child[hit - 1];
      }
      // Leaves are visited where they are met; the walk resumes from the stack, skipping what
      // lies past the (possibly shortened) max_t.
      for (;;) {
        if (next == kNull) {
          if (top == 0) return;
          const Entry e = stack[--top];
          if (e.t > max_t) continue;
          next = e.child;
        }
        if ((next & kLeafBit) == 0) break;
        max_t = f(next & ~kLeafBit, max_t);
        if (max_t < 0) return;
        next = kNull;
      }
      node = next;
    }
  }

  // Slab test: whether the ray o + t d (inv = 1 / d per axis, +-inf on an axis the ray runs
  // parallel to) enters the closed box `b` at some t in [0, max_t], and where (t_enter). The
  // near face of each axis is chosen by the sign of inv; 0 * inf = NaN (the origin on a face of
  // a slab the ray runs along) leaves that bound unconstrained: the box is closed, so the ray is
  // in the slab. The reference of the walk's 4-lane test (same operations, same bits).
  static bool enters(const TreeBox& b, const Vec3& o, const Vec3& inv, Real max_t, Real& t_enter) {
    Real t0 = 0, t1 = max_t;
    for (int a = 0; a < 3; ++a) {
      const bool neg = std::signbit(inv[a]);
      const Real s0 = ((neg ? b.hi[a] : b.lo[a]) - o[a]) * inv[a];
      const Real s1 = ((neg ? b.lo[a] : b.hi[a]) - o[a]) * inv[a];
      // A NaN compares false: the bound stays.
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
  void reinsert(uint32_t leaf, const TreeBox& fat);
  void insert_leaf(uint32_t leaf);
  void remove_leaf(uint32_t leaf);
  uint32_t balance(uint32_t a);
  void refit_up(uint32_t n);

  // Per-ray constants of the 4-lane slab test: for each axis, the origin of the near-face lanes
  // (o + s g, s the sign of d, g the growth) and of the far-face lanes (o - s g), 1 / d, and
  // which of lo / hi is the near face.
  struct SweepLanes {
    SweepLanes(const Vec3& o, const Vec3& d, const Vec3& grow) {
      for (int a = 0; a < 3; ++a) {
        inv[a] = Real(1) / d[a];
        near_hi[a] = std::signbit(inv[a]) ? 1 : 0;
        const Real sg = near_hi[a] ? -grow[a] : grow[a];
        o_near[a] = o[a] + sg;
        o_far[a] = o[a] - sg;
      }
    }
    Real o_near[3], o_far[3], inv[3];
    int near_hi[3];
  };

  // enters() for the box grown by the sweep's growth.
  static bool enters_grown(const TreeBox& b, const SweepLanes& r, Real max_t, Real& t_enter) {
    Real t0 = 0, t1 = max_t;
    for (int a = 0; a < 3; ++a) {
      const Real n = r.near_hi[a] ? b.hi[a] : b.lo[a], f = r.near_hi[a] ? b.lo[a] : b.hi[a];
      const Real s0 = (n - r.o_near[a]) * r.inv[a], s1 = (f - r.o_far[a]) * r.inv[a];
      t0 = s0 > t0 ? s0 : t0;
      t1 = s1 < t1 ? s1 : t1;
    }
    t_enter = t0;
    return t0 <= t1;
  }

  // Both children of an internal node against the sweep: bit k of the result is set when child
  // k is entered within [0, max_t], t[k] its entry.
  static int children_entered(const WideNode& w, const SweepLanes& r, Real max_t, Real t[2]);

  void sync(uint32_t n);

  std::vector<Node> nodes_;
  // wide_[n]: internal node n's children as the walk reads them (sync keeps it in step).
  std::vector<WideNode> wide_;
  std::vector<uint32_t> leaf_of_;
  // compact()'s buffers, kept so that a warm compaction does not allocate.
  std::vector<Node> scratch_nodes_;
  std::vector<uint32_t> scratch_index_;
  std::size_t inserts_since_compact_ = 0;
  uint32_t root_ = kNull;
  uint32_t free_ = kNull;
};

}  // namespace elan::detail
