// SPDX-License-Identifier: MIT
// Scene queries: ray against each shape type in its principal frame (closed forms; hulls by
// their face planes), and the world-level ray cast and box overlap over cached bounds.
#include "core/world/queries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/compound.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/triangle_mesh.hpp"
#include "core/world/events.hpp"
#include "core/world/world_access.hpp"
#include "elan/world.hpp"

namespace elan::detail {

namespace {

constexpr Real kInf = std::numeric_limits<Real>::infinity();

// Entry into the sphere |x - c| = r of a ray starting outside it: t = -b - sqrt(b^2 - c).
bool ray_sphere(const Vec3& o, const Vec3& d, const Vec3& center, Real r, Real& t, Vec3& n) {
  const Vec3 m = o - center;
  const Real b = m.dot(d);
  const Real c = m.squaredNorm() - r * r;
  if (c <= 0 || b > 0) return false;  // inside, or outside and pointing away
  const Real disc = b * b - c;
  if (disc < 0) return false;
  t = std::max(Real(0), -b - std::sqrt(disc));
  n = (m + t * d) / r;
  return true;
}

// Side of the infinite cylinder x^2 + z^2 = r^2 (axis Y), entry only, hit height within |y| <= h.
bool ray_cylinder_side(const Vec3& o, const Vec3& d, Real r, Real h, Real& t, Vec3& n) {
  const Real a = d.x() * d.x() + d.z() * d.z();
  if (a <= Real(1e-12)) return false;
  const Real b = o.x() * d.x() + o.z() * d.z();
  const Real c = o.x() * o.x() + o.z() * o.z() - r * r;
  if (c <= 0 || b > 0) return false;
  const Real disc = b * b - a * c;
  if (disc < 0) return false;
  const Real s = std::max(Real(0), (-b - std::sqrt(disc)) / a);
  const Vec3 p = o + s * d;
  if (std::abs(p.y()) > h) return false;
  t = s;
  n = Vec3(p.x(), 0, p.z()) / r;
  return true;
}

// Cyrus-Beck clipping against half-spaces n.x <= offset: the ray enters at the largest entering
// t. `inside` reports an origin inside every half-space.
template <class Planes>
bool ray_half_spaces(const Vec3& o, const Vec3& d, const Planes& planes, std::size_t count, Real& t,
                     Vec3& n) {
  Real t_in = -kInf, t_out = kInf;
  bool inside = true;
  for (std::size_t k = 0; k < count; ++k) {
    const auto [normal, offset] = planes(k);
    const Real num = offset - normal.dot(o);
    const Real den = normal.dot(d);
    if (num < 0) inside = false;
    if (den == 0) {
      if (num < 0) return false;
      continue;
    }
    const Real s = num / den;
    if (den < 0) {
      if (s > t_in) {
        t_in = s;
        n = normal;
      }
    } else {
      t_out = std::min(t_out, s);
    }
    if (t_in > t_out) return false;
  }
  if (inside || t_in < 0) return false;
  t = t_in;
  return true;
}

bool ray_local(const Shape& shape, const Vec3& o, const Vec3& d, Real max_t, Real& t, Vec3& n);
bool ray_box(const Vec3& o, const Vec3& d, const Vec3& inv_d, const Real* lo, const Real* hi,
             Real max_t);

// The nearest child hit of a compound (its principal frame): each part's ray in the part's
// pose, the normal turned back; parts whose box the ray misses are skipped. Ties keep the first
// part in the compound's fixed order.
bool ray_compound(const Compound& c, const Vec3& o, const Vec3& d, Real max_t, Real& t, Vec3& n) {
  bool found = false;
  const auto test = [&](uint32_t k, Real limit) {
    const CompoundPart& p = c.parts[k];
    Real tk = 0;
    Vec3 nk = Vec3::UnitY();
    const Vec3 po = p.pose.apply_inverse(o);
    const Vec3 pd = p.pose.rotation.conjugate() * d;
    if (!ray_local(p.shape, po, pd, limit, tk, nk) || !(tk <= limit)) return limit;
    if (found && !(tk < t)) return limit;
    found = true;
    t = tk;
    n = p.pose.rotation * nk;
    return tk;
  };
  if (c.tree.nodes.empty()) {
    Real limit = max_t;
    for (uint32_t k = 0; k < c.parts.size(); ++k) {
      const Real lo[3] = {c.parts[k].box.min.x(), c.parts[k].box.min.y(), c.parts[k].box.min.z()};
      const Real hi[3] = {c.parts[k].box.max.x(), c.parts[k].box.max.y(), c.parts[k].box.max.z()};
      if (!ray_box(o, d, d.cwiseInverse(), lo, hi, limit)) continue;
      limit = test(k, limit);
    }
  } else {
    bvh_ray(c.tree, o, d, max_t, [&](uint32_t first, uint32_t count, Real limit) {
      for (uint32_t k = first; k < first + count; ++k) limit = test(k, limit);
      return limit;
    });
  }
  return found;
}

bool ray_local(const Shape& shape, const Vec3& o, const Vec3& d, Real max_t, Real& t, Vec3& n) {
  switch (shape.type) {
    case ShapeType::Sphere:
      return ray_sphere(o, d, Vec3::Zero(), shape.radius, t, n);
    case ShapeType::Box: {
      const Vec3 h = shape.half_extents;
      auto face = [&](std::size_t k) {
        const int axis = int(k / 2);
        const Real sign = (k % 2) ? Real(1) : Real(-1);
        return std::pair<Vec3, Real>(sign * Vec3::Unit(axis), h[axis]);
      };
      return ray_half_spaces(o, d, face, 6, t, n);
    }
    case ShapeType::Capsule: {
      // The capsule is the union of a finite cylinder and two end spheres; from outside, the
      // first entry into a union is the first entry into any part.
      const Real hh = shape.half_height, r = shape.radius;
      const Real y = std::clamp(o.y(), -hh, hh);
      if ((o - Vec3(0, y, 0)).squaredNorm() <= r * r) return false;  // starts inside
      bool hit = false;
      Real best = kInf, s;
      Vec3 m;
      if (ray_cylinder_side(o, d, r, hh, s, m) && s < best) best = s, n = m, hit = true;
      for (Real cy : {-hh, hh}) {
        if (ray_sphere(o, d, Vec3(0, cy, 0), r, s, m) && s < best) best = s, n = m, hit = true;
      }
      t = best;
      return hit;
    }
    case ShapeType::Cylinder: {
      const Real hh = shape.half_height, r = shape.radius;
      if (std::abs(o.y()) <= hh && o.x() * o.x() + o.z() * o.z() <= r * r) return false;
      bool hit = false;
      Real best = kInf, s;
      Vec3 m;
      if (ray_cylinder_side(o, d, r, hh, s, m)) best = s, n = m, hit = true;
      // Caps: the plane y = +-h entered from outside, inside the disc.
      if (d.y() != 0) {
        const Real cap = d.y() < 0 ? hh : -hh;
        s = (cap - o.y()) / d.y();
        const Vec3 p = o + s * d;
        if (s >= 0 && s < best && p.x() * p.x() + p.z() * p.z() <= r * r) {
          best = s;
          n = Vec3(0, cap > 0 ? 1 : -1, 0);
          hit = true;
        }
      }
      t = best;
      return hit;
    }
    case ShapeType::ConvexHull: {
      const ConvexHull& hull = *shape.hull;
      auto face = [&](std::size_t k) {
        return std::pair<Vec3, Real>(hull.faces[k].normal, hull.faces[k].offset);
      };
      return ray_half_spaces(o, d, face, hull.faces.size(), t, n);
    }
    case ShapeType::Plane: {
      auto face = [&](std::size_t) {
        return std::pair<Vec3, Real>(shape.plane_normal, shape.plane_offset);
      };
      return ray_half_spaces(o, d, face, 1, t, n);
    }
    case ShapeType::Mesh:
    case ShapeType::Heightfield: {
      SurfaceHit hit;
      const bool found = shape.mesh ? ray_cast_mesh(*shape.mesh, o, d, max_t, hit)
                                    : ray_cast_heightfield(*shape.heightfield, o, d, max_t, hit);
      if (!found) return false;
      t = hit.t;
      n = hit.normal;
      return true;
    }
    case ShapeType::Compound:
      return ray_compound(*shape.compound, o, d, max_t, t, n);
  }
  return false;
}

// Does the ray enter the box [lo, hi] before `max_t`? Slab test; an axis the ray runs parallel
// to must contain the origin. NaN boxes (frozen bodies) never pass.
bool ray_box(const Vec3& o, const Vec3& d, const Vec3& inv_d, const Real* lo, const Real* hi,
             Real max_t) {
  Real t0 = 0, t1 = max_t;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (!(o[a] >= lo[a] && o[a] <= hi[a])) return false;
      continue;
    }
    Real s0 = (lo[a] - o[a]) * inv_d[a], s1 = (hi[a] - o[a]) * inv_d[a];
    if (s0 > s1) std::swap(s0, s1);
    t0 = std::max(t0, s0);
    t1 = std::min(t1, s1);
    if (!(t0 <= t1)) return false;
  }
  return true;
}

const BoundsColumns& query_bounds(WorldState& s) {
  ApiState& api = s.api;
  if (api.query_mutations != api.mutations || api.query_step != s.step_count ||
      api.query_bounds.size() != s.bodies.size()) {
    compute_bounds(s.bodies, s.shapes, 0, 0, api.query_bounds);
    api.query_mutations = api.mutations;
    api.query_step = s.step_count;
  }
  return api.query_bounds;
}

Vec3 checked_direction(const Vec3& origin, const Vec3& direction, Real max_distance) {
  check_arg(origin.allFinite(), "origin", "must be finite");
  check_arg(direction.allFinite() && direction.norm() > 0, "direction",
            "must be finite and non-zero");
  check_arg(!std::isnan(max_distance) && max_distance >= 0, "max_distance", "must be >= 0");
  return direction.normalized();
}

// Box2D's query filter rule, then the caller's own test.
bool passes(const WorldState& s, const QueryFilter& filter, std::size_t i) {
  const auto& t = s.bodies.traits_of(i);
  if ((t.category & filter.mask_bits) == 0 || (t.mask & filter.category_bits) == 0) return false;
  return !filter.accept || filter.accept(body_id_at(s, uint32_t(i)));
}

// Calls f(index, hit) for every body the ray enters within max_t(), in index order; max_t is
// re-read per body so the closest-hit search can shrink it.
template <class MaxT, class F>
void for_each_ray_hit(WorldState& s, const Vec3& o, const Vec3& d, const QueryFilter& filter,
                      MaxT&& max_t, F&& f) {
  const BoundsColumns& b = query_bounds(s);
  const Vec3 inv_d = d.cwiseInverse();
  for (std::size_t i = 0; i < b.size(); ++i) {
    const Real lo[3] = {b.min_x[i], b.min_y[i], b.min_z[i]};
    const Real hi[3] = {b.max_x[i], b.max_y[i], b.max_z[i]};
    const Shape& shape = s.shapes[s.bodies.shape[i]];
    if (shape.type != ShapeType::Plane && !ray_box(o, d, inv_d, lo, hi, max_t())) continue;
    if (!passes(s, filter, i)) continue;
    ShapeRayHit hit;
    const Transform pose{s.bodies.position(i), s.bodies.orientation(i)};
    if (ray_shape(shape, pose, o, d, max_t(), hit)) f(i, hit);
  }
}

}  // namespace

bool ray_shape(const Shape& shape, const Transform& pose, const Vec3& origin, const Vec3& dir,
               Real max_distance, ShapeRayHit& out) {
  const Vec3 o = pose.apply_inverse(origin);
  const Vec3 d = pose.rotation.conjugate() * dir;
  Real t = 0;
  Vec3 n = Vec3::UnitY();
  if (!ray_local(shape, o, d, max_distance, t, n) || !(t <= max_distance)) return false;
  out.distance = t;
  out.normal = (pose.rotation * n).normalized();
  return true;
}

}  // namespace elan::detail

namespace elan {

std::optional<RayHit> World::cast_ray(const Vec3& origin, const Vec3& direction, Real max_distance,
                                      const QueryFilter& filter) const {
  const Vec3 d = detail::checked_direction(origin, direction, max_distance);
  detail::WorldState& s = *state_;
  std::optional<RayHit> best;
  Real best_t = max_distance;
  // Strictly closer replaces: among equal distances the lower index, visited first, stays.
  detail::for_each_ray_hit(
      s, origin, d, filter, [&] { return best_t; },
      [&](std::size_t i, const detail::ShapeRayHit& h) {
        if (best && !(h.distance < best_t)) return;
        best_t = h.distance;
        best = RayHit{detail::body_id_at(s, uint32_t(i)), h.distance, origin + h.distance * d,
                      h.normal};
      });
  return best;
}

void World::cast_ray_all(const Vec3& origin, const Vec3& direction, Real max_distance,
                         std::vector<RayHit>& out, const QueryFilter& filter) const {
  const Vec3 d = detail::checked_direction(origin, direction, max_distance);
  detail::WorldState& s = *state_;
  out.clear();
  std::vector<std::pair<Real, uint32_t>> order;
  std::vector<RayHit> hits;
  detail::for_each_ray_hit(
      s, origin, d, filter, [&] { return max_distance; },
      [&](std::size_t i, const detail::ShapeRayHit& h) {
        order.emplace_back(h.distance, uint32_t(hits.size()));
        hits.push_back(RayHit{detail::body_id_at(s, uint32_t(i)), h.distance,
                              origin + h.distance * d, h.normal});
      });
  // Hits were found in index order, so (distance, position) is (distance, index).
  std::sort(order.begin(), order.end());
  out.reserve(hits.size());
  for (const auto& [t, k] : order) out.push_back(hits[k]);
}

void World::overlap_box(const Vec3& lo, const Vec3& hi, std::vector<BodyId>& out,
                        const QueryFilter& filter) const {
  detail::check_arg(lo.allFinite() && hi.allFinite() && (lo.array() <= hi.array()).all(), "box",
                    "corners must be finite with lo <= hi");
  detail::WorldState& s = *state_;
  const detail::BoundsColumns& b = detail::query_bounds(s);
  out.clear();
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.min_x[i] <= hi.x() && lo.x() <= b.max_x[i] && b.min_y[i] <= hi.y() &&
        lo.y() <= b.max_y[i] && b.min_z[i] <= hi.z() && lo.z() <= b.max_z[i] &&
        detail::passes(s, filter, i)) {
      out.push_back(detail::body_id_at(s, uint32_t(i)));
    }
  }
}

}  // namespace elan
