// SPDX-License-Identifier: MIT
// Overlap queries of the public API: exact shape overlap, bounding-box overlap and point
// containment. The query tree gives the candidates; each is tested exactly, and the answer is
// sorted into dense index order.
#include <algorithm>

#include "core/world/query_common.hpp"
#include "core/world/shape_queries.hpp"
#include "elan/world.hpp"
#include "narrowphase/shape_point.hpp"

namespace elan {

namespace {

// The ids of `indices`, sorted by index (the tree's order is not the index order).
void ids_in_index_order(const detail::WorldState& s, std::vector<uint32_t>& indices,
                        std::vector<BodyId>& out) {
  std::sort(indices.begin(), indices.end());
  out.clear();
  out.reserve(indices.size());
  for (const uint32_t i : indices) out.push_back(detail::body_id_at(s, i));
}

}  // namespace

void World::overlap_shape(ShapeId shape, const Transform& pose, std::vector<BodyId>& out,
                          const QueryFilter& filter) const {
  const detail::WorldState& s = *state_;
  const detail::Shape& a = detail::query_shape(s, shape);
  const Transform x = detail::principal_pose(a, pose);
  Vec3 lo, hi;
  detail::shape_bounds(a, x.position, x.rotation, lo, hi);
  std::vector<uint32_t> found;
  detail::for_each_candidate(s, lo, hi, filter, [&](uint32_t i) {
    if (detail::shapes_overlap(a, x, detail::body_shape(s, i), detail::body_pose(s, i))) {
      found.push_back(i);
    }
  });
  ids_in_index_order(s, found, out);
}

void World::overlap_box(const Vec3& lo, const Vec3& hi, std::vector<BodyId>& out,
                        const QueryFilter& filter) const {
  detail::check_arg(lo.allFinite() && hi.allFinite() && (lo.array() <= hi.array()).all(), "box",
                    "corners must be finite with lo <= hi");
  const detail::WorldState& s = *state_;
  std::vector<uint32_t> found;
  // The leaves are fat: each candidate's own exact box decides.
  detail::for_each_candidate(s, lo, hi, filter, [&](uint32_t i) {
    Vec3 blo, bhi;
    detail::shape_bounds(detail::body_shape(s, i), s.bodies.position(i), s.bodies.orientation(i),
                         blo, bhi);
    if ((blo.array() <= hi.array()).all() && (lo.array() <= bhi.array()).all()) found.push_back(i);
  });
  ids_in_index_order(s, found, out);
}

void World::overlap_point(const Vec3& point, std::vector<BodyId>& out,
                          const QueryFilter& filter) const {
  detail::check_arg(point.allFinite(), "point", "must be finite");
  const detail::WorldState& s = *state_;
  std::vector<uint32_t> found;
  detail::for_each_candidate(s, point, point, filter, [&](uint32_t i) {
    if (detail::shape_contains(detail::body_shape(s, i), detail::body_pose(s, i), point)) {
      found.push_back(i);
    }
  });
  ids_in_index_order(s, found, out);
}

}  // namespace elan
