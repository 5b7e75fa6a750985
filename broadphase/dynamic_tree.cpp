// SPDX-License-Identifier: MIT
// The dynamic tree's updates: node pool with a free list, insertion by the surface-area cost,
// removal, and the AVL-style rotation that keeps every node's children within one level.
#include "broadphase/dynamic_tree.hpp"

#include <algorithm>

#if defined(__SSE2__) && !defined(ELAN_DOUBLE)
#include <emmintrin.h>
#define ELAN_TREE_SSE2 1
#endif

namespace elan::detail {

namespace {

TreeBox merged(const TreeBox& a, const TreeBox& b) {
  return {a.lo.cwiseMin(b.lo), a.hi.cwiseMax(b.hi)};
}

// Half the surface area: the SAH's measure of how likely a random ray or box meets a node.
Real half_area(const TreeBox& b) {
  const Vec3 e = b.hi - b.lo;
  return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
}

}  // namespace

void DynamicTree::clear() {
  nodes_.clear();
  wide_.clear();
  std::fill(leaf_of_.begin(), leaf_of_.end(), kNull);
  root_ = kNull;
  free_ = kNull;
  inserts_since_compact_ = 0;
}

void DynamicTree::compact() {
  inserts_since_compact_ = 0;
  std::vector<uint32_t>& new_index = scratch_index_;
  new_index.assign(nodes_.size(), kNull);
  std::vector<Node>& out = scratch_nodes_;
  out.clear();
  if (root_ != kNull) {
    // Preorder, child1 first: a subtree's nodes are contiguous, each node before its children.
    uint32_t stack[kMaxStack];
    int top = 0;
    stack[top++] = root_;
    while (top > 0) {
      const uint32_t n = stack[--top];
      new_index[n] = uint32_t(out.size());
      out.push_back(nodes_[n]);
      if (!nodes_[n].leaf()) {
        stack[top++] = nodes_[n].child2;
        stack[top++] = nodes_[n].child1;
      }
    }
  }
  for (Node& n : out) {
    if (n.parent != kNull) n.parent = new_index[n.parent];
    if (!n.leaf()) {
      n.child1 = new_index[n.child1];
      n.child2 = new_index[n.child2];
    }
  }
  for (uint32_t& l : leaf_of_) {
    if (l != kNull) l = new_index[l];
  }
  root_ = out.empty() ? kNull : 0;
  free_ = kNull;
  nodes_.swap(out);
  wide_.resize(nodes_.size());
  for (uint32_t n = 0; n < nodes_.size(); ++n) {
    if (!nodes_[n].leaf()) sync(n);
  }
}

void DynamicTree::resize_items(std::size_t count) {
  leaf_of_.resize(count, kNull);
}

uint32_t DynamicTree::allocate() {
  if (free_ == kNull) {
    // perf: the pool only grows; a freed node is reused before the vector grows again.
    nodes_.emplace_back();
    wide_.emplace_back();
    return uint32_t(nodes_.size() - 1);
  }
  const uint32_t n = free_;
  free_ = nodes_[n].parent;
  nodes_[n] = Node{};
  return n;
}

void DynamicTree::free_node(uint32_t n) {
  nodes_[n].parent = free_;
  nodes_[n].height = -1;
  free_ = n;
}

void DynamicTree::insert(uint32_t item, const TreeBox& fat) {
  ++inserts_since_compact_;
  const uint32_t leaf = allocate();
  nodes_[leaf].box = fat;
  nodes_[leaf].child2 = item;
  nodes_[leaf].height = 0;
  leaf_of_[item] = leaf;
  insert_leaf(leaf);
}

void DynamicTree::remove(uint32_t item) {
  const uint32_t leaf = leaf_of_[item];
  if (leaf == kNull) return;
  remove_leaf(leaf);
  free_node(leaf);
  leaf_of_[item] = kNull;
}

void DynamicTree::rename(uint32_t from, uint32_t to) {
  const uint32_t leaf = leaf_of_[from];
  leaf_of_[to] = leaf;
  leaf_of_[from] = kNull;
  if (leaf == kNull) return;
  nodes_[leaf].child2 = to;
  if (nodes_[leaf].parent != kNull) sync(nodes_[leaf].parent);
}

bool DynamicTree::update(uint32_t item, const TreeBox& box, Real margin) {
  const uint32_t leaf = leaf_of_[item];
  if (leaf != kNull && nodes_[leaf].box.contains(box)) return false;
  const Vec3 m = Vec3::Constant(margin);
  const TreeBox fat{box.lo - m, box.hi + m};
  if (leaf == kNull) {
    insert(item, fat);
    return true;
  }
  reinsert(leaf, fat);
  return true;
}

bool DynamicTree::set_exact(uint32_t item, const TreeBox& fat) {
  const uint32_t leaf = leaf_of_[item];
  if (leaf == kNull) {
    insert(item, fat);
    return true;
  }
  const TreeBox& now = nodes_[leaf].box;
  if (now.lo == fat.lo && now.hi == fat.hi) return false;
  reinsert(leaf, fat);
  return true;
}

// Keeps the node and moves it: removed from its place, re-inserted with the new box.
void DynamicTree::reinsert(uint32_t leaf, const TreeBox& fat) {
  ++inserts_since_compact_;
  remove_leaf(leaf);
  nodes_[leaf].box = fat;
  nodes_[leaf].parent = kNull;
  insert_leaf(leaf);
}

bool DynamicTree::update_moving(uint32_t item, const TreeBox& box, Real margin,
                                const Vec3& displacement) {
  const Vec3 stretch =
      displacement.allFinite() ? Vec3(kPredictSteps * displacement) : Vec3(Vec3::Zero());
  const Vec3 m = Vec3::Constant(margin);
  const TreeBox fat{box.lo - m + stretch.cwiseMin(Vec3::Zero()),
                    box.hi + m + stretch.cwiseMax(Vec3::Zero())};
  const uint32_t leaf = leaf_of_[item];
  if (leaf != kNull && nodes_[leaf].box.contains(box)) {
    // The stretch counts on both sides: the trailing side of a steadily moving leaf falls behind
    // by a displacement a step, and that leaf is not to be re-inserted for it.
    const Vec3 slack = Vec3::Constant(kShrinkMargins * margin) + stretch.cwiseAbs();
    if (TreeBox{fat.lo - slack, fat.hi + slack}.contains(nodes_[leaf].box)) return false;
  }
  if (leaf == kNull) {
    insert(item, fat);
    return true;
  }
  reinsert(leaf, fat);
  return true;
}

// Descends from the root towards the sibling whose merge costs least: at each node, the cost of
// pairing the leaf with the node itself (a new parent of both: 2 * area(node + leaf)) against the
// cheapest cost down either child (the area every ancestor grows by, plus the child's own).
void DynamicTree::insert_leaf(uint32_t leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    nodes_[leaf].parent = kNull;
    return;
  }
  const TreeBox box = nodes_[leaf].box;
  uint32_t index = root_;
  while (!nodes_[index].leaf()) {
    const Node& n = nodes_[index];
    const Real area = half_area(n.box);
    const Real combined = half_area(merged(n.box, box));
    const Real here = 2 * combined;
    const Real inherited = 2 * (combined - area);
    const auto down = [&](uint32_t c) {
      const TreeBox m = merged(box, nodes_[c].box);
      if (nodes_[c].leaf()) return half_area(m) + inherited;
      return half_area(m) - half_area(nodes_[c].box) + inherited;
    };
    const Real c1 = down(n.child1), c2 = down(n.child2);
    if (here < c1 && here < c2) break;
    index = c1 <= c2 ? n.child1 : n.child2;
  }
  const uint32_t sibling = index;
  const uint32_t old_parent = nodes_[sibling].parent;
  const uint32_t parent = allocate();
  nodes_[parent].parent = old_parent;
  nodes_[parent].box = merged(box, nodes_[sibling].box);
  nodes_[parent].height = nodes_[sibling].height + 1;
  nodes_[parent].child1 = sibling;
  nodes_[parent].child2 = leaf;
  nodes_[sibling].parent = parent;
  nodes_[leaf].parent = parent;
  if (old_parent == kNull) {
    root_ = parent;
  } else if (nodes_[old_parent].child1 == sibling) {
    nodes_[old_parent].child1 = parent;
  } else {
    nodes_[old_parent].child2 = parent;
  }
  refit_up(nodes_[leaf].parent);
}

void DynamicTree::remove_leaf(uint32_t leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  const uint32_t parent = nodes_[leaf].parent;
  const uint32_t grand = nodes_[parent].parent;
  const uint32_t sibling =
      nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
  if (grand == kNull) {
    root_ = sibling;
    nodes_[sibling].parent = kNull;
    free_node(parent);
    return;
  }
  if (nodes_[grand].child1 == parent) {
    nodes_[grand].child1 = sibling;
  } else {
    nodes_[grand].child2 = sibling;
  }
  nodes_[sibling].parent = grand;
  free_node(parent);
  refit_up(grand);
}

// Walks to the root: balance each node, then recompute its height and box from its children.
void DynamicTree::refit_up(uint32_t n) {
  while (n != kNull) {
    n = balance(n);
    Node& node = nodes_[n];
    const Node& c1 = nodes_[node.child1];
    const Node& c2 = nodes_[node.child2];
    node.height = 1 + std::max(c1.height, c2.height);
    node.box = merged(c1.box, c2.box);
    sync(n);
    n = node.parent;
  }
}

// If one child of `a` is two levels taller than the other, lifts the taller child's taller
// child into `a`'s place (a single rotation of an AVL tree). Returns the node now where `a` was.
uint32_t DynamicTree::balance(uint32_t ia) {
  Node& a = nodes_[ia];
  if (a.leaf() || a.height < 2) return ia;
  const uint32_t ib = a.child1, ic = a.child2;
  const int32_t skew = nodes_[ic].height - nodes_[ib].height;
  if (skew >= -1 && skew <= 1) return ia;
  // The taller child `up` rises; `a` takes its shorter grandchild in its place.
  const bool right = skew > 1;
  const uint32_t iup = right ? ic : ib;
  const uint32_t iother = right ? ib : ic;
  Node& up = nodes_[iup];
  const uint32_t f = up.child1, g = up.child2;
  up.child1 = ia;
  up.parent = a.parent;
  a.parent = iup;
  if (up.parent == kNull) {
    root_ = iup;
  } else if (nodes_[up.parent].child1 == ia) {
    nodes_[up.parent].child1 = iup;
  } else {
    nodes_[up.parent].child2 = iup;
  }
  // Of up's children, the taller stays with up; the shorter goes down to `a`.
  const bool keep_f = nodes_[f].height > nodes_[g].height;
  const uint32_t stay = keep_f ? f : g, go = keep_f ? g : f;
  up.child2 = stay;
  if (right) {
    a.child2 = go;
  } else {
    a.child1 = go;
  }
  nodes_[go].parent = ia;
  (void)iother;
  a.box = merged(nodes_[a.child1].box, nodes_[a.child2].box);
  a.height = 1 + std::max(nodes_[a.child1].height, nodes_[a.child2].height);
  sync(ia);  // `up` is synced by refit_up, which carries on from it
  up.box = merged(a.box, nodes_[stay].box);
  up.height = 1 + std::max(a.height, nodes_[stay].height);
  return iup;
}

void DynamicTree::sync(uint32_t n) {
  const Node& node = nodes_[n];
  WideNode& w = wide_[n];
  const uint32_t c[2] = {node.child1, node.child2};
  for (int k = 0; k < 2; ++k) {
    const Node& child = nodes_[c[k]];
    for (int a = 0; a < 3; ++a) {
      w.box[a][0][k] = child.box.lo[a];
      w.box[a][1][k] = child.box.hi[a];
    }
    w.child[k] = child.leaf() ? (child.child2 | kLeafBit) : c[k];
  }
}

// The two children's slab tests of enters_grown at once. Lanes 0, 1: the near faces of child 1
// and 2, entry t = (near - o_near) * inv; lanes 2, 3: the far faces, with inv negated, so that
// one running max gives the latest entry in lanes 0, 1 and minus the earliest exit in lanes 2, 3.
// maxps returns its second operand when either is NaN, so a NaN slab leaves the bound as it was,
// as the scalar test does.
int DynamicTree::children_entered(const WideNode& w, const SweepLanes& r, Real max_t, Real t[2]) {
#if defined(ELAN_TREE_SSE2)
  __m128 acc = _mm_setr_ps(0, 0, -max_t, -max_t);
  for (int a = 0; a < 3; ++a) {
    const int n = r.near_hi[a];
    __m128 v = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(w.box[a][n])));
    v = _mm_loadh_pi(v, reinterpret_cast<const __m64*>(w.box[a][1 - n]));
    const __m128 o = _mm_setr_ps(r.o_near[a], r.o_near[a], r.o_far[a], r.o_far[a]);
    const __m128 inv = _mm_setr_ps(r.inv[a], r.inv[a], -r.inv[a], -r.inv[a]);
    acc = _mm_max_ps(_mm_mul_ps(_mm_sub_ps(v, o), inv), acc);
  }
  const __m128 exit = _mm_xor_ps(_mm_movehl_ps(acc, acc), _mm_set1_ps(-0.0f));
  _mm_storel_pi(reinterpret_cast<__m64*>(t), acc);
  return _mm_movemask_ps(_mm_cmple_ps(acc, exit)) & 3;
#else
  int hit = 0;
  for (int k = 0; k < 2; ++k) {
    Real t0 = 0, t1 = max_t;
    for (int a = 0; a < 3; ++a) {
      const int n = r.near_hi[a];
      const Real s0 = (w.box[a][n][k] - r.o_near[a]) * r.inv[a];
      const Real s1 = (w.box[a][1 - n][k] - r.o_far[a]) * r.inv[a];
      t0 = s0 > t0 ? s0 : t0;
      t1 = s1 < t1 ? s1 : t1;
    }
    t[k] = t0;
    if (t0 <= t1) hit |= 1 << k;
  }
  return hit;
#endif
}

bool DynamicTree::valid() const {
  std::size_t leaves = 0;
  if (root_ != kNull) {
    if (nodes_[root_].parent != kNull) return false;
    uint32_t stack[kMaxStack];
    int top = 0;
    stack[top++] = root_;
    while (top > 0) {
      const uint32_t i = stack[--top];
      const Node& n = nodes_[i];
      if (n.leaf()) {
        if (n.height != 0 || n.child2 >= leaf_of_.size() || leaf_of_[n.child2] != i) return false;
        ++leaves;
        continue;
      }
      const Node &c1 = nodes_[n.child1], &c2 = nodes_[n.child2];
      if (c1.parent != i || c2.parent != i) return false;
      if (n.height != 1 + std::max(c1.height, c2.height)) return false;
      if (!n.box.contains(c1.box) || !n.box.contains(c2.box)) return false;
      // The walk's copy of the children.
      const WideNode& w = wide_[i];
      const uint32_t c[2] = {n.child1, n.child2};
      for (int k = 0; k < 2; ++k) {
        const Node& ck = nodes_[c[k]];
        if (w.child[k] != (ck.leaf() ? (ck.child2 | kLeafBit) : c[k])) return false;
        for (int a = 0; a < 3; ++a) {
          if (w.box[a][0][k] != ck.box.lo[a] || w.box[a][1][k] != ck.box.hi[a]) return false;
        }
      }
      if (top + 2 > kMaxStack) return false;
      stack[top++] = n.child1;
      stack[top++] = n.child2;
    }
  }
  if (height() > kMaxStack / 2) return false;
  std::size_t mapped = 0;
  for (const uint32_t l : leaf_of_) mapped += l != kNull;
  return mapped == leaves;
}

}  // namespace elan::detail
