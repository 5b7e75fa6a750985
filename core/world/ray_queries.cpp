// SPDX-License-Identifier: MIT
// Ray casts of the public API: closest, any, all, and the batched closest on the world's pool.
// The query tree is walked nearer child first with the best distance so far as its limit; each
// leaf's body is tested exactly (queries.hpp: ray_shape), the planes after the tree.
#include <algorithm>
#include <string>

#include "core/base/parallel.hpp"
#include "core/base/tbb_hand_off.hpp"
#include "core/world/queries.hpp"
#include "core/world/query_common.hpp"
#include "core/world/thread_pool_access.hpp"
#include "elan/world.hpp"

namespace elan::detail {

namespace {

// determinism: each block of rays writes its own hits (rule 1); a block is a fixed range (rule 2).
constexpr std::size_t kRayGrain = 32;

// Calls f(index, hit, limit) for every body (passing the filter) the ray enters within the
// limit; f returns the new limit (< 0 stops).
template <class F>
void walk_ray(const WorldState& s, const Vec3& o, const Vec3& d, Real max_t,
              const QueryFilter& filter, F&& f) {
  const QueryTree& q = fresh_query_tree(s);
  q.tree.ray(o, d, max_t, [&](uint32_t i, Real limit) {
    ShapeRayHit hit;
    if (!passes(s, filter, i)) return limit;
    if (!ray_shape(body_shape(s, i), body_pose(s, i), o, d, limit, hit)) return limit;
    return f(i, hit, limit);
  });
  for (const uint32_t p : q.planes) {
    if (max_t < 0) return;
    ShapeRayHit hit;
    if (!passes(s, filter, p)) continue;
    if (!ray_shape(body_shape(s, p), body_pose(s, p), o, d, max_t, hit)) continue;
    max_t = f(p, hit, max_t);
  }
}

// The closest hit: strictly closer replaces, and among equal distances the lower index (the
// walk's order is the tree's, not the index order).
std::optional<RayHit> closest_ray(const WorldState& s, const Vec3& origin, const Vec3& d,
                                  Real max_distance, const QueryFilter& filter) {
  uint32_t best = UINT32_MAX;
  ShapeRayHit best_hit;
  walk_ray(s, origin, d, max_distance, filter, [&](uint32_t i, const ShapeRayHit& h, Real limit) {
    if (best == UINT32_MAX || h.distance < best_hit.distance ||
        (h.distance == best_hit.distance && i < best)) {
      best = i;
      best_hit = h;
      return h.distance;
    }
    return limit;
  });
  if (best == UINT32_MAX) return std::nullopt;
  return RayHit{body_id_at(s, best), best_hit.distance, origin + best_hit.distance * d,
                best_hit.normal};
}

}  // namespace

}  // namespace elan::detail

namespace elan {

std::optional<RayHit> World::cast_ray(const Vec3& origin, const Vec3& direction, Real max_distance,
                                      const QueryFilter& filter) const {
  const Vec3 d = detail::checked_direction(origin, direction, max_distance);
  return detail::closest_ray(*state_, origin, d, max_distance, filter);
}

std::optional<RayHit> World::cast_ray_any(const Vec3& origin, const Vec3& direction,
                                          Real max_distance, const QueryFilter& filter) const {
  const Vec3 d = detail::checked_direction(origin, direction, max_distance);
  const detail::WorldState& s = *state_;
  std::optional<RayHit> found;
  detail::walk_ray(
      s, origin, d, max_distance, filter, [&](uint32_t i, const detail::ShapeRayHit& h, Real) {
        found = RayHit{detail::body_id_at(s, i), h.distance, origin + h.distance * d, h.normal};
        return Real(-1);
      });
  return found;
}

void World::cast_ray_all(const Vec3& origin, const Vec3& direction, Real max_distance,
                         std::vector<RayHit>& out, const QueryFilter& filter) const {
  const Vec3 d = detail::checked_direction(origin, direction, max_distance);
  const detail::WorldState& s = *state_;
  out.clear();
  struct Found {
    Real distance;
    uint32_t index;
    Vec3 normal;
  };
  std::vector<Found> found;
  detail::walk_ray(s, origin, d, max_distance, filter,
                   [&](uint32_t i, const detail::ShapeRayHit& h, Real limit) {
                     found.push_back({h.distance, i, h.normal});
                     return limit;
                   });
  // determinism: sorted by (distance, index), whatever order the tree was walked in.
  std::sort(found.begin(), found.end(), [](const Found& a, const Found& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.index < b.index);
  });
  out.reserve(found.size());
  for (const Found& f : found) {
    out.push_back({detail::body_id_at(s, f.index), f.distance, origin + f.distance * d, f.normal});
  }
}

void World::cast_rays(std::span<const Ray> rays, std::span<RayHit> hits,
                      const QueryFilter& filter) const {
  detail::check_arg(rays.size() == hits.size(), "hits", "must be as many as the rays");
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const Ray& r = rays[k];
    detail::check_arg(r.origin.allFinite(), "rays",
                      "ray " + std::to_string(k) + ": origin must be finite");
    detail::check_arg(r.direction.allFinite() && r.direction.norm() > 0, "rays",
                      "ray " + std::to_string(k) + ": direction must be finite and non-zero");
    detail::check_arg(!std::isnan(r.max_distance) && r.max_distance >= 0, "rays",
                      "ray " + std::to_string(k) + ": max_distance must be >= 0");
  }
  detail::WorldState& s = *state_;
  // threading: the arena runs `run` on this thread when it has a free slot, else on a worker
  // while this thread waits; the hand-off tells TSan of the second case's ordering (the hits
  // written there are read by the caller after execute returns).
  detail::TbbHandOff hand_off;
  const auto run = [&] {
    detail::TbbHandOff::TaskScope task(hand_off);
    detail::for_blocks(rays.size(), detail::kRayGrain,
                       [&](std::size_t b, std::size_t e, std::size_t) {
                         for (std::size_t k = b; k < e; ++k) {
                           const Ray& r = rays[k];
                           const Vec3 d = r.direction.normalized();
                           const std::optional<RayHit> h =
                               detail::closest_ray(s, r.origin, d, r.max_distance, filter);
                           hits[k] = h ? *h : RayHit{};
                         }
                       });
  };
  // The refit of the leaves the last step moved, here and once, not by the first block while the
  // others wait on the tree's lock (and a pool shared with another world's step idles).
  detail::fresh_query_tree(s);
  // The world's pool: arena.execute may be called from any thread, and the workers only read.
  tbb::task_arena& arena = s.def.thread_pool ? detail::arena_of(*s.def.thread_pool) : *s.arena;
  hand_off.spawn(run);
  arena.execute(run);
  hand_off.joined();
}

}  // namespace elan
