// SPDX-License-Identifier: MIT
// Shape creation: validation, exact mass properties per unit density (closed forms, and polyhedral
// integrals for hulls), principal frames and bounds; plus the support functions.
#include "core/base/shape.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>

#include "core/base/range_checks.hpp"
#include "elan/error.hpp"

namespace elan::detail {
namespace {

using Vec3d = Eigen::Vector3d;
using Mat3d = Eigen::Matrix3d;

constexpr double kPi = std::numbers::pi;

// A size (radius, half extent, half height): positive, and within the supported range.
void require_size(Real value, const char* field) {
  if (!std::isfinite(value) || !(value > 0)) {
    throw Error(field, "must be finite and > 0, got " + std::to_string(value));
  }
  check_range(value, limits::kMinSize, limits::kMaxSize, field, "m");
}

void set_box_bounds(Shape& s, const Vec3& half) {
  s.local_min = -half;
  s.local_max = half;
}

// Volume, centroid and covariance C = integral of x x^T dV (unit density) of a closed polyhedron,
// summed over tetrahedra (ref, a, b, c) of a fan triangulation of each face. For one tetrahedron
// with edge vectors a, b, c from ref: V = det/6 and C = det/120 (aa^T + bb^T + cc^T + ss^T),
// s = a + b + c (Blow & Binstock 2004; Tonon 2004). Signed volumes make the result exact for any
// reference point; the vertex mean keeps the terms small.
struct PolyMass {
  double volume = 0;
  Vec3d centroid = Vec3d::Zero();
  Mat3d inertia = Mat3d::Zero();  // about the centroid, per unit density
};

PolyMass polyhedron_mass(const ConvexHull& hull) {
  Vec3d ref = Vec3d::Zero();
  for (const Vec3& v : hull.vertices) ref += v.cast<double>();
  ref /= double(hull.vertices.size());

  double vol = 0;
  Vec3d first = Vec3d::Zero();
  Mat3d cov = Mat3d::Zero();
  for (const HullFace& f : hull.faces) {
    const Vec3d a = hull.vertices[hull.face_vertices[f.first]].cast<double>() - ref;
    for (uint32_t k = 1; k + 1 < f.count; ++k) {
      const Vec3d b = hull.vertices[hull.face_vertices[f.first + k]].cast<double>() - ref;
      const Vec3d c = hull.vertices[hull.face_vertices[f.first + k + 1]].cast<double>() - ref;
      const double det = a.dot(b.cross(c));
      const Vec3d s = a + b + c;
      vol += det / 6;
      first += det / 24 * s;
      cov += det / 120 *
             (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }
  }
  PolyMass m;
  m.volume = vol;
  const Vec3d c = first / vol;
  m.centroid = ref + c;
  // Parallel-axis shift of the covariance to the centroid, then I = tr(C) Id - C.
  const Mat3d cc = cov - vol * c * c.transpose();
  m.inertia = cc.trace() * Mat3d::Identity() - cc;
  return m;
}

// Rotation whose columns are principal axes of `inertia`, chosen deterministically: columns are
// permuted to lie closest to the identity, the first two point along +their diagonal axis, and
// the third is their cross product (det +1). An inertia that is already diagonal (relative to its
// trace, at Real precision) keeps the identity, so boxes, cubes and regular solids given in their
// own axes are not spun by eigen-solver noise in a degenerate eigenspace.
Mat3d principal_axes(const Mat3d& inertia, Vec3d& moments) {
  const double off = std::abs(inertia(0, 1)) + std::abs(inertia(0, 2)) + std::abs(inertia(1, 2));
  if (off <= 64 * double(std::numeric_limits<Real>::epsilon()) * inertia.trace()) {
    moments = inertia.diagonal();
    return Mat3d::Identity();
  }
  Eigen::SelfAdjointEigenSolver<Mat3d> eig(inertia);
  const Mat3d e = eig.eigenvectors();
  const Vec3d l = eig.eigenvalues();
  std::array<int, 3> perm{0, 1, 2}, best = perm;
  double best_score = -1;
  do {
    double score = 0;
    for (int i = 0; i < 3; ++i) score += std::abs(e(i, perm[i]));
    if (score > best_score + 1e-12) best_score = score, best = perm;
  } while (std::next_permutation(perm.begin(), perm.end()));
  Mat3d r;
  for (int i = 0; i < 3; ++i) {
    r.col(i) = e.col(best[i]);
    moments[i] = l[best[i]];
  }
  for (int i = 0; i < 2; ++i) {
    if (r(i, i) < 0) r.col(i) = -r.col(i);
  }
  r.col(2) = r.col(0).cross(r.col(1)).normalized();
  return r;
}

void make_hull(Shape& s, const ShapeDef& def) {
  // The points are in the body's frame: their offset is a position, their spread a size.
  for (const Vec3& p : def.points) {
    check_coordinates(p, limits::kMaxPosition, "shape.points", "m");
  }
  ConvexHull hull;
  try {
    hull = build_convex_hull(def.points);
  } catch (const Error& e) {
    // The hull builder names its own argument "points"; here it is the def's field.
    throw Error("shape.points", std::string(e.what()).substr(e.field().size() + 2));
  }
  const PolyMass m = polyhedron_mass(hull);
  Vec3d moments;
  const Mat3d r = principal_axes(m.inertia, moments);
  s.volume = Real(m.volume);
  s.unit_inertia = (moments / m.volume).cast<Real>();
  s.frame_position = m.centroid.cast<Real>();
  s.frame_rotation = Quat(r.cast<Real>()).normalized();
  auto principal = std::make_shared<ConvexHull>(
      transform_hull(hull, s.frame_position, r.transpose().cast<Real>()));
  s.local_min = Vec3::Constant(std::numeric_limits<Real>::max());
  s.local_max = -s.local_min;
  for (const Vec3& v : principal->vertices) {
    s.local_min = s.local_min.cwiseMin(v);
    s.local_max = s.local_max.cwiseMax(v);
    s.bounding_radius = std::max(s.bounding_radius, v.norm());
  }
  // Its half extents along the principal axes, as a box's.
  for (int i = 0; i < 3; ++i) {
    check_range(0.5 * (double(s.local_max[i]) - double(s.local_min[i])), limits::kMinSize,
                limits::kMaxSize, "shape.points", "m (the hull's half extent)");
  }
  s.hull = std::move(principal);
}

// Unit direction of d, or `fallback` when d = 0. A d so short (or long) that its squared norm
// under- or overflows is first rescaled by its largest component, off the common path.
Vec3 direction_or(const Vec3& d, const Vec3& fallback) {
  const Real n = d.norm();
  if (n > std::numeric_limits<Real>::min() && n <= std::numeric_limits<Real>::max()) return d / n;
  const Real m = d.cwiseAbs().maxCoeff();
  if (!(m > 0) || !std::isfinite(m)) return fallback;
  return (d / m).normalized();
}

}  // namespace

Shape make_shape(const ShapeDef& def) {
  Shape s;
  s.type = def.type;
  switch (def.type) {
    case ShapeType::Sphere: {
      require_size(def.radius, "shape.radius");
      const double r = def.radius;
      s.radius = def.radius;
      s.volume = Real(4.0 / 3.0 * kPi * r * r * r);
      s.unit_inertia = Vec3::Constant(Real(0.4 * r * r));
      set_box_bounds(s, Vec3::Constant(s.radius));
      s.bounding_radius = s.radius;
      break;
    }
    case ShapeType::Box: {
      for (int i = 0; i < 3; ++i) require_size(def.half_extents[i], "shape.half_extents");
      const Vec3d h = def.half_extents.cast<double>();
      const Vec3d h2 = h.cwiseProduct(h);
      s.half_extents = def.half_extents;
      s.volume = Real(8 * h.prod());
      // Solid box with half extents a, b, c: I_x / m = (b^2 + c^2) / 3.
      s.unit_inertia = Vec3d(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y()).cast<Real>() / 3;
      set_box_bounds(s, s.half_extents);
      s.bounding_radius = s.half_extents.norm();
      break;
    }
    case ShapeType::Capsule: {
      require_size(def.radius, "shape.radius");
      require_size(def.half_height, "shape.half_height");
      const double r = def.radius, h = def.half_height;
      const double mc = kPi * r * r * 2 * h;          // cylinder of height 2h
      const double ms = 4.0 / 3.0 * kPi * r * r * r;  // both caps together
      // Axis: cylinder m r^2/2, the caps a sphere's 2/5 m r^2. Across: cylinder
      // m (3r^2 + (2h)^2)/12; each cap of mass ms/2 has 2/5 (ms/2) r^2 about its flat face, its
      // centroid 3r/8 from that face and h + 3r/8 from the centre, so by the parallel-axis theorem
      // both give ms (2/5 r^2 - (3r/8)^2 + (h + 3r/8)^2) = ms (2/5 r^2 + h^2 + 3hr/4).
      const double axial = mc * r * r / 2 + ms * 0.4 * r * r;
      const double across =
          mc * (3 * r * r + 4 * h * h) / 12 + ms * (0.4 * r * r + h * h + 0.75 * h * r);
      const double m = mc + ms;
      s.radius = def.radius;
      s.half_height = def.half_height;
      s.volume = Real(m);
      s.unit_inertia = Vec3d(across / m, axial / m, across / m).cast<Real>();
      set_box_bounds(s, Vec3(s.radius, s.half_height + s.radius, s.radius));
      s.bounding_radius = s.half_height + s.radius;
      break;
    }
    case ShapeType::Cylinder: {
      require_size(def.radius, "shape.radius");
      require_size(def.half_height, "shape.half_height");
      const double r = def.radius, h = def.half_height;
      s.radius = def.radius;
      s.half_height = def.half_height;
      s.volume = Real(kPi * r * r * 2 * h);
      // Solid cylinder of height 2h: axis r^2/2, across (3r^2 + (2h)^2)/12.
      const double across = (3 * r * r + 4 * h * h) / 12;
      s.unit_inertia = Vec3d(across, r * r / 2, across).cast<Real>();
      set_box_bounds(s, Vec3(s.radius, s.half_height, s.radius));
      s.bounding_radius = Real(std::sqrt(r * r + h * h));
      break;
    }
    case ShapeType::ConvexHull:
      make_hull(s, def);
      break;
    case ShapeType::Plane: {
      const Real n = def.normal.norm();
      if (!def.normal.allFinite() || !(n > 0) || !std::isfinite(n)) {
        throw Error("shape.normal", "must be finite and non-zero");
      }
      if (!std::isfinite(def.offset)) throw Error("shape.offset", "must be finite");
      check_range(def.offset, -limits::kMaxPosition, limits::kMaxPosition, "shape.offset", "m");
      s.plane_normal = def.normal / n;
      s.plane_offset = def.offset;
      break;
    }
    default:
      throw Error("shape.type", "unknown shape type");
  }
  return s;
}

Vec3 support(const Shape& shape, const Vec3& d) {
  switch (shape.type) {
    case ShapeType::Sphere:
      return shape.radius * direction_or(d, Vec3::UnitY());
    case ShapeType::Box:
      // perf: copysign is branch-free (random-sign directions mispredict a compare). A zero
      // component gives +h or -h by the sign of zero: either corner of that face is a support.
      return Vec3(std::copysign(shape.half_extents.x(), d.x()),
                  std::copysign(shape.half_extents.y(), d.y()),
                  std::copysign(shape.half_extents.z(), d.z()));
    case ShapeType::Capsule: {
      // Minkowski sum of the Y segment and a sphere: support of each, added.
      const Vec3 tip(0, std::copysign(shape.half_height, d.y()), 0);
      return tip + shape.radius * direction_or(d, Vec3::UnitY());
    }
    case ShapeType::Cylinder: {
      // Cap side by the sign of d_y, rim point along the radial part of d (the cap centre when
      // there is none). The 2D length is taken directly: squared, it only underflows for
      // |d| < 1e-19 (float), where the rescaling of direction_or is used instead.
      const Real y = std::copysign(shape.half_height, d.y());
      const Real n2 = d.x() * d.x() + d.z() * d.z();
      if (n2 > std::numeric_limits<Real>::min()) {
        const Real k = shape.radius / std::sqrt(n2);
        return Vec3(d.x() * k, y, d.z() * k);
      }
      const Vec3 radial = direction_or(Vec3(d.x(), 0, d.z()), Vec3::Zero());
      return shape.radius * radial + Vec3(0, y, 0);
    }
    case ShapeType::ConvexHull: {
      // determinism: ties go to the lowest vertex index.
      const std::vector<Vec3>& v = shape.hull->vertices;
      size_t best = 0;
      Real best_dot = v[0].dot(d);
      for (size_t i = 1; i < v.size(); ++i) {
        const Real h = v[i].dot(d);
        if (h > best_dot) best_dot = h, best = i;
      }
      return v[best];
    }
    case ShapeType::Plane:
    default:
      // A half-space has no support in most directions; its point nearest the origin stands in.
      return shape.plane_normal * shape.plane_offset;
  }
}

}  // namespace elan::detail
