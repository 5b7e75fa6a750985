// SPDX-License-Identifier: MIT
// Shape casts of the public API: the bodies whose leaf meets the swept box of the cast shape are
// each swept against exactly (narrowphase/shape_cast.hpp); the first (the tree walked along the
// cast, nearest first, pruned by the best fraction so far), or all sorted.
#include <algorithm>

#include "core/world/query_common.hpp"
#include "core/world/shape_queries.hpp"
#include "elan/world.hpp"
#include "narrowphase/shape_cast.hpp"

namespace elan::detail {

const Shape& query_shape(const WorldState& s, ShapeId id) {
  check_arg(shape_live(s, id), "shape", "not a live shape of this world");
  const Shape& shape = s.shapes[id.index];
  check_arg(is_convex(shape) || shape.type == ShapeType::Compound, "shape",
            "a query shape must be convex or a compound (not a plane, mesh or heightfield)");
  return shape;
}

Transform principal_pose(const Shape& shape, const Transform& user) {
  check_arg(user.position.allFinite(), "pose", "position must be finite");
  check_arg(user.rotation.coeffs().allFinite() && user.rotation.norm() > Real(1e-12), "pose",
            "rotation must be a finite non-zero quaternion");
  const Quat q = user.rotation.normalized();
  return {user.position + q * shape.frame_position, (q * shape.frame_rotation).normalized()};
}

void swept_box(const Shape& shape, const Transform& x, const Vec3& translation, Real grow, Vec3& lo,
               Vec3& hi) {
  shape_bounds(shape, x.position, x.rotation, lo, hi);
  lo += translation.cwiseMin(Vec3::Zero()) - Vec3::Constant(grow);
  hi += translation.cwiseMax(Vec3::Zero()) + Vec3::Constant(grow);
}

void for_each_cast_hit(const WorldState& s, const Shape& shape, const Transform& x,
                       const Vec3& translation, Real target, const QueryFilter& filter,
                       const std::function<void(uint32_t, const CastContact&)>& f) {
  Vec3 lo, hi;
  swept_box(shape, x, translation, target, lo, hi);
  for_each_candidate(s, lo, hi, filter, [&](uint32_t i) {
    CastContact c;
    if (shape_cast(shape, x, translation, body_shape(s, i), body_pose(s, i), target, c)) f(i, c);
  });
}

void first_cast_hit(const WorldState& s, const Shape& shape, const Transform& x,
                    const Vec3& translation, const QueryFilter& filter, uint32_t& best,
                    CastContact& best_c) {
  best = UINT32_MAX;
  // The earliest; equal fractions go to the lower index, so the order of the walk (the planes,
  // then the tree nearest first) does not change the answer.
  const auto consider = [&](uint32_t i) {
    CastContact c;
    if (!passes(s, filter, i)) return;
    if (!shape_cast(shape, x, translation, body_shape(s, i), body_pose(s, i), 0, c)) return;
    if (best == UINT32_MAX || c.fraction < best_c.fraction ||
        (c.fraction == best_c.fraction && i < best)) {
      best = i;
      best_c = c;
    }
  };
  const QueryTree& q = fresh_query_tree(s);
  for (const uint32_t p : q.planes) consider(p);
  // The cast shape's box, its centre moving along the translation (fraction t in [0, 1]) against
  // the leaves grown by its half extents. The advancement reports a body at a fraction where the
  // two are still up to 1e-4 of the larger bounding radius apart (toi.cpp): grown by that too, a
  // body reported at fraction f has its leaf entered at or before f, so pruning the entries past
  // the best fraction so far drops no body that could beat it.
  Vec3 lo, hi;
  shape_bounds(shape, x.position, x.rotation, lo, hi);
  const Real slack = Real(1e-4) * std::max(shape.bounding_radius, q.max_radius);
  const Vec3 grow = (hi - lo) / 2 + Vec3::Constant(slack);
  q.tree.sweep((lo + hi) / 2, translation, grow, 1, [&](uint32_t i, Real limit) {
    consider(i);
    return best == UINT32_MAX ? limit : best_c.fraction;
  });
}

}  // namespace elan::detail

namespace elan {

namespace {

void check_translation(const Vec3& t) {
  detail::check_arg(t.allFinite(), "translation", "must be finite");
}

}  // namespace

std::optional<ShapeCastHit> World::cast_shape(ShapeId shape, const Transform& start,
                                              const Vec3& translation,
                                              const QueryFilter& filter) const {
  const detail::WorldState& s = *state_;
  const detail::Shape& a = detail::query_shape(s, shape);
  const Transform x = detail::principal_pose(a, start);
  check_translation(translation);
  uint32_t best;
  detail::CastContact best_c;
  detail::first_cast_hit(s, a, x, translation, filter, best, best_c);
  if (best == UINT32_MAX) return std::nullopt;
  return ShapeCastHit{detail::body_id_at(s, best), best_c.fraction, best_c.point, best_c.normal};
}

void World::cast_shape_all(ShapeId shape, const Transform& start, const Vec3& translation,
                           std::vector<ShapeCastHit>& out, const QueryFilter& filter) const {
  const detail::WorldState& s = *state_;
  const detail::Shape& a = detail::query_shape(s, shape);
  const Transform x = detail::principal_pose(a, start);
  check_translation(translation);
  std::vector<std::pair<uint32_t, detail::CastContact>> found;
  detail::for_each_cast_hit(
      s, a, x, translation, 0, filter,
      [&](uint32_t i, const detail::CastContact& c) { found.emplace_back(i, c); });
  // determinism: by (fraction, index), whatever order the tree was walked in.
  std::sort(found.begin(), found.end(), [](const auto& p, const auto& q) {
    return p.second.fraction < q.second.fraction ||
           (p.second.fraction == q.second.fraction && p.first < q.first);
  });
  out.clear();
  for (const auto& [i, c] : found) {
    out.push_back({detail::body_id_at(s, i), c.fraction, c.point, c.normal});
  }
}

}  // namespace elan
