// SPDX-License-Identifier: MIT
// Upkeep of the query tree: per-body refits between steps, the step's marks and the refit of
// the first query after it, rebuilds.
#include "core/world/query_tree.hpp"

#include <algorithm>

#include "core/world/world_state.hpp"

namespace elan::detail {

namespace {

// Compacts the tree (DynamicTree::compact) once the inserts since the last compaction reach half
// its nodes: O(nodes) every nodes / 2 inserts, O(1) amortised per insert, and a tree of more than
// a few thousand nodes (past the caches' reach, where the layout matters) walked in memory order.
// determinism: the trigger counts inserts, a function of the world's history and of when it was
// queried; the compaction changes no leaf's box, no query's answer and no walk's order.
void maybe_compact(QueryTree& q) {
  const std::size_t nodes = q.tree.node_count();
  if (nodes >= 4096 && q.tree.inserts_since_compact() * 2 >= nodes) q.tree.compact();
}

void drop_plane(std::vector<uint32_t>& planes, uint32_t index) {
  const auto it = std::lower_bound(planes.begin(), planes.end(), index);
  if (it != planes.end() && *it == index) planes.erase(it);
}

// Files body i by its exact box: a plane to the plane list, a finite box to the tree, a
// non-finite one (a quarantined body) nowhere. A static body's leaf is its box grown by the
// margin, exactly: determinism: the continuous stage picks its static candidates by their leaves
// during the step, and a leaf kept from the body's moving days (update_moving keeps any leaf
// that still holds the box) would depend on when the world was last queried, which refits the
// moving leaves (fresh_query_tree).
void place(QueryTree& q, uint32_t i, bool plane, bool is_static, const Vec3& lo, const Vec3& hi,
           const Vec3& displacement = Vec3::Zero()) {
  if (plane) {
    q.tree.remove(i);
    const auto it = std::lower_bound(q.planes.begin(), q.planes.end(), i);
    if (it == q.planes.end() || *it != i) q.planes.insert(it, i);
    return;
  }
  if (!lo.allFinite() || !hi.allFinite()) {
    q.tree.remove(i);
    return;
  }
  if (is_static) {
    const Vec3 m = Vec3::Constant(kQueryFatMargin);
    q.tree.set_exact(i, {lo - m, hi + m});
    return;
  }
  q.tree.update_moving(i, {lo, hi}, kQueryFatMargin, displacement);
}

// Refits the leaves query_tree_after_step left pending, in index order.
void refit_pending(const WorldState& s, QueryTree& q) {
  const BodyStore& b = s.bodies;
  const std::size_t n = std::min(q.pending.size(), b.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (!q.pending[i]) continue;
    q.pending[i] = 0;
    Vec3 lo, hi;
    shape_bounds(s.shapes[b.shape[i]], b.position(i), b.orientation(i), lo, hi);
    place(q, uint32_t(i), false, b.is_static(i), lo, hi, b.linear_velocity(i) * q.pending_dt);
  }
  maybe_compact(q);
}

}  // namespace

const QueryTree& fresh_query_tree(const WorldState& s) {
  QueryTree& q = s.query;
  if (q.stale.load(std::memory_order_acquire)) {
    const std::lock_guard<std::mutex> lock(q.refit_lock);
    if (q.stale.load(std::memory_order_relaxed)) {
      refit_pending(s, q);
      q.stale.store(false, std::memory_order_release);
    }
  }
  return q;
}

void query_tree_update(WorldState& s, uint32_t index) {
  QueryTree& q = s.query;
  if (q.tree.item_count() < s.bodies.size()) q.tree.resize_items(s.bodies.size());
  // Placed now from its pose: no refit is left pending for it.
  if (index < q.pending.size()) q.pending[index] = 0;
  const Shape& shape = s.shapes[s.bodies.shape[index]];
  q.max_radius = std::max(q.max_radius, shape.bounding_radius);
  Vec3 lo, hi;
  shape_bounds(shape, s.bodies.position(index), s.bodies.orientation(index), lo, hi);
  if (shape.type != ShapeType::Plane) drop_plane(q.planes, index);
  place(q, index, shape.type == ShapeType::Plane, s.bodies.is_static(index), lo, hi);
  maybe_compact(q);
}

void query_tree_remove(WorldState& s, uint32_t index) {
  QueryTree& q = s.query;
  const uint32_t last = uint32_t(s.bodies.size() - 1);
  q.tree.remove(index);
  drop_plane(q.planes, index);
  // The last body's pending mark moves with it; one made since the last step has none.
  if (last < q.pending.size()) {
    q.pending[index] = q.pending[last];
    q.pending.resize(last);
  } else if (index < q.pending.size()) {
    q.pending[index] = 0;
  }
  if (index != last) {
    q.tree.rename(last, index);
    const auto it = std::lower_bound(q.planes.begin(), q.planes.end(), last);
    if (it != q.planes.end() && *it == last) {
      q.planes.erase(it);
      q.planes.insert(std::lower_bound(q.planes.begin(), q.planes.end(), index), index);
    }
  }
  q.tree.resize_items(last);
}

void query_tree_refit_all(WorldState& s) {
  QueryTree& q = s.query;
  const uint32_t n = uint32_t(s.bodies.size());
  for (std::size_t i = n; i < q.tree.item_count(); ++i) q.tree.remove(uint32_t(i));
  q.planes.erase(std::lower_bound(q.planes.begin(), q.planes.end(), n), q.planes.end());
  q.tree.resize_items(n);
  // perf: a rollback restores poses a few steps back, most inside their leaves: a containment
  // test each, not a rebuild.
  for (uint32_t i = 0; i < n; ++i) query_tree_update(s, i);
  q.stale.store(false, std::memory_order_relaxed);  // every mark was cleared above
}

void query_tree_after_step(WorldState& s, Real dt) {
  QueryTree& q = s.query;
  const BodyStore& b = s.bodies;
  const std::size_t n = b.size();
  if (q.tree.item_count() != n) {
    query_tree_refit_all(s);
    return;
  }
  // What the step may have moved: static bodies move only through the API (which refits them),
  // and a sleeping body keeps its pose; a body frozen this step left its pose non-finite.
  const auto moved = [&](std::size_t i) {
    return MotionType(b.motion[i]) != MotionType::Static && (b.flags[i] & (kAwake | kFrozen));
  };
  q.pending.resize(n);
  // A pass over one byte a body, serial: the boxes and leaves are the refit's (refit_pending,
  // serially in index order, so the tree's shape is the same for any thread count). A body
  // pending from an earlier step keeps its mark.
  for (std::size_t i = 0; i < n; ++i) {
    if (moved(i)) q.pending[i] = 1;
  }
  q.pending_dt = dt;
  q.stale.store(true, std::memory_order_relaxed);  // the step's caller publishes the world
}

}  // namespace elan::detail
