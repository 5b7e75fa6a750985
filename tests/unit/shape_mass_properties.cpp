// SPDX-License-Identifier: MIT
// Shape creation: mass properties against hand values and an independent slice-integration oracle,
// hull principal frames against exactly known solids, bounds, and validation of bad definitions.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/base/compound.hpp"
#include "core/base/shape.hpp"
#include "elan/error.hpp"

namespace elan::detail {
namespace shape_mass_properties_test {

constexpr double kPi = std::numbers::pi;

// Closed forms are evaluated in double and rounded once to Real: 1e-6 relative covers that
// rounding (float ulp 6e-8) with margin, yet catches any wrong term (they change values by %).
constexpr double kExact = 1e-6;
// Clouds rotated and shifted in Real carry coordinate rounding of ~1e-7 of their magnitude
// (~10 m here) on a body of ~1 m, i.e. ~1e-6 relative per coordinate, squared in inertias.
constexpr double kRounded = 1e-4;

void expect_rel(double got, double want, double rel, const std::string& what) {
  EXPECT_NEAR(got, want, rel * std::abs(want)) << what;
}

std::array<double, 3> sorted(const Vec3& v) {
  std::array<double, 3> s = {v.x(), v.y(), v.z()};
  std::sort(s.begin(), s.end());
  return s;
}

ShapeDef def_of(ShapeType type) {
  ShapeDef d;
  d.type = type;
  return d;
}

ShapeDef hull_def(std::vector<Vec3> pts) {
  ShapeDef d = def_of(ShapeType::ConvexHull);
  d.points = std::move(pts);
  return d;
}

std::vector<Vec3> box_corners(const Vec3& h) {
  std::vector<Vec3> c;
  for (int i = 0; i < 8; ++i) {
    c.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  }
  return c;
}

// Independent oracle for solids of revolution about Y: integrate disc slices of radius rho(y).
// A disc of area pi rho^2 has axial moment pi rho^4 / 2 and, about a transverse axis through the
// origin, pi rho^4 / 4 + pi rho^2 y^2. On each smooth piece the integrands are polynomials of
// degree <= 4 in y (rho^2 = r^2 - (|y| - h)^2 on a cap), so 5-point Gauss-Legendre is exact.
struct SliceMass {
  double volume, axial, across;  // per unit density
};

template <class Rho2>
SliceMass integrate_slices(const std::vector<double>& breaks, Rho2 rho2) {
  const std::array<double, 5> x = {0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                   0.9061798459386640};
  const std::array<double, 5> w = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                   0.2369268850561891, 0.2369268850561891};
  SliceMass m{0, 0, 0};
  for (size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double a = breaks[k], b = breaks[k + 1], half = (b - a) / 2, mid = (a + b) / 2;
    for (int i = 0; i < 5; ++i) {
      const double y = mid + half * x[i], r2 = rho2(y), wt = w[i] * half;
      m.volume += wt * kPi * r2;
      m.axial += wt * kPi * r2 * r2 / 2;
      m.across += wt * (kPi * r2 * r2 / 4 + kPi * r2 * y * y);
    }
  }
  return m;
}

void expect_matches_slices(const Shape& s, const SliceMass& m, const std::string& what) {
  expect_rel(s.volume, m.volume, kExact, what + " volume");
  expect_rel(s.unit_inertia.y(), m.axial / m.volume, kExact, what + " axial");
  expect_rel(s.unit_inertia.x(), m.across / m.volume, kExact, what + " across x");
  expect_rel(s.unit_inertia.z(), m.across / m.volume, kExact, what + " across z");
  EXPECT_EQ(s.frame_position, Vec3::Zero());
  EXPECT_EQ(s.frame_rotation.coeffs(), Quat::Identity().coeffs());
}

TEST(ShapeMass, SphereMatchesClosedForm) {
  ShapeDef d = def_of(ShapeType::Sphere);
  d.radius = 2;
  const Shape s = make_shape(d);
  expect_rel(s.volume, 32 * kPi / 3, kExact, "volume");
  for (int i = 0; i < 3; ++i) expect_rel(s.unit_inertia[i], 1.6, kExact, "2/5 r^2");
  const double r = 2;
  expect_matches_slices(s, integrate_slices({-r, r}, [&](double y) { return r * r - y * y; }),
                        "sphere");
  EXPECT_EQ(s.local_max, Vec3::Constant(2));
  EXPECT_EQ(s.local_min, Vec3::Constant(-2));
  EXPECT_EQ(s.bounding_radius, 2);
}

TEST(ShapeMass, BoxMatchesClosedForm) {
  ShapeDef d = def_of(ShapeType::Box);
  d.half_extents = Vec3(1, 2, 3);
  const Shape s = make_shape(d);
  // Full sides 2, 4, 6: V = 48, I_x / m = (4^2 + 6^2) / 12 = 13/3, and so on.
  expect_rel(s.volume, 48, kExact, "volume");
  expect_rel(s.unit_inertia.x(), 13.0 / 3, kExact, "Ix");
  expect_rel(s.unit_inertia.y(), 10.0 / 3, kExact, "Iy");
  expect_rel(s.unit_inertia.z(), 5.0 / 3, kExact, "Iz");
  EXPECT_EQ(s.local_max, Vec3(1, 2, 3));
  EXPECT_EQ(s.local_min, Vec3(-1, -2, -3));
  expect_rel(s.bounding_radius, std::sqrt(14.0), kExact, "radius");
}

TEST(ShapeMass, CapsuleMatchesSliceIntegration) {
  for (const auto& [r, h] : {std::pair{0.5, 0.5}, {0.3, 1.7}, {1.2, 0.1}}) {
    ShapeDef d = def_of(ShapeType::Capsule);
    d.radius = Real(r);
    d.half_height = Real(h);
    const Shape s = make_shape(d);
    // Use the Real-rounded sizes the shape actually holds.
    const double rr = s.radius, hh = s.half_height;
    const SliceMass m = integrate_slices({-hh - rr, -hh, hh, hh + rr}, [&](double y) {
      const double t = std::max(std::abs(y) - hh, 0.0);
      return rr * rr - t * t;
    });
    expect_matches_slices(s, m, "capsule r=" + std::to_string(r) + " h=" + std::to_string(h));
    EXPECT_EQ(s.local_max, Vec3(s.radius, s.half_height + s.radius, s.radius));
    EXPECT_EQ(s.local_min, -s.local_max);
    EXPECT_EQ(s.bounding_radius, s.half_height + s.radius);
  }
}

TEST(ShapeMass, CylinderMatchesSliceIntegration) {
  for (const auto& [r, h] : {std::pair{0.5, 0.5}, {0.3, 1.7}, {1.2, 0.1}}) {
    ShapeDef d = def_of(ShapeType::Cylinder);
    d.radius = Real(r);
    d.half_height = Real(h);
    const Shape s = make_shape(d);
    const double rr = s.radius, hh = s.half_height;
    expect_matches_slices(s, integrate_slices({-hh, hh}, [&](double) { return rr * rr; }),
                          "cylinder");
    // Hand value: axis r^2/2, across (3 r^2 + (2h)^2) / 12.
    expect_rel(s.unit_inertia.y(), rr * rr / 2, kExact, "axial");
    expect_rel(s.unit_inertia.x(), (3 * rr * rr + 4 * hh * hh) / 12, kExact, "across");
    EXPECT_EQ(s.local_max, Vec3(s.radius, s.half_height, s.radius));
    expect_rel(s.bounding_radius, std::sqrt(rr * rr + hh * hh), kExact, "radius");
  }
}

TEST(ShapeMass, HullOfBoxCornersEqualsBox) {
  ShapeDef box = def_of(ShapeType::Box);
  box.half_extents = Vec3(0.5f, 1, 1.5f);
  const Shape b = make_shape(box);
  const Shape h = make_shape(hull_def(box_corners(box.half_extents)));
  ASSERT_TRUE(h.hull);
  EXPECT_EQ(h.hull->vertices.size(), 8u);
  EXPECT_EQ(h.hull->faces.size(), 6u);
  EXPECT_EQ(h.hull->edges.size(), 12u);
  expect_rel(h.volume, b.volume, kExact, "volume");
  for (int i = 0; i < 3; ++i) expect_rel(h.unit_inertia[i], b.unit_inertia[i], kExact, "inertia");
  // Already principal: the frame stays the identity and the bounds are the box's.
  EXPECT_EQ(h.frame_position, Vec3::Zero());
  EXPECT_EQ(h.frame_rotation.coeffs(), Quat::Identity().coeffs());
  EXPECT_LT((h.local_max - b.local_max).norm(), 1e-6);
  EXPECT_LT((h.local_min - b.local_min).norm(), 1e-6);
  expect_rel(h.bounding_radius, b.bounding_radius, kExact, "radius");
}

TEST(ShapeMass, HullOfRegularTetrahedronMatchesFormula) {
  // Edge a = 2 sqrt(2): V = a^3 / (6 sqrt 2) = 8/3 and I / m = a^2 / 20 = 0.4 about any axis
  // through the centroid. Shifted off the origin, the centroid must come back as frame_position.
  const Vec3 shift(0.5f, -1, 2);
  std::vector<Vec3> pts = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
  for (Vec3& p : pts) p += shift;
  const Shape s = make_shape(hull_def(pts));
  const double a = 2 * std::sqrt(2.0);
  expect_rel(s.volume, a * a * a / (6 * std::sqrt(2.0)), kExact, "volume");
  for (int i = 0; i < 3; ++i) expect_rel(s.unit_inertia[i], a * a / 20, kExact, "inertia");
  EXPECT_LT((s.frame_position - shift).norm(), 1e-6);
  EXPECT_EQ(s.hull->faces.size(), 4u);
  // Vertices at the circumradius sqrt(3) from the centroid.
  expect_rel(s.bounding_radius, std::sqrt(3.0), kExact, "radius");
}

// Checks that a principal-frame hull maps back onto the user's points through its frame.
void expect_frame_maps_to_input(const Shape& s, const std::vector<Vec3>& pts, double tol) {
  EXPECT_NEAR(s.frame_rotation.norm(), 1, 1e-6);
  EXPECT_NEAR(s.frame_rotation.toRotationMatrix().determinant(), 1, 1e-5);
  for (const Vec3& v : s.hull->vertices) {
    EXPECT_TRUE((v.array() <= s.local_max.array()).all()) << v.transpose();
    EXPECT_TRUE((v.array() >= s.local_min.array()).all()) << v.transpose();
    EXPECT_LE(v.norm(), s.bounding_radius);
    const Vec3 user = s.frame_rotation * v + s.frame_position;
    double best = 1e30;
    for (const Vec3& p : pts) best = std::min(best, double((p - user).norm()));
    EXPECT_LT(best, tol) << user.transpose();
  }
}

TEST(ShapeMass, OffCentreRotatedBoxCloudRecoversCentroidAndPrincipalAxes) {
  const Vec3 half(0.4f, 0.7f, 1.1f), centre(3, -2, 5);
  const Quat q = Quat(Eigen::AngleAxis<Real>(Real(0.9), Vec3(1, -2, 0.5f).normalized()));
  std::vector<Vec3> pts;
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> u(-1, 1);
  for (const Vec3& c : box_corners(half)) {
    pts.push_back(q * c + centre);
    pts.push_back(pts.back());  // duplicate
  }
  for (int i = 0; i < 40; ++i) {
    pts.push_back(q * Vec3{half.cwiseProduct(Vec3{u(rng), u(rng), u(rng)}) * 0.95f} + centre);
  }
  const Shape s = make_shape(hull_def(pts));
  EXPECT_EQ(s.hull->vertices.size(), 8u);
  EXPECT_EQ(s.hull->faces.size(), 6u);
  EXPECT_LT((s.frame_position - centre).norm(), kRounded);
  expect_rel(s.volume, 8 * double(half.prod()), kRounded, "volume");
  const Vec3 h2 = half.cwiseProduct(half);
  const Vec3 box_moments = Vec3(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y()) / 3;
  const auto got = sorted(s.unit_inertia), want = sorted(box_moments);
  for (int i = 0; i < 3; ++i) expect_rel(got[i], want[i], kRounded, "moment");
  // The principal axes are the box's axes: frame^-1 * q is a signed permutation, and the hull
  // in the principal frame is the axis-aligned box.
  const Mat3 m = (s.frame_rotation.conjugate() * q).toRotationMatrix();
  for (int i = 0; i < 9; ++i) {
    const double a = std::abs(m.data()[i]);
    EXPECT_LT(std::min(a, std::abs(a - 1)), kRounded) << m;
  }
  const auto ext = sorted(s.local_max), hs = sorted(half);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(ext[i], hs[i], kRounded);
  EXPECT_LT((s.local_max + s.local_min).norm(), kRounded);
  expect_frame_maps_to_input(s, pts, kRounded);
}

TEST(ShapeMass, HullOfParallelepipedMatchesAffineImageOfCube) {
  // The image A [-1, 1]^3 + t of the cube has V = 8 |det A| and centroidal covariance
  // C = |det A| (8/3) A A^T, so I = tr(C) Id - C: an exact oracle with sheared, non-rectangular
  // faces, independent of the builder's tetrahedral sums.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::Matrix3d a;
    for (int i = 0; i < 9; ++i) a.data()[i] = u(rng);
    a += 1.5 * Eigen::Matrix3d::Identity();
    const Eigen::Vector3d t{u(rng) * 4, u(rng) * 4, u(rng) * 4};
    std::vector<Vec3> pts;
    for (const Vec3& c : box_corners(Vec3::Ones())) {
      pts.push_back((a * c.cast<double>() + t).cast<Real>());
    }
    const Shape s = make_shape(hull_def(pts));
    EXPECT_EQ(s.hull->faces.size(), 6u);
    const double det = std::abs(a.determinant());
    const Eigen::Matrix3d c = det * 8.0 / 3.0 * a * a.transpose();
    const Eigen::Matrix3d inertia = c.trace() * Eigen::Matrix3d::Identity() - c;
    const Eigen::Vector3d want =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues() / (8 * det);
    expect_rel(s.volume, 8 * det, kRounded, "volume");
    const auto got = sorted(s.unit_inertia);
    for (int i = 0; i < 3; ++i) expect_rel(got[i], want[i], kRounded, "moment");
    EXPECT_LT((s.frame_position.cast<double>() - t).norm(), kRounded * 4);
    expect_frame_maps_to_input(s, pts, kRounded * 4);
  }
}

TEST(ShapeMass, HullMassIsInvariantUnderRigidMotion) {
  std::mt19937 rng(5);
  std::normal_distribution<Real> g(0, 1);
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<Vec3> pts, moved;
    for (int i = 0; i < 30; ++i) pts.push_back(Vec3{g(rng), g(rng) * 0.5f, g(rng) * 2});
    const Quat q = Quat{Eigen::AngleAxis<Real>(g(rng), Vec3{g(rng), g(rng), g(rng)}.normalized())};
    const Vec3 t{g(rng), g(rng), g(rng)};
    for (const Vec3& p : pts) moved.push_back(q * p + t);
    const Shape a = make_shape(hull_def(pts));
    const Shape b = make_shape(hull_def(moved));
    expect_rel(b.volume, a.volume, kRounded, "volume");
    const auto ma = sorted(a.unit_inertia), mb = sorted(b.unit_inertia);
    for (int i = 0; i < 3; ++i) expect_rel(mb[i], ma[i], kRounded, "moment");
    EXPECT_LT((b.frame_position - (q * a.frame_position + t)).norm(), kRounded * 10);
    expect_frame_maps_to_input(a, pts, kRounded);
    expect_frame_maps_to_input(b, moved, kRounded * 10);
  }
}

TEST(ShapeMass, PlaneIsNormalisedAndMassless) {
  ShapeDef d = def_of(ShapeType::Plane);
  d.normal = Vec3(0, 3, 4);
  d.offset = 2;
  const Shape s = make_shape(d);
  EXPECT_LT((s.plane_normal - Vec3(0, 0.6f, 0.8f)).norm(), 1e-6);
  EXPECT_EQ(s.plane_offset, 2);
  EXPECT_EQ(s.volume, 0);
}

void expect_field(const ShapeDef& d, const std::string& field) {
  try {
    make_shape(d);
    ADD_FAILURE() << "no error, expected " << field;
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), field) << e.what();
  }
}

TEST(ShapeValidation, BadSizesThrowNamingTheField) {
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Real inf = std::numeric_limits<Real>::infinity();
  for (const Real bad : {Real(0), Real(-1), nan, inf}) {
    for (ShapeType t : {ShapeType::Sphere, ShapeType::Capsule, ShapeType::Cylinder}) {
      ShapeDef d = def_of(t);
      d.radius = bad;
      expect_field(d, "shape.radius");
    }
    for (ShapeType t : {ShapeType::Capsule, ShapeType::Cylinder}) {
      ShapeDef d = def_of(t);
      d.half_height = bad;
      expect_field(d, "shape.half_height");
    }
    for (int axis = 0; axis < 3; ++axis) {
      ShapeDef d = def_of(ShapeType::Box);
      d.half_extents[axis] = bad;
      expect_field(d, "shape.half_extents");
    }
  }
  ShapeDef plane = def_of(ShapeType::Plane);
  plane.normal = Vec3::Zero();
  expect_field(plane, "shape.normal");
  plane.normal = Vec3(0, nan, 1);
  expect_field(plane, "shape.normal");
  plane.normal = Vec3(0, 1, 0);
  plane.offset = inf;
  expect_field(plane, "shape.offset");
  expect_field(hull_def({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}), "shape.points");
  expect_field(hull_def(std::vector<Vec3>(6, Vec3(1, 1, 1))), "shape.points");
}

// --- compounds, meshes, heightfields --------------------------------------------------------

ShapeDef box_def(const Vec3& h) {
  ShapeDef d = def_of(ShapeType::Box);
  d.half_extents = h;
  return d;
}

CompoundChild child(const ShapeDef& shape, const Vec3& position, const Quat& orientation) {
  CompoundChild c;
  c.shape = shape;
  c.position = position;
  c.orientation = orientation;
  return c;
}

// The inertia tensor per unit density in the shape frame, from the principal frame and moments:
// V R diag(unit_inertia) R^T.
Eigen::Matrix3d tensor_of(const Shape& s) {
  const Eigen::Matrix3d r = s.frame_rotation.toRotationMatrix().cast<double>();
  return double(s.volume) * r * s.unit_inertia.cast<double>().asDiagonal() * r.transpose();
}

void expect_matrix(const Eigen::Matrix3d& got, const Eigen::Matrix3d& want, double tol,
                   const std::string& what) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(got(i, j), want(i, j), tol) << what << " (" << i << ", " << j << ")";
    }
  }
}

TEST(ShapeMass, CompoundLOfTwoBoxesMatchesTheHandComputedTensor) {
  // Box A: half extents (1, 0.5, 0.5) at the origin. Box B: the same box turned 90 degrees about
  // z (so half extents (0.5, 1, 0.5)) at (0.5, 1.5, 0): an L in the xy plane.
  ShapeDef l = def_of(ShapeType::Compound);
  const Quat quarter(Eigen::AngleAxis<Real>(Real(kPi / 2), Vec3::UnitZ()));
  l.children = {child(box_def(Vec3(1, 0.5f, 0.5f)), Vec3::Zero(), Quat::Identity()),
                child(box_def(Vec3(1, 0.5f, 0.5f)), Vec3(0.5f, 1.5f, 0), quarter)};
  const Shape s = make_shape(l);
  // Each volume 8 * 1 * 0.5 * 0.5 = 2; the centre of mass is the mean (0.25, 0.75, 0).
  expect_rel(s.volume, 4, kExact, "volume");
  EXPECT_NEAR(s.frame_position.x(), 0.25, 1e-6);
  EXPECT_NEAR(s.frame_position.y(), 0.75, 1e-6);
  EXPECT_NEAR(s.frame_position.z(), 0, 1e-6);
  // Own moments V (b^2 + c^2) / 3: A (1/3, 5/6, 5/6), B (5/6, 1/3, 5/6). Offsets from the centre
  // d = -+(0.25, 0.75, 0), |d|^2 = 0.625; V (|d|^2 Id - d d^T) per box: xx 2 (0.625 - 0.0625) =
  // 1.125, yy 2 (0.625 - 0.5625) = 0.125, zz 1.25, xy -2 (0.25 * 0.75) = -0.375.
  Eigen::Matrix3d want = Eigen::Matrix3d::Zero();
  want(0, 0) = 1.0 / 3 + 5.0 / 6 + 2 * 1.125;
  want(1, 1) = 5.0 / 6 + 1.0 / 3 + 2 * 0.125;
  want(2, 2) = 5.0 / 6 + 5.0 / 6 + 2 * 1.25;
  want(0, 1) = want(1, 0) = 2 * -0.375;
  // Float moments of O(4) after a rotation: a few ulps of 4.
  expect_matrix(tensor_of(s), want, 1e-5, "L inertia");
  // The parts put back in the shape frame are the boxes where they were given.
  const Compound& c = *s.compound;
  ASSERT_EQ(c.parts.size(), 2u);
  EXPECT_EQ(c.child_of, (std::vector<uint32_t>{0, 1}));
  const Vec3 b_centre = s.frame_rotation * c.parts[1].pose.position + s.frame_position;
  EXPECT_LT((b_centre - Vec3(0.5f, 1.5f, 0)).norm(), 1e-5);
  // Bounds: the union of the two boxes, x in [-1, 1], y in [-0.5, 2.5], in the principal frame;
  // every corner of both boxes lies inside them.
  for (const Vec3& corner :
       {Vec3(-1, -0.5f, -0.5f), Vec3(1, 0.5f, 0.5f), Vec3(0, 2.5f, 0.5f), Vec3(1, 2.5f, -0.5f)}) {
    const Vec3 p = s.frame_rotation.conjugate() * (corner - s.frame_position);
    EXPECT_TRUE((p.array() >= s.local_min.array() - 1e-5f).all() &&
                (p.array() <= s.local_max.array() + 1e-5f).all())
        << corner.transpose();
  }
}

TEST(ShapeMass, CompoundOfOneChildEqualsTheChild) {
  // A box at the origin: the same shape exactly.
  ShapeDef one = def_of(ShapeType::Compound);
  const ShapeDef box = box_def(Vec3(0.3f, 0.7f, 1.1f));
  one.children = {child(box, Vec3::Zero(), Quat::Identity())};
  const Shape c = make_shape(one), b = make_shape(box);
  EXPECT_EQ(c.volume, b.volume);
  EXPECT_EQ(c.unit_inertia, b.unit_inertia);
  EXPECT_EQ(c.frame_position, Vec3::Zero());
  EXPECT_EQ(c.frame_rotation.coeffs(), Quat::Identity().coeffs());
  EXPECT_EQ(c.local_min, b.local_min);
  EXPECT_EQ(c.local_max, b.local_max);
  EXPECT_EQ(c.bounding_radius, b.bounding_radius);

  // An off-centre hull, placed at an offset and turned: the compound's centre is the hull's
  // centroid placed, its tensor the hull's turned, its principal moments the hull's.
  const ShapeDef hull = hull_def({Vec3(0.2f, 0, 0), Vec3(1.4f, 0.1f, 0), Vec3(0.3f, 0.9f, 0),
                                  Vec3(0.4f, 0.2f, 0.7f), Vec3(1.1f, 0.8f, 0.6f)});
  const Vec3 at(3, -1, 2);
  const Quat q = Quat(Eigen::AngleAxis<Real>(Real(0.7), Vec3(1, 2, 3).normalized())).normalized();
  one.children = {child(hull, at, q)};
  const Shape hc = make_shape(one), h = make_shape(hull);
  expect_rel(hc.volume, h.volume, kExact, "volume");
  EXPECT_LT((hc.frame_position - (at + q * h.frame_position)).norm(), 1e-5);
  const Eigen::Matrix3d qr = q.toRotationMatrix().cast<double>();
  expect_matrix(tensor_of(hc), qr * tensor_of(h) * qr.transpose(), 1e-6 * tensor_of(h).norm(),
                "hull tensor");
  const auto want = sorted(h.unit_inertia), got = sorted(hc.unit_inertia);
  for (int i = 0; i < 3; ++i) expect_rel(got[i], want[i], 1e-5, "moment");
  // The part put back in the shape frame is the hull placed: each vertex lands where the child
  // definition puts it.
  const CompoundPart& p = hc.compound->parts[0];
  for (const Vec3& v : h.hull->vertices) {
    const Vec3 in_child = h.frame_rotation * v + h.frame_position;
    const Vec3 want_v = at + q * in_child;
    const Vec3 got_v = hc.frame_rotation * p.pose.apply(v) + hc.frame_position;
    EXPECT_LT((got_v - want_v).norm(), 1e-5) << v.transpose();
    const Vec3 local = p.pose.apply(v);
    EXPECT_TRUE((local.array() >= p.box.min.array()).all() &&
                (local.array() <= p.box.max.array()).all());
  }
  EXPECT_NEAR(hc.bounding_radius, h.bounding_radius, 1e-5);  // the part sits at the centre
}

TEST(ShapeMass, CompoundOfTwoEqualSpheres) {
  const double r = 0.5, a = 2;
  ShapeDef sphere = def_of(ShapeType::Sphere);
  sphere.radius = Real(r);
  ShapeDef two = def_of(ShapeType::Compound);
  two.children = {child(sphere, Vec3(Real(-a), 0, 0), Quat::Identity()),
                  child(sphere, Vec3(Real(a), 0, 0), Quat::Identity())};
  const Shape s = make_shape(two);
  const double v1 = 4.0 / 3.0 * kPi * r * r * r;
  expect_rel(s.volume, 2 * v1, kExact, "volume");
  EXPECT_EQ(s.frame_position, Vec3::Zero());
  // Along the line of centres each sphere's own 2/5 r^2; across it, plus a^2.
  expect_rel(s.unit_inertia.x(), 0.4 * r * r, kExact, "along");
  expect_rel(s.unit_inertia.y(), 0.4 * r * r + a * a, kExact, "across y");
  expect_rel(s.unit_inertia.z(), 0.4 * r * r + a * a, kExact, "across z");
  EXPECT_NEAR(s.bounding_radius, a + r, 1e-6);
  EXPECT_NEAR(s.local_min.x(), -(a + r), 1e-6);
  EXPECT_NEAR(s.local_max.x(), a + r, 1e-6);
  EXPECT_NEAR(s.local_max.y(), r, 1e-6);
}

TEST(ShapeMass, CompoundOfManyChildrenHasATreeOverItsParts) {
  ShapeDef many = def_of(ShapeType::Compound);
  ShapeDef sphere = def_of(ShapeType::Sphere);
  sphere.radius = 0.3f;
  for (int k = 0; k < 20; ++k) {
    many.children.push_back(
        child(sphere, Vec3(Real(k % 5), Real(k / 5), Real((k * 7) % 3)), Quat::Identity()));
  }
  const Shape s = make_shape(many);
  const Compound& c = *s.compound;
  ASSERT_FALSE(c.tree.nodes.empty());
  std::vector<uint32_t> sorted_children = c.child_of;
  std::sort(sorted_children.begin(), sorted_children.end());
  for (uint32_t k = 0; k < 20; ++k) EXPECT_EQ(sorted_children[k], k);
  // Each part is its child: placed where the definition put it.
  for (uint32_t k = 0; k < 20; ++k) {
    const Vec3 world = s.frame_rotation * c.parts[k].pose.position + s.frame_position;
    EXPECT_LT((world - many.children[c.child_of[k]].position).norm(), 1e-5);
  }
  // A box query finds exactly the parts whose boxes overlap it.
  const Vec3 lo = s.frame_rotation.conjugate() * (Vec3(0.9f, 0.9f, -1) - s.frame_position);
  const Vec3 hi = s.frame_rotation.conjugate() * (Vec3(2.1f, 2.1f, 3) - s.frame_position);
  const Vec3 qlo = lo.cwiseMin(hi), qhi = lo.cwiseMax(hi);
  std::vector<uint32_t> found, expected;
  for_each_part(c, qlo, qhi, [&](uint32_t k, const CompoundPart&) { found.push_back(k); });
  for (uint32_t k = 0; k < 20; ++k) {
    const Aabb& b = c.parts[k].box;
    if (!((b.min.array() > qhi.array()).any() || (b.max.array() < qlo.array()).any())) {
      expected.push_back(k);
    }
  }
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, expected);
  EXPECT_FALSE(expected.empty());
}

TEST(ShapeMass, MeshAndHeightfieldAreStaticSurfacesInTheirOwnFrame) {
  ShapeDef mesh = def_of(ShapeType::Mesh);
  mesh.vertices = {Vec3(-1, 0, -2), Vec3(3, 0, -2), Vec3(-1, 1, 4)};
  mesh.triangles = {{0, 1, 2}};
  const Shape m = make_shape(mesh);
  EXPECT_EQ(m.volume, 0);
  EXPECT_EQ(m.unit_inertia, Vec3::Zero());
  EXPECT_EQ(m.frame_position, Vec3::Zero());
  EXPECT_EQ(m.local_min, Vec3(-1, 0, -2));
  EXPECT_EQ(m.local_max, Vec3(3, 1, 4));
  EXPECT_NEAR(m.bounding_radius, std::sqrt(9.0 + 1 + 16), 1e-5);
  ASSERT_TRUE(m.mesh);

  ShapeDef field = def_of(ShapeType::Heightfield);
  field.heights = {0, 1, -2, 0.5f, 0.25f, 3};
  field.columns = 3;
  field.spacing_x = 2;
  field.spacing_z = 0.5f;
  const Shape f = make_shape(field);
  EXPECT_EQ(f.volume, 0);
  EXPECT_EQ(f.local_min, Vec3(0, -2, 0));
  EXPECT_EQ(f.local_max, Vec3(4, 3, 0.5f));
  EXPECT_NEAR(f.bounding_radius, std::sqrt(16 + 9 + 0.25), 1e-5);
  ASSERT_TRUE(f.heightfield);
}

TEST(ShapeValidation, CompoundErrorsNameTheChild) {
  ShapeDef c = def_of(ShapeType::Compound);
  expect_field(c, "shape.children");
  ShapeDef sphere = def_of(ShapeType::Sphere);
  c.children = {child(sphere, Vec3::Zero(), Quat::Identity()),
                child(sphere, Vec3(1, 0, 0), Quat::Identity()),
                child(sphere, Vec3(2, 0, 0), Quat::Identity())};
  for (ShapeType t :
       {ShapeType::Plane, ShapeType::Mesh, ShapeType::Heightfield, ShapeType::Compound}) {
    ShapeDef bad = c;
    bad.children[1].shape.type = t;
    expect_field(bad, "shape.children[1].shape.type");
  }
  ShapeDef bad = c;
  bad.children[2].shape.radius = -1;
  expect_field(bad, "shape.children[2].shape.radius");
  try {
    make_shape(bad);
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("shape.children[2].shape.radius: must be", 0), 0u)
        << e.what();
  }
  bad = c;
  bad.children[0].position.y() = std::numeric_limits<Real>::infinity();
  expect_field(bad, "shape.children[0].position");
  bad = c;
  bad.children[0].position.y() = 1e6f;
  expect_field(bad, "shape.children[0].position");
  bad = c;
  bad.children[2].orientation = Quat(0, 0, 0, 0);
  expect_field(bad, "shape.children[2].orientation");
  bad = c;
  bad.children[2].orientation.x() = std::numeric_limits<Real>::quiet_NaN();
  expect_field(bad, "shape.children[2].orientation");
  bad = c;
  bad.children[1].shape = hull_def(std::vector<Vec3>(6, Vec3(1, 1, 1)));
  expect_field(bad, "shape.children[1].shape.points");
}

}  // namespace shape_mass_properties_test
}  // namespace elan::detail
