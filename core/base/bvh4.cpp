// SPDX-License-Identifier: MIT
// The binary tree's collapse into a 4-wide one, and the ray's slab test against one child (see
// bvh4.hpp).
#include "core/base/bvh4.hpp"

#include <limits>

namespace elan::detail {
namespace {

double half_area(const BvhNode& n) {
  const double x = double(n.max[0]) - n.min[0], y = double(n.max[1]) - n.min[1],
               z = double(n.max[2]) - n.min[2];
  return x * y + y * z + z * x;
}

struct Collapser {
  const std::vector<BvhNode>& in;
  std::vector<Bvh4Node>& out;

  // The 4-wide node of binary node b (inner, or a lone leaf at the root), its subtree after it.
  uint32_t make(uint32_t b) {
    const uint32_t self = uint32_t(out.size());
    out.emplace_back();
    uint32_t slot[4];
    int m = 0;
    if (in[b].leaf()) {
      slot[m++] = b;
    } else {
      slot[m++] = b + 1;
      slot[m++] = in[b].index;
      while (m < 4) {
        // determinism: the inner child of largest area, the first on a tie.
        int widest = -1;
        double widest_area = -1;
        for (int k = 0; k < m; ++k) {
          if (in[slot[k]].leaf()) continue;
          const double a = half_area(in[slot[k]]);
          if (a > widest_area) widest_area = a, widest = k;
        }
        if (widest < 0) break;
        // Its two children take its place, in order: the leaves keep the binary tree's order.
        const uint32_t c = slot[widest];
        for (int k = m; k > widest + 1; --k) slot[k] = slot[k - 1];
        slot[widest] = c + 1;
        slot[widest + 1] = in[c].index;
        ++m;
      }
    }
    Bvh4Node node;
    for (int k = 0; k < 4; ++k) {
      for (int a = 0; a < 3; ++a) {
        node.min[a][k] = std::numeric_limits<float>::infinity();
        node.max[a][k] = -std::numeric_limits<float>::infinity();
      }
      node.index[k] = 0;
      node.count[k] = kBvh4Empty;
    }
    for (int k = 0; k < m; ++k) {
      const BvhNode& c = in[slot[k]];
      for (int a = 0; a < 3; ++a) node.min[a][k] = c.min[a], node.max[a][k] = c.max[a];
      if (c.leaf()) {
        node.index[k] = c.index;
        node.count[k] = c.count;
      } else {
        node.index[k] = make(slot[k]);  // depth first, in order
        node.count[k] = 0;
      }
    }
    out[self] = node;
    return self;
  }
};

}  // namespace

Bvh4 collapse_to_bvh4(const Bvh& binary) {
  Bvh4 tree;
  if (binary.nodes.empty()) return tree;
  // perf: about a quarter of the binary tree's nodes (fewer than four children where only
  // leaves are left to take).
  tree.nodes.reserve(binary.nodes.size() / 3 + 1);
  Collapser{binary.nodes, tree.nodes}.make(0);
  tree.nodes.shrink_to_fit();
  return tree;
}

Real ray_enters_child(const Bvh4Node& n, int k, const Vec3& origin, const Vec3& inv_dir,
                      Real max_t) {
  BvhNode box;
  for (int a = 0; a < 3; ++a) box.min[a] = n.min[a][k], box.max[a] = n.max[a][k];
  box.index = 0;
  box.count = 1;
  return ray_enters_node(box, origin, inv_dir, max_t);
}

}  // namespace elan::detail
