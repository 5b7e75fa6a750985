// SPDX-License-Identifier: MIT
// What the shape queries (shape casts, overlaps, the character mover) share: the query shape's
// checks, its principal pose, and the sweep over the bodies near its path.
#pragma once

#include <functional>

#include "core/world/world_state.hpp"
#include "elan/queries.hpp"
#include "narrowphase/shape_cast.hpp"

namespace elan::detail {

// The live convex or compound shape `id`; elan::Error "shape" otherwise.
const Shape& query_shape(const WorldState& s, ShapeId id);
// The principal-frame pose of `shape` placed at the user's pose (checked: "pose").
Transform principal_pose(const Shape& shape, const Transform& user);
// The box of `shape` at x swept along `translation`, grown by `grow` on every side.
void swept_box(const Shape& shape, const Transform& x, const Vec3& translation, Real grow, Vec3& lo,
               Vec3& hi);
// Calls f(index, contact) for every body passing the filter that the shape, swept from x along
// `translation`, comes within `target` of (shape_cast), in the query tree's order.
void for_each_cast_hit(const WorldState& s, const Shape& shape, const Transform& x,
                       const Vec3& translation, Real target, const QueryFilter& filter,
                       const std::function<void(uint32_t, const CastContact&)>& f);
// The first body passing the filter that the shape, swept from x along `translation`, touches
// (shape_cast with target 0): the least fraction, ties to the lower index; best = UINT32_MAX when
// none. The same answer as the earliest of for_each_cast_hit's, found by walking the query tree
// along the cast and skipping every node entered after the best fraction so far.
void first_cast_hit(const WorldState& s, const Shape& shape, const Transform& x,
                    const Vec3& translation, const QueryFilter& filter, uint32_t& best,
                    CastContact& best_c);

}  // namespace elan::detail
