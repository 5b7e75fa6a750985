// SPDX-License-Identifier: MIT
// What every scene query shares: the filter rule, argument checks, a body's principal-frame
// pose, and the walk over the bodies whose leaf meets a box (the query tree, then the planes).
// All read the world only.
#pragma once

#include <cmath>

#include "core/base/body_traits.hpp"
#include "core/world/events.hpp"
#include "core/world/query_tree.hpp"
#include "core/world/world_access.hpp"
#include "core/world/world_state.hpp"
#include "elan/queries.hpp"

namespace elan::detail {

// Box2D's query filter rule, sensors, then the caller's own test.
inline bool passes(const WorldState& s, const QueryFilter& filter, std::size_t i) {
  const BodyTraits& t = s.bodies.traits_of(i);
  if ((t.category & filter.mask_bits) == 0 || (t.mask & filter.category_bits) == 0) return false;
  if ((t.flags & kTraitSensor) && !filter.include_sensors) return false;
  return !filter.accept || filter.accept(body_id_at(s, uint32_t(i)));
}

inline Transform body_pose(const WorldState& s, std::size_t i) {
  return {s.bodies.position(i), s.bodies.orientation(i)};
}

inline const Shape& body_shape(const WorldState& s, std::size_t i) {
  return s.shapes[s.bodies.shape[i]];
}

inline Vec3 checked_direction(const Vec3& origin, const Vec3& direction, Real max_distance) {
  check_arg(origin.allFinite(), "origin", "must be finite");
  check_arg(direction.allFinite() && direction.norm() > 0, "direction",
            "must be finite and non-zero");
  check_arg(!std::isnan(max_distance) && max_distance >= 0, "max_distance", "must be >= 0");
  return direction.normalized();
}

// Calls f(index) for every body that passes the filter and whose leaf meets [lo, hi] (a plane:
// always), tree bodies first in the tree's order, then the planes in index order.
template <class F>
void for_each_candidate(const WorldState& s, const Vec3& lo, const Vec3& hi,
                        const QueryFilter& filter, F&& f) {
  const QueryTree& q = fresh_query_tree(s);
  q.tree.query({lo, hi}, [&](uint32_t i) {
    if (passes(s, filter, i)) f(i);
    return true;
  });
  for (const uint32_t p : q.planes) {
    if (passes(s, filter, p)) f(p);
  }
}

}  // namespace elan::detail
