// SPDX-License-Identifier: MIT
// The bounding-volume hierarchy's builder (binned SAH, Wald 2007, "On fast construction of
// SAH-based bounding volume hierarchies") and the ray's slab test against one node.
#include "core/base/bvh.hpp"

#include <algorithm>
#include <cmath>

namespace elan::detail {
namespace {

constexpr int kBins = 16;

// The surface-area heuristic's cost of walking into a node, in units of one item's test: a
// split is taken only if kTraversal * area(node) + sum(area(child) * count(child)) is below
// area(node) * count, so items whose boxes all coincide stay one leaf.
constexpr double kTraversal = 1;

// A float at or below (above) x: float boxes rounded outward contain the Real boxes.
float float_down(Real x) {
  float f = float(x);
  if (double(f) > double(x)) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
float float_up(Real x) {
  float f = float(x);
  if (double(f) < double(x)) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// Half the surface area of a box, the SAH's measure of how likely a random ray or box hits it.
double half_area(const Aabb& b) {
  const Vec3 e = b.max - b.min;
  return double(e.x()) * e.y() + double(e.y()) * e.z() + double(e.z()) * e.x();
}

Aabb empty_box() {
  Aabb b;
  b.min = Vec3::Constant(std::numeric_limits<Real>::max());
  b.max = Vec3::Constant(-std::numeric_limits<Real>::max());
  return b;
}

void grow(Aabb& b, const Aabb& o) {
  b.min = b.min.cwiseMin(o.min);
  b.max = b.max.cwiseMax(o.max);
}

void grow(Aabb& b, const Vec3& p) {
  b.min = b.min.cwiseMin(p);
  b.max = b.max.cwiseMax(p);
}

struct Bin {
  Aabb box = empty_box();        // of the items
  Aabb centroids = empty_box();  // of the items' centroids
  uint32_t count = 0;
};

// perf: the recursion carries each node's box and centroid box down from the parent's bins, so
// a node costs one binning pass and one partition over its items and allocates nothing.
struct Builder {
  std::span<const Aabb> boxes;
  std::vector<Vec3> centroids;
  uint32_t* order = nullptr;
  std::vector<BvhNode>* nodes = nullptr;
  uint32_t leaf_size = 1;

  void scan(uint32_t first, uint32_t count, Aabb& box, Aabb& cbox) const {
    box = empty_box();
    cbox = empty_box();
    for (uint32_t k = first; k < first + count; ++k) {
      grow(box, boxes[order[k]]);
      grow(cbox, centroids[order[k]]);
    }
  }

  void build(uint32_t first, uint32_t count, const Aabb& box, const Aabb& cbox, int depth) {
    const std::size_t self = nodes->size();
    BvhNode node;
    for (int a = 0; a < 3; ++a) {
      node.min[a] = float_down(box.min[a]);
      node.max[a] = float_up(box.max[a]);
    }
    node.index = first;
    node.count = count;
    nodes->push_back(node);
    if (count <= leaf_size || depth >= kBvhMaxDepth) return;

    const Vec3 extent = cbox.max - cbox.min;
    int axis = 0;
    if (extent.y() > extent[axis]) axis = 1;
    if (extent.z() > extent[axis]) axis = 2;
    const double lo = cbox.min[axis];
    const double scale = kBins / (double(cbox.max[axis]) - lo);

    uint32_t left_count = 0;
    Aabb left_box, left_c, right_box, right_c;
    if (!(extent[axis] > 0) || !std::isfinite(scale)) {
      // determinism: all centroids at one point; the median in index order.
      left_count = count / 2;
      scan(first, left_count, left_box, left_c);
      scan(first + left_count, count - left_count, right_box, right_c);
    } else {
      const auto bin_of = [&](uint32_t item) {
        const int b = int((double(centroids[item][axis]) - lo) * scale);
        return std::clamp(b, 0, kBins - 1);
      };
      std::array<Bin, kBins> bins;
      for (uint32_t k = first; k < first + count; ++k) {
        Bin& b = bins[bin_of(order[k])];
        grow(b.box, boxes[order[k]]);
        grow(b.centroids, centroids[order[k]]);
        ++b.count;
      }
      // Sweep from the right for the right-hand sides, then from the left for the costs. The
      // lowest and highest bins hold the extreme centroids, so both sides of every plane are
      // non-empty.
      std::array<double, kBins> right_cost{};
      Aabb acc = empty_box();
      uint32_t n = 0;
      for (int b = kBins - 1; b > 0; --b) {
        grow(acc, bins[b].box);
        n += bins[b].count;
        right_cost[b] = half_area(acc) * n;
      }
      acc = empty_box();
      n = 0;
      double best = std::numeric_limits<double>::infinity();
      int split = -1;
      for (int b = 0; b + 1 < kBins; ++b) {
        grow(acc, bins[b].box);
        n += bins[b].count;
        const double cost = half_area(acc) * n + right_cost[b + 1];
        if (cost < best) best = cost, split = b;  // ties: the lowest plane
      }
      const double parent = half_area(box);
      if (!(kTraversal * parent + best < parent * count)) return;  // no split improves
      left_box = left_c = right_box = right_c = empty_box();
      for (int b = 0; b < kBins; ++b) {
        Aabb& side_box = b <= split ? left_box : right_box;
        Aabb& side_c = b <= split ? left_c : right_c;
        grow(side_box, bins[b].box);
        grow(side_c, bins[b].centroids);
        if (b <= split) left_count += bins[b].count;
      }
      // determinism: std::partition's result is a function of its input sequence.
      std::partition(order + first, order + first + count,
                     [&](uint32_t item) { return bin_of(item) <= split; });
    }
    (*nodes)[self].count = 0;
    build(first, left_count, left_box, left_c, depth + 1);
    (*nodes)[self].index = uint32_t(nodes->size());
    build(first + left_count, count - left_count, right_box, right_c, depth + 1);
  }
};

}  // namespace

Bvh build_bvh(std::span<const Aabb> boxes, int leaf_size, std::vector<uint32_t>& order) {
  Bvh tree;
  const uint32_t n = uint32_t(boxes.size());
  order.resize(n);
  for (uint32_t k = 0; k < n; ++k) order[k] = k;
  if (n == 0) return tree;
  Builder b;
  b.boxes = boxes;
  b.centroids.resize(n);
  for (uint32_t k = 0; k < n; ++k) b.centroids[k] = (boxes[k].min + boxes[k].max) / 2;
  b.order = order.data();
  b.nodes = &tree.nodes;
  b.leaf_size = uint32_t(std::max(leaf_size, 1));
  // perf: a tree of leaves of leaf_size items has about 2 n / leaf_size nodes.
  tree.nodes.reserve(2 * (std::size_t(n) / b.leaf_size) + 1);
  Aabb box, cbox;
  b.scan(0, n, box, cbox);
  b.build(0, n, box, cbox, 0);
  tree.nodes.shrink_to_fit();
  return tree;
}

// The slab test rounds each t by up to 3 ulps; widening the exit by 2 gamma(3) relative (Pharr,
// Jakob & Humphreys, PBRT 3rd ed., 3.9.2) keeps it conservative, so a ray that meets a triangle
// exactly on its leaf's box (a flat mesh's boxes have no thickness) still enters the leaf.
constexpr Real kGamma3 =
    3 * std::numeric_limits<Real>::epsilon() / (1 - 3 * std::numeric_limits<Real>::epsilon());

Real ray_enters_node(const BvhNode& n, const Vec3& origin, const Vec3& inv_dir, Real max_t) {
  Real t_in = 0, t_out = max_t;
  for (int a = 0; a < 3; ++a) {
    const Real lo = Real(n.min[a]), hi = Real(n.max[a]);
    if (std::isinf(inv_dir[a])) {
      // Parallel to this slab: inside it or never (and no 0 * inf).
      if (origin[a] < lo || origin[a] > hi) return -1;
      continue;
    }
    Real t1 = (lo - origin[a]) * inv_dir[a];
    Real t2 = (hi - origin[a]) * inv_dir[a];
    if (t1 > t2) std::swap(t1, t2);
    t2 *= 1 + 2 * kGamma3;
    t_in = std::max(t_in, t1);
    t_out = std::min(t_out, t2);
    if (t_in > t_out) return -1;
  }
  return t_in;
}

}  // namespace elan::detail
