// SPDX-License-Identifier: MIT
// Time of impact (conservative advancement) against the analytic contact time, and against a
// surface the distance sampled along the path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "core/base/fixed_math.hpp"
#include "core/base/fixed_slerp.hpp"
#include "core/base/heightfield.hpp"
#include "narrowphase/collide.hpp"
#include "narrowphase/gjk.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_toi_test {

Shape make(ShapeType type, Real r, Vec3 he = Vec3::Zero()) {
  ShapeDef d;
  d.type = type;
  d.radius = r;
  d.half_extents = he;
  return make_shape(d);
}

Transform at(Real x, Real y, Real z, Quat q = Quat::Identity()) {
  Transform t;
  t.position = Vec3(x, y, z);
  t.rotation = q;
  return t;
}

// The stopping rule: distance within [target, target + max(target / 4, 1e-4 * size)].
Real allowance(Real target, Real size) {
  return std::max(target / 4, Real(1e-4) * size);
}

TEST(TimeOfImpact, SphereAtThinBoxMatchesAnalyticTime) {
  const Shape ball = make(ShapeType::Sphere, Real(0.1));
  const Shape plate = make(ShapeType::Box, 0, Vec3(1, Real(0.005), 1));
  const Real target = Real(0.01);
  // The ball crosses the 1 cm plate from y = 2 to y = -2 in one step: it would tunnel.
  const Real t = time_of_impact(ball, at(0.1, 2, 0.2), at(0.1, -2, 0.2), plate, at(0, 0, 0),
                                at(0, 0, 0), target);
  // Centre height at contact: half thickness + radius + target.
  const Real exact = (2 - (Real(0.005) + Real(0.1) + target)) / 4;
  EXPECT_LE(t, exact + Real(1e-6));
  EXPECT_GE(t, exact - allowance(target, plate.bounding_radius) / 4 - Real(1e-6));
  // Both moving: the same relative motion gives the same time.
  const Real t2 = time_of_impact(ball, at(0.1, 2, 0.2), at(0.1, 0, 0.2), plate, at(0, 0, 0),
                                 at(0, 2, 0), target);
  EXPECT_NEAR(t2, t, 1e-4);
}

TEST(TimeOfImpact, MissAndSeparatingReturnOne) {
  const Shape ball = make(ShapeType::Sphere, Real(0.1));
  const Shape plate = make(ShapeType::Box, 0, Vec3(1, Real(0.005), 1));
  EXPECT_EQ(
      time_of_impact(ball, at(3, 2, 0), at(3, -2, 0), plate, at(0, 0, 0), at(0, 0, 0), Real(0.01)),
      1);
  EXPECT_EQ(
      time_of_impact(ball, at(0, 1, 0), at(0, 3, 0), plate, at(0, 0, 0), at(0, 0, 0), Real(0.01)),
      1);
}

// A spinning bar sweeps into a resting ball: the distance at the returned time is at the target
// (no overshoot from the rotation bound), and the bar does reach the ball within the step.
TEST(TimeOfImpact, RotationIsBoundedWithoutOvershoot) {
  const Shape ball = make(ShapeType::Sphere, Real(0.1));
  const Shape bar = make(ShapeType::Box, 0, Vec3(1, Real(0.05), Real(0.05)));
  const Transform xb0 = at(0, 0, 0);
  const Transform xb1 = at(0, 0, 0, Quat(Eigen::AngleAxis<Real>(Real(1.2), Vec3::UnitZ())));
  const Transform xs = at(Real(0.4), Real(0.6), 0);
  const Real target = Real(0.01);
  const Real t = time_of_impact(ball, xs, xs, bar, xb0, xb1, target);
  ASSERT_LT(t, 1);
  Transform xb;
  xb.rotation = fixed_slerp(xb0.rotation, t, xb1.rotation);
  const GjkResult g = gjk_distance(ball, xs, bar, xb);
  EXPECT_GE(g.distance, target - Real(1e-5));
  EXPECT_LE(g.distance, target + allowance(target, bar.bounding_radius) + Real(1e-5));
  // Analytic: the bar's top face (y = 0.05 in its frame) meets the ball's bottom when the
  // ball centre is 0.05 + 0.1 + target above the rotating face line: atan2 geometry.
  const Real rho = std::hypot(Real(0.4), Real(0.6));
  const Real angle = std::atan2(Real(0.6), Real(0.4)) - std::asin((Real(0.16)) / rho);
  EXPECT_NEAR(t * Real(1.2), angle, 0.01);
}

// Conservative advancement with the whole distance at every step (the time of impact before its
// GJK learned to stop on the sweep bound): the reference the fast search must match bit for bit.
Real reference_time_of_impact(const Shape& a, const Transform& xa0, const Transform& xa1,
                              const Shape& b, const Transform& xb0, const Transform& xb1,
                              Real target) {
  const Real tolerance =
      std::max(Real(0.25) * target, Real(1e-4) * std::max(a.bounding_radius, b.bounding_radius));
  const Vec3 delta = (xa1.position - xa0.position) - (xb1.position - xb0.position);
  const auto angle = [](const Quat& q0, const Quat& q1) {
    return 2 * Real(fixed_acos(std::min(std::abs(q0.dot(q1)), Real(1))));
  };
  const Real spin = angle(xa0.rotation, xa1.rotation) * a.bounding_radius +
                    angle(xb0.rotation, xb1.rotation) * b.bounding_radius;
  const auto pose = [](const Transform& x0, const Transform& x1, Real t) {
    Transform x;
    x.position = x0.position + t * (x1.position - x0.position);
    x.rotation = fixed_slerp(x0.rotation, t, x1.rotation);
    return x;
  };
  Vec3 dir = xb0.position - xa0.position;
  Real t = 0;
  for (int iter = 0; iter < 64; ++iter) {
    const GjkResult g = gjk_distance(a, pose(xa0, xa1, t), b, pose(xb0, xb1, t), true, &dir);
    if (g.overlap || g.distance <= target + tolerance) return t;
    const Vec3 n = (g.point_b - g.point_a) / g.distance;
    const Real speed = delta.dot(n) + spin;
    if (!(speed > 0)) return 1;
    t += (g.distance - target) / speed;
    if (t >= 1) return 1;
    dir = n;
  }
  return t;
}

// Random fast convex bodies passing, grazing and hitting a slow one, turning as they go: the time
// of impact is the full advancement's, bit for bit (the sweep bound only spares distances whose
// answer is no impact).
TEST(TimeOfImpact, ConvexMatchesTheFullAdvancement) {
  std::vector<Shape> shapes;
  shapes.push_back(make(ShapeType::Sphere, Real(0.3)));
  shapes.push_back(make(ShapeType::Box, 0, Vec3(Real(0.35), Real(0.2), Real(0.4))));
  shapes.push_back(test::capsule(Real(0.25), Real(0.3)));
  shapes.push_back(test::cylinder(Real(0.35), Real(0.3)));
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> u(-1, 1);
  const auto turn = [&] { return test::random_turn(rng, u); };
  int hits = 0, misses = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Shape& sa = shapes[std::size_t(trial) % shapes.size()];
    const Shape& sb = shapes[std::size_t(trial / 4) % shapes.size()];
    const Vec3 start{Real(2) * u(rng), Real(1.5) + u(rng), Real(2) * u(rng)};
    const Vec3 end = start + Vec3{u(rng), Real(-2) + u(rng), u(rng)};
    const Quat q0 = turn();
    const Quat q1 = (Quat(Eigen::AngleAxis<Real>(Real(0.5) * u(rng), Vec3::UnitX())) * q0);
    const Transform xa0 = at(start.x(), start.y(), start.z(), q0);
    const Transform xa1 = at(end.x(), end.y(), end.z(), q1.normalized());
    const Vec3 pb{Real(0.2) * u(rng), 0, Real(0.2) * u(rng)};
    const Transform xb = test::pose(pb, turn());
    const Real t = time_of_impact(sa, xa0, xa1, sb, xb, xb, Real(0.005));
    const Real ref = reference_time_of_impact(sa, xa0, xa1, sb, xb, xb, Real(0.005));
    ASSERT_EQ(t, ref) << trial;
    (t < 1 ? hits : misses) += 1;
  }
  EXPECT_GT(hits, 300);
  EXPECT_GT(misses, 300);
}

// Oracle: the distance to every triangle, sampled along the path. Bodies of each shape pass
// through, by and over a bumpy heightfield, turning as they go: before the returned time no
// triangle facing the body (a heightfield's are one-sided) is nearer than the target, and at a
// time below 1 one is within the stopping rule's allowance. A triangle the walk skipped that the
// path meets first would show nearer than the target at a sample before the returned time.
TEST(TimeOfImpact, SurfaceImpactIsTheEarliestOverItsTriangles) {
  constexpr uint32_t kColumns = 9;
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<Real> heights(kColumns * kColumns);
  for (Real& h : heights) h = Real(0.15) * u(rng);
  auto field =
      std::make_shared<HeightField>(build_heightfield(heights, kColumns, Real(0.5), Real(0.5)));
  Shape surface;
  surface.type = ShapeType::Heightfield;
  surface.local_min = Vec3(0, field->min_height, 0);
  surface.local_max = Vec3(4, field->max_height, 4);
  surface.bounding_radius = Real(3);
  surface.heightfield = field;
  const Shape shapes[] = {make(ShapeType::Sphere, Real(0.2)),
                          make(ShapeType::Box, 0, Vec3(Real(0.3), Real(0.1), Real(0.2))),
                          test::capsule(Real(0.1), Real(0.3)),
                          test::cylinder(Real(0.25), Real(0.1))};
  const Real target = Real(0.01);
  const Transform still = at(0, 0, 0);
  int hits = 0, misses = 0;
  for (int trial = 0; trial < 240; ++trial) {
    const Shape& s = shapes[trial % 4];
    const Quat q0 = test::random_turn(rng, u);
    const Real angle = Real(0.8) * u(rng);
    const Vec3 axis = Vec3{u(rng), u(rng), u(rng)}.normalized();
    const Quat q1 = (Quat(Eigen::AngleAxis<Real>(angle, axis)) * q0).normalized();
    const Transform x0 = test::pose(
        Vec3{2 + Real(1.2) * u(rng), 1 + Real(0.4) * u(rng), 2 + Real(1.2) * u(rng)}, q0);
    const Vec3 d{Real(1.5) * u(rng), Real(-1.2) + Real(0.6) * u(rng), Real(1.5) * u(rng)};
    Transform x1 = x0;
    x1.position += d;
    x1.rotation = q1;
    const Real t = time_of_impact(s, x0, x1, surface, still, still, target);
    const auto nearest = [&](Real time) {
      Transform x;
      x.position = x0.position + time * d;
      x.rotation = fixed_slerp(x0.rotation, time, x1.rotation);
      Real best = std::numeric_limits<Real>::max();
      for (uint32_t k = 0; k < 2 * (kColumns - 1) * (kColumns - 1); ++k) {
        const MeshTriangle tri = field->corners(k);
        if (tri.normal().dot(x0.position - tri.v[0]) < 0) continue;  // behind: one-sided
        const Vec3 v[3] = {tri.v[0] - x.position, tri.v[1] - x.position, tri.v[2] - x.position};
        Simplex simplex;
        const GjkResult g =
            gjk_triangle(place(s, {Vec3::Zero(), x.rotation}, true), v, Vec3::UnitY(), simplex);
        best = std::min(best, g.overlap ? Real(0) : g.distance);
      }
      return best;
    };
    constexpr int kSamples = 40;
    for (int k = 0; k < kSamples; ++k) {
      const Real time = t * Real(k) / kSamples;
      ASSERT_GE(nearest(time), target - Real(1e-4)) << "trial " << trial << " at " << time;
    }
    if (t < 1) {
      ++hits;
      ASSERT_LE(nearest(t), target + allowance(target, s.bounding_radius) + Real(1e-4))
          << "trial " << trial;
    } else {
      ++misses;
    }
  }
  EXPECT_GT(hits, 60);
  EXPECT_GT(misses, 20);
}

}  // namespace narrowphase_toi_test
}  // namespace elan::detail
