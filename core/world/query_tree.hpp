// SPDX-License-Identifier: MIT
// The query tree: a dynamic tree (broadphase/dynamic_tree.hpp) over every body's exact box, leaves
// grown by kQueryFatMargin, which every scene query reads. Every API call that changes a pose, a
// shape or the body set refits it at once (query_tree_update, query_tree_remove,
// query_tree_refit_all). The step only notes which bodies it moved (query_tree_after_step); their
// leaves are refitted by the first query after it (fresh_query_tree), under a lock, so a world that
// is stepped and not queried never pays for the tree's upkeep, and any number of threads may still
// query at once between steps.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#include "broadphase/dynamic_tree.hpp"

namespace elan::detail {

struct WorldState;

// m: how far a body may move before its leaf is rebuilt. perf: the queries test the exact shape
// after the leaf, so a wider leaf costs only extra shape tests; 5 cm keeps a settling pile's
// bodies in their leaves while a query's leaves stay tight.
inline constexpr Real kQueryFatMargin = Real(0.05);

struct QueryTree {
  DynamicTree tree;
  // Bodies kept out of the tree, by index, sorted: planes (infinite boxes). Quarantined bodies
  // (non-finite poses) are in neither list: no query finds them.
  std::vector<uint32_t> planes;
  // The bodies a step moved whose leaves are not yet refitted (1 each), and the last step's dt (a
  // leaf is stretched by velocity * dt). Their boxes are computed at the refit, from the poses
  // then: a pose changes between steps only through the API, which refits the leaf at once.
  // perf: a falling body leaves its leaf every few steps, each time a serial re-insert, and most
  // worlds are stepped many times for each query, or never queried.
  std::vector<uint8_t> pending;
  Real pending_dt = 0;
  // Set by a step, cleared by the refit of the pending leaves (release: a query that reads it
  // false with acquire sees the refitted tree). The lock makes one thread do the refit.
  std::atomic<bool> stale{false};
  std::mutex refit_lock;
  // m: the largest bounding radius of any shape a body has had since the world was made (only
  // grows): the shape cast's bound on the advancement's tolerance (shape_cast.cpp).
  Real max_radius = 0;
};

// THE per-body hook: body `index`'s pose, shape or existence changed between steps (a new body:
// call after it is stored). Recomputes its exact box and refits its leaf.
void query_tree_update(WorldState& s, uint32_t index);
// Body `index` is about to be swap-removed (the last body takes its index): call before the
// store's swap_remove.
void query_tree_remove(WorldState& s, uint32_t index);
// Every body may have changed (bulk setters, snapshot and rollback restores): every body's leaf
// refitted, entries past the body count dropped.
void query_tree_refit_all(WorldState& s);
// The step's last stage: marks every body the step may have moved (awake dynamic, kinematic,
// quarantined) pending; their leaves are refitted by the next query (fresh_query_tree) or the
// next API hook that touches them.
void query_tree_after_step(WorldState& s, Real dt);
// The tree, its pending leaves refitted first (serially in index order, under the tree's lock):
// what every query reads. A leaf is stretched along the body's motion over one step (its
// velocity times the step's dt; DynamicTree::update_moving): perf: a falling or sliding body
// queried every step is then re-inserted every few steps, not every step.
// determinism: the tree's shape then depends on when the world was queried as well as on its
// history; no query's answer does (ARCHITECTURE.md, "The query tree and the queries").
const QueryTree& fresh_query_tree(const WorldState& s);

}  // namespace elan::detail
