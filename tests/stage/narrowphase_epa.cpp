// SPDX-License-Identifier: MIT
// EPA penetration depth, normal and witness points against closed forms and an exact SAT oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "narrowphase/gjk.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase_oracle.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_epa_test {

using test::at;
using test::axis_angle;
using test::box;
using test::capsule;
using test::cylinder;
using test::sphere;

// EPA stops at a relative gap of 1e-5 (float); boxes and cores are polytopes, so the answer is
// exact up to rounding.
constexpr double kTol = sizeof(Real) == 4 ? 1e-4 : 1e-8;

void expect_finite_unit(const EpaResult& e) {
  EXPECT_TRUE(std::isfinite(e.depth));
  EXPECT_TRUE(e.point_a.allFinite());
  EXPECT_TRUE(e.point_b.allFinite());
  EXPECT_NEAR(e.normal.norm(), 1, 1e-5);
}

TEST(Epa, OverlappingSpheresMatchClosedForm) {
  const Shape a = sphere(0.5), b = sphere(0.7);
  const Vec3 d = Vec3(0.3, 0.6, -0.2);
  const EpaResult e = epa_penetration(a, at(1, 1, 1), b, at(1 + d.x(), 1 + d.y(), 1 + d.z()));
  ASSERT_TRUE(e.ok);
  EXPECT_NEAR(e.depth, 1.2 - d.norm(), kTol);
  EXPECT_TRUE(e.normal.isApprox(d.normalized(), Real(1e-5)));
  EXPECT_TRUE(e.point_a.isApprox(Vec3(1, 1, 1) + Real(0.5) * d.normalized(), Real(1e-5)));
  EXPECT_NEAR((e.point_a - e.point_b).dot(e.normal), e.depth, kTol);
}

TEST(Epa, BoxFaceContactMatchesClosedForm) {
  const Shape a = box(1, 1, 1), b = box(0.5, 2, 1.5);
  // Overlap 0.2 along x is the least; along y and z it is several units.
  const EpaResult e = epa_penetration(a, at(0, 0, 0), b, at(1.3, 0.4, -0.3));
  ASSERT_TRUE(e.ok);
  EXPECT_NEAR(e.depth, 0.2, kTol);
  EXPECT_TRUE(e.normal.isApprox(Vec3::UnitX(), Real(1e-5)));
  EXPECT_NEAR(e.point_a.x(), 1, kTol);
  EXPECT_NEAR(e.point_b.x(), 0.8, kTol);
  // Rotated frame: the same contact seen after turning both bodies.
  const Quat q(Eigen::AngleAxis<Real>(Real(0.7), Vec3(1, 2, -1).normalized()));
  const EpaResult r = epa_penetration(a, at(0, 0, 0, q), b, at(0, 0, 0, q));
  ASSERT_TRUE(r.ok);
  const EpaResult s = epa_penetration(a, at(2, 3, 4, q), b, at(2, 3, 4, q));
  EXPECT_NEAR(r.depth, s.depth, kTol);
  Transform xb = at(0, 0, 0, q);
  xb.position = q * Vec3(1.3, 0.4, -0.3);
  const EpaResult t = epa_penetration(a, at(0, 0, 0, q), b, xb);
  EXPECT_NEAR(t.depth, 0.2, 5 * kTol);
  EXPECT_TRUE(t.normal.isApprox(q * Vec3::UnitX(), Real(1e-4)));
}

TEST(Epa, CapsulesMatchClosedForms) {
  const Shape a = capsule(0.3, 1), b = capsule(0.2, 0.5);
  // Crossing at right angles, axes 0.4 apart along x: depth 0.5 - 0.4.
  const Quat qz(Eigen::AngleAxis<Real>(Real(std::numbers::pi / 2), Vec3::UnitX()));
  EpaResult e = epa_penetration(a, at(0, 0, 0), b, at(0.4, 0.2, 0.1, qz));
  ASSERT_TRUE(e.ok);
  EXPECT_NEAR(e.depth, 0.1, kTol);
  EXPECT_TRUE(e.normal.isApprox(Vec3::UnitX(), Real(1e-5)));
  // Cores crossing (distance 0): depth is the sum of radii, normal along the common perpendicular.
  e = epa_penetration(a, at(0, 0, 0), b, at(0, 0.2, 0, qz));
  ASSERT_TRUE(e.ok);
  EXPECT_NEAR(e.depth, 0.5, kTol);
  EXPECT_NEAR(std::abs(e.normal.x()), 1, 1e-5);
  // A capsule standing in a box near its top: the core must rise 1 - 0.4, plus the radius.
  e = epa_penetration(capsule(0.2, 0.5), at(0, 0.9, 0), box(2, 1, 2), at(0, 0, 0));
  ASSERT_TRUE(e.ok);
  EXPECT_NEAR(e.depth, 0.8, kTol);
  EXPECT_TRUE(e.normal.isApprox(-Vec3::UnitY(), Real(1e-5)));
}

// Random overlapping hulls: EPA's depth equals the exact SAT depth (minimum overlap over face
// normals and edge-pair axes), and its normal is an axis that achieves it.
TEST(Epa, MatchesSatDepthOnRandomHulls) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0;
  for (int i = 0; i < 300 && tested < 150; ++i) {
    const Shape a = oracle::random_hull(rng, 8 + i % 16, 1.0);
    const Shape b = oracle::random_hull(rng, 8 + (i * 5) % 24, 0.8);
    const Transform xa = at(0, 0, 0, oracle::random_rotation(rng));
    const Vec3 offset = test::draw3(rng, u, Real(0.6));
    const Transform xb = test::pose(offset, oracle::random_rotation(rng));
    const oracle::Poly pa = oracle::place_hull(a, xa), pb = oracle::place_hull(b, xb);
    const double depth = oracle::sat_depth(pa, pb);
    if (depth < 1e-3) continue;
    ++tested;
    const EpaResult e = epa_penetration(a, xa, b, xb);
    ASSERT_TRUE(e.ok) << i;
    expect_finite_unit(e);
    EXPECT_NEAR(e.depth, depth, 2e-4 * (1 + depth)) << i;
    // Along e.normal the overlap of the projections is the reported depth.
    const Eigen::Vector3d n = e.normal.cast<double>();
    const auto [alo, ahi] = oracle::project(pa, n);
    const auto [blo, bhi] = oracle::project(pb, n);
    EXPECT_NEAR(ahi - blo, depth, 2e-4 * (1 + depth)) << i;
    (void)alo, (void)bhi;
  }
  EXPECT_GE(tested, 100);
}

TEST(Epa, DegenerateInputsStayFinite) {
  const Shape unit = box(1, 1, 1);
  // Identical boxes at one pose: depth 2 along some face normal.
  EpaResult e = epa_penetration(unit, at(0, 0, 0), unit, at(0, 0, 0));
  ASSERT_TRUE(e.ok);
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 2, kTol * 2);
  // Coincident sphere centres: depth = sum of radii, any unit normal.
  e = epa_penetration(sphere(1), at(1, 2, 3), sphere(0.5), at(1, 2, 3));
  ASSERT_TRUE(e.ok);
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 1.5, kTol);
  // Coincident parallel capsules (flat core difference).
  e = epa_penetration(capsule(0.2, 1), at(0, 0, 0), capsule(0.2, 1), at(0, 0, 0));
  ASSERT_TRUE(e.ok);
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 0.4, kTol);
  EXPECT_NEAR(e.normal.y(), 0, 1e-5);
  // Touching exactly: depth 0 within rounding.
  e = epa_penetration(unit, at(0, 0, 0), unit, at(2, 0.5, 0.5));
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 0, 1e-5);
  // Thin plates (1e-3) overlapping by 5e-4.
  const Shape thin = box(1, Real(1e-3), 1);
  e = epa_penetration(thin, at(0, 0, 0), thin, at(0.2, Real(1.5e-3), 0.1));
  ASSERT_TRUE(e.ok);
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 5e-4, 1e-6);
  EXPECT_NEAR(e.normal.y(), 1, 1e-4);
  // Huge box and tiny sphere sunk 0.005 into its top face.
  e = epa_penetration(sphere(0.01), at(3, Real(1000.005), -7), box(1000, 1000, 1000), at(0, 0, 0));
  ASSERT_TRUE(e.ok);
  expect_finite_unit(e);
  EXPECT_NEAR(e.depth, 0.005, 1e-4);
  EXPECT_NEAR(e.normal.y(), -1, 1e-4);
}

// Support of a cylinder (axis y in its frame) or a capsule (segment along y, swept by its
// radius) placed at x, in double: the brute-force reference below needs no engine code.
double support_along(const Shape& s, const Transform& x, const oracle::V3& n) {
  const Eigen::Matrix3d r = x.rotation.toRotationMatrix().cast<double>();
  const oracle::V3 d = r.transpose() * n;  // n in the shape's frame
  const double h = double(s.half_height), rad = double(s.radius);
  double local;
  if (s.type == ShapeType::Cylinder) {
    local = std::abs(d.y()) * h + rad * std::hypot(d.x(), d.z());
  } else {
    local = std::abs(d.y()) * h + rad * d.norm();
  }
  return local + n.dot(x.position.cast<double>());
}

// The overlap of A and B along unit n: how far B must move along n to leave A.
double overlap_along(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                     const oracle::V3& n) {
  return support_along(a, xa, n) + support_along(b, xb, -n);
}

// Penetration depth by brute force: the least overlap over unit directions, first on a
// golden-angle spiral of 40,000 directions (about 0.018 rad apart), then by a local search whose
// step halves down to 1e-9 rad.
double least_overlap(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  const int n = 40000;
  oracle::V3 best_n(0, 1, 0);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    const double y = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - y * y), t = 2.399963229728653 * i;
    const oracle::V3 d(r * std::cos(t), y, r * std::sin(t));
    const double o = overlap_along(a, xa, b, xb, d);
    if (o < best) best = o, best_n = d;
  }
  for (double step = 0.02; step > 1e-9; step *= 0.5) {
    for (bool moved = true; moved;) {
      moved = false;
      const oracle::V3 u = best_n.unitOrthogonal(), v = best_n.cross(u);
      for (int k = 0; k < 16; ++k) {
        const double ang = 2 * std::numbers::pi * k / 16;
        const oracle::V3 d = (best_n + step * (std::cos(ang) * u + std::sin(ang) * v)).normalized();
        const double o = overlap_along(a, xa, b, xb, d);
        if (o < best) best = o, best_n = d, moved = true;
      }
    }
  }
  return best;
}

// Found by fuzz_narrowphase (tests/fuzz/corpus/narrowphase/regression_epa_infinite_depth): a
// cylinder and a capsule overlapping by about 0.82 m, for which EPA (in clang's build) reported
// ok with an infinite depth: rounding on faces nearly coplanar with a new support point (the
// cylinder's flat cap) gave a wrong horizon, a new face turned inwards, the polytope stopped
// being convex, the face buffer filled, and the answer was read from a reused slot holding a
// sliver (distance kInf). The depth must be finite and correct: within 0.2% of the least overlap
// over all directions (EPA stops at a support gap of 1e-5 relative, or, at an inverted face, at
// the last convex polytope's gap, here 3e-4 relative), and the overlap along EPA's normal is its
// depth.
TEST(Epa, CylinderAgainstCapsuleGivesTheLeastOverlap) {
  const Shape a = cylinder(0x1.ea2fdp-1f, 0x1.d1b286p-1f);
  const Shape b = capsule(0x1.67db4ep-1f, 0x1.5f0bdep+0f);
  const Transform xa = at(0x1.b242p-6f, -0x1.86dc86p+0f, -0x1.39663ap+0f,
                          Quat(0x1.3c494p-3f, -0x1.cb5bccp-1f, -0x1.fe1bfep-1f, -1).normalized());
  const Transform xb = at(-0x1.09db08p-1f, -0x1.beddcp-2f, -0x1.131414p+0f,
                          Quat(0x1.a451ap-4f, -0x1.ed79fp-3f, 0x1.bc1fbcp-1f, -1).normalized());
  const EpaResult e = epa_penetration(a, xa, b, xb);
  ASSERT_TRUE(e.ok);
  expect_finite_unit(e);
  const double ref = least_overlap(a, xa, b, xb);
  const double tol = 2e-3 * ref;
  EXPECT_NEAR(e.depth, ref, tol);
  EXPECT_NEAR(overlap_along(a, xa, b, xb, e.normal.cast<double>()), e.depth, tol);
}

// collide_general's path: its own GJK on the cores, to a contact's precision (stopped early only
// past the reject distance plus the radii, or apart), ended in overlap and handed to EPA, gives
// epa_penetration's answer bit for bit, for overlapping pairs of boxes, cylinders, hulls and
// capsules (a capsule's core: its segment).
TEST(Epa, AfterTheCallersGjkMatchesItsOwnSearch) {
  const Shape shapes[] = {box(Real(0.3), Real(0.2), Real(0.5)), cylinder(Real(0.35), Real(0.3)),
                          test::round_hull(20, Real(0.4)),
                          test::box_hull(Real(0.3), Real(0.3), Real(0.2)),
                          capsule(Real(0.2), Real(0.3))};
  std::mt19937 rng(43);
  std::uniform_real_distribution<float> u(-1, 1);
  int overlapping = 0, rounded = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const Shape& sa = shapes[trial % 5];
    const Shape& sb = shapes[(trial / 5) % 5];
    const Quat qa = test::random_turn(rng, u);
    const Quat qb = test::random_turn(rng, u);
    const Vec3 centre_a{Real(5) + u(rng), Real(0.5) * u(rng), 0};
    const Vec3 centre_b{Real(5) + u(rng), Real(0.5) * u(rng), Real(0.6) * u(rng)};
    const Transform xa = test::pose(centre_a, qa), xb = test::pose(centre_b, qb);
    const PlacedShape pa = place(sa, xa, false), pb = place(sb, xb, false);
    const Real radii = core_radius(sa) + core_radius(sb);
    Simplex s;
    const GjkResult g = gjk_contact(pa, pb, Vec3::Zero(), s, Real(0.05) + radii);
    if (!g.overlap) continue;
    ++overlapping;
    rounded += radii > 0;
    const EpaResult own = epa_penetration(sa, xa, sb, xb);
    const EpaResult after = epa_after_gjk(pa, pb, g, s);
    ASSERT_EQ(after.ok, own.ok) << trial;
    ASSERT_EQ(after.depth, own.depth) << trial;
    ASSERT_EQ(after.normal, own.normal) << trial;
    ASSERT_EQ(after.point_a, own.point_a) << trial;
    ASSERT_EQ(after.point_b, own.point_b) << trial;
  }
  EXPECT_GT(overlapping, 500);
  EXPECT_GT(rounded, 150);
}

}  // namespace narrowphase_epa_test
}  // namespace elan::detail
