// SPDX-License-Identifier: MIT
// Closest points and containment per shape type: closed forms for the round shapes and the box,
// the face planes of a hull from inside and GJK from outside, the triangles of a surface under
// a search box, and a compound's parts.
#include "narrowphase/shape_point.hpp"

#include <algorithm>
#include <cmath>

#include "core/base/compound.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/triangle_mesh.hpp"
#include "narrowphase/closest_on_triangle.hpp"
#include "narrowphase/minkowski.hpp"

namespace elan::detail {

namespace {

constexpr Real kInf = std::numeric_limits<Real>::infinity();

// The direction from c to q, or `fallback` when they coincide.
Vec3 unit_or(const Vec3& v, const Vec3& fallback) {
  const Real len = v.norm();
  return len > 0 ? Vec3(v / len) : fallback;
}

// Round shapes: the surface at `r` around the closest point c of the core.
void round_closest(const Vec3& q, const Vec3& c, Real r, ShapePoint& out) {
  const Vec3 n = unit_or(q - c, Vec3::UnitY());
  out.normal = n;
  out.point = c + r * n;
  out.distance = (q - c).norm() - r;
}

void box_closest(const Vec3& q, const Vec3& h, ShapePoint& out) {
  const Vec3 c = q.cwiseMax(-h).cwiseMin(h);
  if (c != q) {
    out.point = c;
    out.distance = (q - c).norm();
    out.normal = (q - c) / out.distance;
    return;
  }
  // Inside: the nearest face.
  int axis = 0;
  Real gap = kInf;
  for (int a = 0; a < 3; ++a) {
    const Real g = h[a] - std::abs(q[a]);
    if (g < gap) gap = g, axis = a;
  }
  const Real sign = q[axis] < 0 ? Real(-1) : Real(1);
  out.point = q;
  out.point[axis] = sign * h[axis];
  out.distance = -gap;
  out.normal = sign * Vec3::Unit(axis);
}

void cylinder_closest(const Vec3& q, Real r, Real hh, ShapePoint& out) {
  const Real rho = std::sqrt(q.x() * q.x() + q.z() * q.z());
  const Vec3 radial = rho > 0 ? Vec3(q.x() / rho, 0, q.z() / rho) : Vec3::UnitX();
  if (rho > r || std::abs(q.y()) > hh) {
    const Real s = rho > r ? r / rho : Real(1);
    const Vec3 c(q.x() * s, std::clamp(q.y(), -hh, hh), q.z() * s);
    out.point = c;
    out.distance = (q - c).norm();
    out.normal = (q - c) / out.distance;
    return;
  }
  const Real side = r - rho, cap = hh - std::abs(q.y());
  if (side < cap) {
    out.point = Vec3(radial.x() * r, q.y(), radial.z() * r);
    out.distance = -side;
    out.normal = radial;
  } else {
    const Real sign = q.y() < 0 ? Real(-1) : Real(1);
    out.point = Vec3(q.x(), sign * hh, q.z());
    out.distance = -cap;
    out.normal = sign * Vec3::UnitY();
  }
}

void hull_closest(const Shape& shape, const Vec3& q, ShapePoint& out) {
  const ConvexHull& hull = *shape.hull;
  std::size_t nearest = 0;
  Real gap = kInf;
  bool inside = true;
  for (std::size_t k = 0; k < hull.faces.size(); ++k) {
    const Real g = hull.faces[k].offset - hull.faces[k].normal.dot(q);
    if (g < 0) inside = false;
    if (g < gap) gap = g, nearest = k;
  }
  if (inside) {
    // From inside a convex solid the nearest face plane's foot lies on that face.
    const Vec3 n = hull.faces[nearest].normal;
    out.point = q + gap * n;
    out.distance = -gap;
    out.normal = n;
    return;
  }
  Simplex s;
  const Vec3 core[1] = {q};
  const GjkResult g = gjk_core_in_frame_of_b(core, shape, s);
  out.point = g.point_b;
  out.distance = (q - g.point_b).norm();
  out.normal = unit_or(q - g.point_b, hull.faces[nearest].normal);
}

// The surface's triangles under the box q +- radius, the closest kept (ties: the first in the
// surface's fixed order).
template <class Surface>
bool surface_closest(const Surface& surface, const Vec3& q, Real radius, ShapePoint& out) {
  bool found = false;
  Real best = radius;
  const Vec3 lo = q - Vec3::Constant(radius), hi = q + Vec3::Constant(radius);
  for_each_triangle(surface, lo, hi, [&](const MeshTriangle& t) {
    const Vec3 c = closest_on_triangle(q, t.v[0], t.v[1], t.v[2]);
    const Real d = (q - c).norm();
    if (!(d <= best) || (found && !(d < best))) return;
    best = d;
    found = true;
    out.point = c;
    out.distance = d;
    Vec3 n = t.normal();
    if (n.dot(q - c) < 0) n = -n;
    out.normal = unit_or(q - c, n);
  });
  return found;
}

template <class Surface>
bool surface_search(const Shape& shape, const Surface& surface, const Vec3& q, Real max_distance,
                    ShapePoint& out) {
  if (std::isfinite(max_distance)) return surface_closest(surface, q, max_distance, out);
  // Widen from the distance to the surface's box until a triangle lies within the radius; a
  // closer one than any found at radius R lies within R, so the first find is the answer.
  const Vec3 outside = (q - q.cwiseMax(shape.local_min).cwiseMin(shape.local_max)).cwiseAbs();
  const Real reach = (shape.local_max - shape.local_min).norm();
  Real radius = std::max(outside.norm(), Real(1e-3) * std::max(reach, Real(1)));
  for (int k = 0; k < 64; ++k) {
    if (surface_closest(surface, q, radius, out)) return true;
    if (radius > outside.norm() + reach) return false;
    radius *= 2;
  }
  return false;
}

bool local_closest(const Shape& shape, const Vec3& q, Real max_distance, ShapePoint& out) {
  switch (shape.type) {
    case ShapeType::Sphere:
      round_closest(q, Vec3::Zero(), shape.radius, out);
      return true;
    case ShapeType::Box:
      box_closest(q, shape.half_extents, out);
      return true;
    case ShapeType::Capsule:
      round_closest(q, Vec3(0, std::clamp(q.y(), -shape.half_height, shape.half_height), 0),
                    shape.radius, out);
      return true;
    case ShapeType::Cylinder:
      cylinder_closest(q, shape.radius, shape.half_height, out);
      return true;
    case ShapeType::ConvexHull:
      hull_closest(shape, q, out);
      return true;
    case ShapeType::Plane: {
      const Vec3 n = shape.plane_normal.normalized();
      const Real h = n.dot(q) - shape.plane_offset / shape.plane_normal.norm();
      out.point = q - h * n;
      out.distance = h;
      out.normal = n;
      return true;
    }
    case ShapeType::Mesh:
      return surface_search(shape, *shape.mesh, q, max_distance, out);
    case ShapeType::Heightfield:
      return surface_search(shape, *shape.heightfield, q, max_distance, out);
    case ShapeType::Compound: {
      bool found = false;
      for (const CompoundPart& part : shape.compound->parts) {
        ShapePoint p;
        const Vec3 pq = part.pose.apply_inverse(q);
        if (!local_closest(part.shape, pq, max_distance, p)) continue;
        if (found && !(p.distance < out.distance)) continue;
        found = true;
        out.distance = p.distance;
        out.point = part.pose.rotation * p.point + part.pose.position;
        out.normal = part.pose.rotation * p.normal;
      }
      return found;
    }
  }
  return false;
}

}  // namespace

Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return p + closest_on_triangle_to_origin<Vec3>(a - p, b - p, c - p).point;
}

bool closest_on_shape(const Shape& shape, const Transform& x, const Vec3& p, ShapePoint& out,
                      Real max_distance) {
  ShapePoint local;
  if (!local_closest(shape, x.apply_inverse(p), max_distance, local)) return false;
  out.point = x.rotation * local.point + x.position;
  out.normal = (x.rotation * local.normal).normalized();
  out.distance = local.distance;
  return true;
}

bool shape_contains(const Shape& shape, const Transform& x, const Vec3& p) {
  if (shape.type == ShapeType::Mesh || shape.type == ShapeType::Heightfield) return false;
  const Vec3 q = x.apply_inverse(p);
  if (shape.type == ShapeType::Compound) {
    for (const CompoundPart& part : shape.compound->parts) {
      if (shape_contains(part.shape, part.pose, q)) return true;
    }
    return false;
  }
  ShapePoint local;
  return local_closest(shape, q, kInf, local) && local.distance <= 0;
}

}  // namespace elan::detail
