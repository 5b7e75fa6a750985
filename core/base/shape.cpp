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

#include "core/base/compound.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/range_checks.hpp"
#include "core/base/triangle_mesh.hpp"
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

// Largest distance from the origin of a corner of the box [lo, hi] (in double, then rounded up
// so that the radius bounds every corner).
Real corner_radius(const Vec3& lo, const Vec3& hi) {
  double r2 = 0;
  for (int k = 0; k < 8; ++k) {
    const Vec3d c((k & 1 ? hi : lo).x(), (k & 2 ? hi : lo).y(), (k & 4 ? hi : lo).z());
    r2 = std::max(r2, c.squaredNorm());
  }
  const Real r = Real(std::sqrt(r2));
  return double(r) < std::sqrt(r2) ? std::nextafter(r, std::numeric_limits<Real>::infinity()) : r;
}

void make_mesh(Shape& s, const ShapeDef& def) {
  auto mesh = std::make_shared<TriangleMesh>(build_triangle_mesh(def.vertices, def.triangles));
  s.local_min = mesh->min;
  s.local_max = mesh->max;
  s.bounding_radius = corner_radius(s.local_min, s.local_max);
  s.mesh = std::move(mesh);
}

void make_heightfield(Shape& s, const ShapeDef& def) {
  auto field = std::make_shared<HeightField>(
      build_heightfield(def.heights, def.columns, def.spacing_x, def.spacing_z));
  s.local_min = Vec3(0, field->min_height, 0);
  // The far samples' coordinates exactly as HeightField::point rounds them.
  s.local_max = Vec3(Real(field->columns - 1) * field->spacing_x, field->max_height,
                     Real(field->rows - 1) * field->spacing_z);
  s.bounding_radius = corner_radius(s.local_min, s.local_max);
  s.heightfield = std::move(field);
}

// The bounds in the compound's principal frame of a child placed at `pose`: exact for spheres,
// capsules and hulls (their extreme points transformed), the transformed corners of the local
// box otherwise.
Aabb part_box(const Shape& c, const Transform& pose) {
  Aabb b;
  b.min = Vec3::Constant(std::numeric_limits<Real>::max());
  b.max = -b.min;
  const auto add = [&](const Vec3& p, Real r) {
    const Vec3 q = pose.apply(p);
    b.min = b.min.cwiseMin(q - Vec3::Constant(r));
    b.max = b.max.cwiseMax(q + Vec3::Constant(r));
  };
  switch (c.type) {
    case ShapeType::Sphere:
      add(Vec3::Zero(), c.radius);
      break;
    case ShapeType::Capsule:
      add(Vec3(0, c.half_height, 0), c.radius);
      add(Vec3(0, -c.half_height, 0), c.radius);
      break;
    case ShapeType::ConvexHull:
      for (const Vec3& v : c.hull->vertices) add(v, 0);
      break;
    default:
      for (int k = 0; k < 8; ++k) {
        add(Vec3((k & 1 ? c.local_max : c.local_min).x(), (k & 2 ? c.local_max : c.local_min).y(),
                 (k & 4 ? c.local_max : c.local_min).z()),
            0);
      }
      break;
  }
  return b;
}

// An error of a child's own definition, its field prefixed with the child's place.
Error child_error(std::size_t k, const Error& e) {
  const std::string what = e.what();
  const std::string message = e.field().empty() ? what : what.substr(e.field().size() + 2);
  return Error("shape.children[" + std::to_string(k) + "]." + e.field(), message);
}

// Exact mass properties of the union of the children (assumed not to overlap): volumes add, the
// centre of mass is the volume-weighted mean, and each child's inertia, rotated into the compound
// frame (R I R^T), moves to the common centre by the parallel-axis theorem
// I += V (|d|^2 Id - d d^T); all in double. The principal axes of the sum give the frame.
void make_compound(Shape& s, const ShapeDef& def) {
  const std::size_t n = def.children.size();
  if (n == 0) throw Error("shape.children", "must have at least one child");
  if (n > std::size_t(UINT32_MAX)) throw Error("shape.children", "too many children");
  std::vector<Shape> shapes(n);
  std::vector<Vec3d> centre(n);  // child principal frame in the compound's shape frame
  std::vector<Eigen::Quaterniond> rot(n);
  for (std::size_t k = 0; k < n; ++k) {
    const CompoundChild& c = def.children[k];
    const std::string at = "shape.children[" + std::to_string(k) + "]";
    const ShapeType t = c.shape.type;
    if (t == ShapeType::Plane || t == ShapeType::Mesh || t == ShapeType::Heightfield ||
        t == ShapeType::Compound) {
      throw Error(at + ".shape.type",
                  "a compound's child must be convex (not a plane, mesh, heightfield or compound)");
    }
    if (!c.position.allFinite()) throw Error(at + ".position", "must be finite");
    check_coordinates(c.position, limits::kMaxPosition, (at + ".position").c_str(), "m");
    if (!c.orientation.coeffs().allFinite()) throw Error(at + ".orientation", "must be finite");
    if (!(c.orientation.norm() > Real(1e-12))) throw Error(at + ".orientation", "zero quaternion");
    try {
      shapes[k] = make_shape(c.shape);
    } catch (const Error& e) {
      throw child_error(k, e);
    }
    const Eigen::Quaterniond q = c.orientation.cast<double>().normalized();
    centre[k] = c.position.cast<double>() + q * shapes[k].frame_position.cast<double>();
    rot[k] = (q * shapes[k].frame_rotation.cast<double>()).normalized();
  }
  double volume = 0;
  Vec3d com = Vec3d::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    volume += double(shapes[k].volume);
    com += double(shapes[k].volume) * centre[k];
  }
  com /= volume;
  Mat3d inertia = Mat3d::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    const double v = shapes[k].volume;
    const Mat3d r = rot[k].toRotationMatrix();
    const Vec3d d = centre[k] - com;
    inertia += r * (v * shapes[k].unit_inertia.cast<double>()).asDiagonal() * r.transpose();
    inertia += v * (d.squaredNorm() * Mat3d::Identity() - d * d.transpose());
  }
  Vec3d moments;
  const Mat3d axes = principal_axes(inertia, moments);
  s.volume = Real(volume);
  s.unit_inertia = (moments / volume).cast<Real>();
  s.frame_position = com.cast<Real>();
  s.frame_rotation = Quat(axes.cast<Real>()).normalized();

  // The parts in the compound's principal frame: x_principal = A^T (x_shape - com).
  const Eigen::Quaterniond to_principal(axes.transpose());
  std::vector<CompoundPart> parts(n);
  std::vector<Aabb> boxes(n);
  for (std::size_t k = 0; k < n; ++k) {
    CompoundPart& p = parts[k];
    p.pose.position = (axes.transpose() * (centre[k] - com)).cast<Real>();
    p.pose.rotation = (to_principal * rot[k]).normalized().cast<Real>();
    p.box = part_box(shapes[k], p.pose);
    p.shape = std::move(shapes[k]);
    boxes[k] = p.box;
  }
  auto compound = std::make_shared<Compound>();
  std::vector<uint32_t> order(n);
  for (uint32_t k = 0; k < n; ++k) order[k] = k;
  if (n >= kCompoundTreeMin) compound->tree = build_bvh(boxes, 2, order);
  compound->parts.reserve(n);
  compound->child_of = order;
  for (uint32_t k = 0; k < n; ++k) compound->parts.push_back(std::move(parts[order[k]]));
  s.local_min = Vec3::Constant(std::numeric_limits<Real>::max());
  s.local_max = -s.local_min;
  for (const CompoundPart& p : compound->parts) {
    s.local_min = s.local_min.cwiseMin(p.box.min);
    s.local_max = s.local_max.cwiseMax(p.box.max);
    s.bounding_radius =
        std::max(s.bounding_radius, p.pose.position.norm() + p.shape.bounding_radius);
  }
  describe_parts(*compound);
  s.compound = std::move(compound);
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
    case ShapeType::Mesh:
      make_mesh(s, def);
      break;
    case ShapeType::Heightfield:
      make_heightfield(s, def);
      break;
    case ShapeType::Compound:
      make_compound(s, def);
      break;
    default:
      throw Error("shape.type", "unknown shape type");
  }
  return s;
}

namespace {

Vec3 support_of(const Shape& shape, const Vec3& d) {
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

}  // namespace

Xyz support_xyz(const Shape& shape, Real dx, Real dy, Real dz) {
  const Vec3 s = support_of(shape, Vec3(dx, dy, dz));
  return {s.x(), s.y(), s.z()};
}

}  // namespace elan::detail
