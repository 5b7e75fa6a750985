// SPDX-License-Identifier: MIT
// The ray kernel of the scene queries: a ray against each shape type in its principal frame
// (closed forms; hulls by their face planes; meshes, heightfields and compounds by their trees).
#include "core/world/queries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/compound.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/triangle_mesh.hpp"

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
