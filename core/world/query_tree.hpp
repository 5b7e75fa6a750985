// SPDX-License-Identifier: MIT
// The query tree: a dynamic tree (broadphase/dynamic_tree.hpp) over every body's exact box, leaves
// grown by kQueryFatMargin, which every scene query reads and nothing else. It is kept in step
// with the world by the step's last stage (query_tree_after_step) and by every API call that
// changes a pose, a shape or the body set (query_tree_update, query_tree_remove,
// query_tree_refit_all), so the queries themselves only read: they are const in fact, and any
// number of threads may run them at once between steps.
#pragma once

#include <cstdint>
#include <vector>

#include "broadphase/bounds.hpp"
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
  BoundsColumns boxes;  // the end-of-step pass's exact boxes (kept: no allocation when warm)
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
// The step's last stage: refits the leaves of every body the step may have moved (awake dynamic,
// kinematic, quarantined), serially in index order after a parallel pass over their boxes. A
// leaf is stretched along the body's motion over the next step of `dt` (its velocity times dt;
// DynamicTree::update_moving): perf: a falling or sliding body is then re-inserted every few
// steps, not every step, and that serial pass was a large part of a rain of bodies' step.
void query_tree_after_step(WorldState& s, Real dt);

}  // namespace elan::detail
