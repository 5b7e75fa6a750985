// SPDX-License-Identifier: MIT
// The bounds stage: world boxes of every body, swept over the step, as one SoA pass in fixed
// blocks. Shapes are reduced to a few per-body numbers so the rotation part is a SIMD loop.
#include "broadphase/bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/parallel.hpp"

namespace elan::detail {

namespace {

// perf: 256 bodies keep the per-block shape parameters (8 columns) in 8 KiB of stack.
constexpr std::size_t kBoundsGrain = 256;

// Every non-plane shape's world half-extent on axis i is
//   e_i = sum_j |R_ij| h_j + sphere_r + cyl_r * sqrt(1 - R_i1^2)
// around the centre p + R c: a box is |R| h; a sphere adds r on every axis; a capsule is its
// segment (h = (0, hh, 0)) plus r; a cylinder's rim circle of radius r about axis a = R e_y has
// extent r * sqrt(1 - a_i^2) on axis i, so its exact bound is hh |a_i| + r sqrt(1 - a_i^2);
// a hull is its principal-frame box, centre c and half size h, rotated (conservative).
struct ShapeParams {
  Real hx[kBoundsGrain], hy[kBoundsGrain], hz[kBoundsGrain];
  Real cx[kBoundsGrain], cy[kBoundsGrain], cz[kBoundsGrain];
  Real sphere_r[kBoundsGrain], cyl_r[kBoundsGrain], bound_r[kBoundsGrain];
};

void shape_params(const Shape& s, ShapeParams& p, std::size_t k) {
  p.hx[k] = p.hy[k] = p.hz[k] = p.cx[k] = p.cy[k] = p.cz[k] = 0;
  p.sphere_r[k] = p.cyl_r[k] = 0;
  p.bound_r[k] = s.bounding_radius;
  switch (s.type) {
    case ShapeType::Sphere:
      p.sphere_r[k] = s.radius;
      break;
    case ShapeType::Box:
      p.hx[k] = s.half_extents.x();
      p.hy[k] = s.half_extents.y();
      p.hz[k] = s.half_extents.z();
      break;
    case ShapeType::Capsule:
      p.hy[k] = s.half_height;
      p.sphere_r[k] = s.radius;
      break;
    case ShapeType::Cylinder:
      p.hy[k] = s.half_height;
      p.cyl_r[k] = s.radius;
      break;
    case ShapeType::ConvexHull:
    case ShapeType::Mesh:
    case ShapeType::Heightfield:
    case ShapeType::Compound: {
      const Vec3 c = Real(0.5) * (s.local_max + s.local_min);
      const Vec3 h = Real(0.5) * (s.local_max - s.local_min);
      p.hx[k] = h.x();
      p.hy[k] = h.y();
      p.hz[k] = h.z();
      p.cx[k] = c.x();
      p.cy[k] = c.y();
      p.cz[k] = c.z();
      break;
    }
    case ShapeType::Plane:
      p.bound_r[k] = 0;  // overwritten by plane_bounds after the SIMD loop
      break;
  }
}

// Half-space dot(n, x - p) <= offset in world. Unbounded on every axis unless n is exactly
// axis-aligned after rotation; then one side is the plane's level. Only exact zeros count, since
// a tolerance would cut off far-away bodies under a slightly tilted plane.
void plane_bounds(const Shape& s, const Quat& q, const Vec3& pos, Real margin, BoundsColumns& out,
                  std::size_t i) {
  constexpr Real kInf = std::numeric_limits<Real>::infinity();
  Real lo[3] = {-kInf, -kInf, -kInf};
  Real hi[3] = {kInf, kInf, kInf};
  const Vec3 n = q * s.plane_normal;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    if (n[b] != 0 || n[c] != 0 || n[a] == 0) continue;
    // n = +-|n_a| e_a: the solid side is x_a <= pos_a + offset / n_a (or >= when n_a < 0).
    const Real level = pos[a] + s.plane_offset / n[a];
    if (n[a] > 0) {
      hi[a] = level + margin;
    } else {
      lo[a] = level - margin;
    }
  }
  out.min_x[i] = lo[0];
  out.min_y[i] = lo[1];
  out.min_z[i] = lo[2];
  out.max_x[i] = hi[0];
  out.max_y[i] = hi[1];
  out.max_z[i] = hi[2];
}

}  // namespace

void BoundsColumns::take_from(StepScratch& scratch) {
  for (ScratchVector<Real>* c : columns()) detail::take_from(*c, scratch);
}

void BoundsColumns::release() {
  for (ScratchVector<Real>* c : columns()) detail::release(*c);
}

void BoundsColumns::resize(std::size_t n) {
  for (ScratchVector<Real>* c : columns()) c->resize(n);
}

namespace {

// Both compute_bounds; `kinds` may be null.
void fill_bounds(const BodyStore& bodies, std::span<const Shape> shapes, Real dt, Real margin,
                 BoundsColumns& out, const BodyKindColumns* kinds) {
  const std::size_t n = bodies.size();
  out.resize(n);
  // determinism: fixed blocks, every body writes only its own slots (rules 1 and 2).
  for_blocks(n, kBoundsGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
    const std::size_t m = end - begin;
    ShapeParams p;
    for (std::size_t k = 0; k < m; ++k) shape_params(shapes[bodies.shape[begin + k]], p, k);

    const Real* px = bodies.px.data() + begin;
    const Real* py = bodies.py.data() + begin;
    const Real* pz = bodies.pz.data() + begin;
    const Real* qw = bodies.qw.data() + begin;
    const Real* qx = bodies.qx.data() + begin;
    const Real* qy = bodies.qy.data() + begin;
    const Real* qz = bodies.qz.data() + begin;
    const Real* vx = bodies.vx.data() + begin;
    const Real* vy = bodies.vy.data() + begin;
    const Real* vz = bodies.vz.data() + begin;
    const Real* wx = bodies.wx.data() + begin;
    const Real* wy = bodies.wy.data() + begin;
    const Real* wz = bodies.wz.data() + begin;
    Real* lo_x = out.min_x.data() + begin;
    Real* lo_y = out.min_y.data() + begin;
    Real* lo_z = out.min_z.data() + begin;
    Real* hi_x = out.max_x.data() + begin;
    Real* hi_y = out.max_y.data() + begin;
    Real* hi_z = out.max_z.data() + begin;

#pragma omp simd
    for (std::size_t k = 0; k < m; ++k) {
      // Rotation matrix of the unit quaternion (w, x, y, z).
      const Real w = qw[k], x = qx[k], y = qy[k], z = qz[k];
      const Real r00 = 1 - 2 * (y * y + z * z), r01 = 2 * (x * y - w * z),
                 r02 = 2 * (x * z + w * y);
      const Real r10 = 2 * (x * y + w * z), r11 = 1 - 2 * (x * x + z * z),
                 r12 = 2 * (y * z - w * x);
      const Real r20 = 2 * (x * z - w * y), r21 = 2 * (y * z + w * x),
                 r22 = 1 - 2 * (x * x + y * y);

      const Real ccx = px[k] + r00 * p.cx[k] + r01 * p.cy[k] + r02 * p.cz[k];
      const Real ccy = py[k] + r10 * p.cx[k] + r11 * p.cy[k] + r12 * p.cz[k];
      const Real ccz = pz[k] + r20 * p.cx[k] + r21 * p.cy[k] + r22 * p.cz[k];

      // A rotation by angle |w| dt moves a point at distance <= R from the centre by at most
      // R |w| dt (arc length), and never leaves the ball of radius R: cap the growth at R.
      const Real wlen = std::sqrt(wx[k] * wx[k] + wy[k] * wy[k] + wz[k] * wz[k]);
      const Real grow = std::min(wlen * dt * p.bound_r[k], p.bound_r[k]) + margin;
      const Real common = p.sphere_r[k] + grow;

      const Real ex = std::abs(r00) * p.hx[k] + std::abs(r01) * p.hy[k] + std::abs(r02) * p.hz[k] +
                      p.cyl_r[k] * std::sqrt(std::max(Real(0), 1 - r01 * r01)) + common;
      const Real ey = std::abs(r10) * p.hx[k] + std::abs(r11) * p.hy[k] + std::abs(r12) * p.hz[k] +
                      p.cyl_r[k] * std::sqrt(std::max(Real(0), 1 - r11 * r11)) + common;
      const Real ez = std::abs(r20) * p.hx[k] + std::abs(r21) * p.hy[k] + std::abs(r22) * p.hz[k] +
                      p.cyl_r[k] * std::sqrt(std::max(Real(0), 1 - r21 * r21)) + common;

      // Union of the box at the start and the same box translated by v dt.
      const Real dx = vx[k] * dt, dy = vy[k] * dt, dz = vz[k] * dt;
      lo_x[k] = ccx - ex + std::min(Real(0), dx);
      lo_y[k] = ccy - ey + std::min(Real(0), dy);
      lo_z[k] = ccz - ez + std::min(Real(0), dz);
      hi_x[k] = ccx + ex + std::max(Real(0), dx);
      hi_y[k] = ccy + ey + std::max(Real(0), dy);
      hi_z[k] = ccz + ez + std::max(Real(0), dz);
    }

    for (std::size_t k = 0; k < m; ++k) {
      const Shape& s = shapes[bodies.shape[begin + k]];
      if (kinds) {
        const std::size_t i = begin + k;
        const BroadKind kind = broad_kind(bodies, i);
        kinds->broad_kind[i] = uint8_t(kind);
        kinds->is_plane[i] = s.type == ShapeType::Plane;
        kinds->idle[i] = kind == BroadKind::Static ||
                         (kind == BroadKind::Sleeping && !(bodies.flags[i] & kFrozen));
      }
      if (s.type != ShapeType::Plane) continue;
      plane_bounds(s, bodies.orientation(begin + k), bodies.position(begin + k), margin, out,
                   begin + k);
    }
  });
}

}  // namespace

void compute_bounds(const BodyStore& bodies, std::span<const Shape> shapes, Real dt, Real margin,
                    BoundsColumns& out) {
  fill_bounds(bodies, shapes, dt, margin, out, nullptr);
}

void compute_bounds(const BodyStore& bodies, std::span<const Shape> shapes, Real dt, Real margin,
                    BoundsColumns& out, const BodyKindColumns& kinds) {
  fill_bounds(bodies, shapes, dt, margin, out, &kinds);
}

Aabb shape_box(const Shape& shape, const Vec3& position, const Quat& orientation) {
  if (shape.type == ShapeType::Plane) {
    BoundsColumns one;
    one.resize(1);
    plane_bounds(shape, orientation, position, 0, one, 0);
    return {Vec3(one.min_x[0], one.min_y[0], one.min_z[0]),
            Vec3(one.max_x[0], one.max_y[0], one.max_z[0])};
  }
  Vec3 h = Vec3::Zero(), c = Vec3::Zero();
  Real sphere_r = 0, cyl_r = 0;
  switch (shape.type) {
    case ShapeType::Sphere:
      sphere_r = shape.radius;
      break;
    case ShapeType::Box:
      h = shape.half_extents;
      break;
    case ShapeType::Capsule:
      h.y() = shape.half_height;
      sphere_r = shape.radius;
      break;
    case ShapeType::Cylinder:
      h.y() = shape.half_height;
      cyl_r = shape.radius;
      break;
    default:
      c = Real(0.5) * (shape.local_max + shape.local_min);
      h = Real(0.5) * (shape.local_max - shape.local_min);
      break;
  }
  const Mat3 r = orientation.toRotationMatrix();
  const Vec3 centre = position + r * c;
  Vec3 e;
  for (int a = 0; a < 3; ++a) {
    e[a] = std::abs(r(a, 0)) * h.x() + std::abs(r(a, 1)) * h.y() + std::abs(r(a, 2)) * h.z() +
           cyl_r * std::sqrt(std::max(Real(0), 1 - r(a, 1) * r(a, 1))) + sphere_r;
  }
  return {centre - e, centre + e};
}

}  // namespace elan::detail
