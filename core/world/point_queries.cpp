// SPDX-License-Identifier: MIT
// Closest-point queries of the public API: on one body, and over the bodies within a distance.
#include "core/world/query_common.hpp"
#include "elan/world.hpp"
#include "narrowphase/shape_point.hpp"

namespace elan {

PointHit World::closest_point(BodyId body, const Vec3& point) const {
  detail::check_arg(point.allFinite(), "point", "must be finite");
  const detail::WorldState& s = *state_;
  const std::size_t i = detail::index_of(s, body);
  detail::ShapePoint p;
  if (!detail::closest_on_shape(detail::body_shape(s, i), detail::body_pose(s, i), point, p)) {
    // Only a body with a non-finite pose (quarantined) has no closest point.
    return PointHit{body, point, std::numeric_limits<Real>::infinity(), Vec3::UnitY()};
  }
  return PointHit{body, p.point, p.distance, p.normal};
}

std::optional<PointHit> World::closest_point(const Vec3& point, Real max_distance,
                                             const QueryFilter& filter) const {
  detail::check_arg(point.allFinite(), "point", "must be finite");
  detail::check_arg(!std::isnan(max_distance) && max_distance >= 0, "max_distance", "must be >= 0");
  const detail::WorldState& s = *state_;
  const Vec3 reach = Vec3::Constant(max_distance);
  uint32_t best = UINT32_MAX;
  detail::ShapePoint best_p;
  // The least distance; equal distances go to the lower index.
  detail::for_each_candidate(s, point - reach, point + reach, filter, [&](uint32_t i) {
    detail::ShapePoint p;
    if (!detail::closest_on_shape(detail::body_shape(s, i), detail::body_pose(s, i), point, p,
                                  max_distance)) {
      return;
    }
    if (!(p.distance <= max_distance)) return;
    if (best == UINT32_MAX || p.distance < best_p.distance ||
        (p.distance == best_p.distance && i < best)) {
      best = i;
      best_p = p;
    }
  });
  if (best == UINT32_MAX) return std::nullopt;
  return PointHit{detail::body_id_at(s, best), best_p.point, best_p.distance, best_p.normal};
}

}  // namespace elan
