// SPDX-License-Identifier: MIT
// The engine's own sin, cos, atan2 and acos (core/base/fixed_math.hpp) against long double
// references, within the bounds its comment states, and the C library's signs at the edges.
// fixed_slerp (core/base/fixed_slerp.hpp) against Eigen's slerp in double.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

#include "core/base/fixed_math.hpp"
#include "core/base/fixed_slerp.hpp"

namespace elan::detail {
namespace fixed_math_test {

// The bound is for the double result; the long double reference (x87, 64-bit mantissa) is good
// to about 1e-19 here, far below it.
constexpr double kTrigBound = 1e-15;
constexpr double kAngleBound = 2e-15;

TEST(FixedMath, SinAndCosWithinTheirBoundUpToAMillionRadians) {
  std::mt19937_64 rng(41);
  double worst = 0;
  for (const double range : {1.0, 4.0, 100.0, 1e6}) {
    std::uniform_real_distribution<double> pick(-range, range);
    for (int i = 0; i < 20000; ++i) {
      const double x = pick(rng);
      const FixedSinCos sc = fixed_sin_cos(x);
      const double es = std::abs(double(sc.sin - std::sin(static_cast<long double>(x))));
      const double ec = std::abs(double(sc.cos - std::cos(static_cast<long double>(x))));
      worst = std::max(worst, std::max(es, ec));
      ASSERT_LE(es, kTrigBound) << "sin " << x;
      ASSERT_LE(ec, kTrigBound) << "cos " << x;
    }
  }
  // A bound that cannot be met by a wrong quadrant or a missing term, which err by 1e-3 or more.
  EXPECT_GT(worst, 0.0);
}

TEST(FixedMath, SinAndCosExactAtZeroAndNanAtInfinity) {
  EXPECT_EQ(fixed_sin(0.0), 0.0);
  EXPECT_EQ(fixed_cos(0.0), 1.0);
  EXPECT_TRUE(std::isnan(fixed_sin(std::numeric_limits<double>::infinity())));
  EXPECT_TRUE(std::isnan(fixed_cos(std::numeric_limits<double>::quiet_NaN())));
  // Beyond the reduction's range the values stay on the unit circle's bounds.
  const FixedSinCos far = fixed_sin_cos(1e300);
  EXPECT_LE(std::abs(far.sin), 1.0);
  EXPECT_LE(std::abs(far.cos), 1.0);
}

TEST(FixedMath, Atan2WithinItsBoundInEveryQuadrant) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::uniform_real_distribution<double> log_radius(-20, 20);
  for (int i = 0; i < 100000; ++i) {
    const double t = angle(rng), r = std::exp(log_radius(rng));
    const double y = r * std::sin(t), x = r * std::cos(t);
    const long double reference =
        std::atan2(static_cast<long double>(y), static_cast<long double>(x));
    ASSERT_LE(std::abs(double(fixed_atan2(y, x) - reference)), kAngleBound) << y << ", " << x;
  }
}

TEST(FixedMath, Atan2SignsAndEdgesAsTheCLibrary) {
  const double inf = std::numeric_limits<double>::infinity();
  const double cases[][2] = {{0.0, 1.0},  {-0.0, 1.0}, {0.0, -1.0}, {-0.0, -1.0}, {1.0, 0.0},
                             {-1.0, 0.0}, {0.0, 0.0},  {-0.0, 0.0}, {0.0, -0.0},  {-0.0, -0.0},
                             {inf, 1.0},  {1.0, inf},  {1.0, -inf}, {inf, inf},   {-inf, -inf},
                             {1.0, 1.0},  {-2.0, 2.0}, {3.0, -3.0}};
  for (const auto& c : cases) {
    const double got = fixed_atan2(c[0], c[1]), want = std::atan2(c[0], c[1]);
    EXPECT_NEAR(got, want, kAngleBound) << c[0] << ", " << c[1];
    EXPECT_EQ(std::signbit(got), std::signbit(want)) << c[0] << ", " << c[1];
  }
  EXPECT_TRUE(std::isnan(fixed_atan2(std::nan(""), 1.0)));
}

TEST(FixedMath, AcosWithinItsBoundAndClampedOutsideOne) {
  for (int i = -1000; i <= 1000; ++i) {
    const double c = i / 1000.0;
    EXPECT_NEAR(fixed_acos(c), double(std::acos(static_cast<long double>(c))), kAngleBound) << c;
  }
  EXPECT_EQ(fixed_acos(1.0), 0.0);
  EXPECT_NEAR(fixed_acos(-1.0), M_PI, kAngleBound);
  EXPECT_EQ(fixed_acos(1.5), 0.0);
  EXPECT_TRUE(std::isnan(fixed_acos(std::nan(""))));
}

// fixed_slerp against Eigen's slerp in double (the C library's trig, good to an ulp of double):
// the float result within a few float epsilons, the rotation at t = 0 and t = 1 its ends' (the
// shorter arc: q1 or -q1), and near-parallel pairs on the straight-line case without NaN.
TEST(FixedMath, SlerpAgreesWithEigensInDoubleAndTakesTheShorterArc) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto draw = [&] { return Eigen::Quaterniond{g(rng), g(rng), g(rng), g(rng)}.normalized(); };
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Quaterniond a = draw();
    // Every fourth pair nearly parallel (down to 1e-7 rad apart), the rest anywhere.
    const Eigen::Quaterniond b =
        i % 4 == 0 ? (a * Eigen::Quaterniond{1, 1e-7 * g(rng), 1e-7 * g(rng), 0}.normalized())
                   : draw();
    const double t = i % 10 == 0 ? double(i % 20 == 0) : unit(rng);
    const Quat qa = a.cast<Real>(), qb = b.cast<Real>();
    const Quat got = fixed_slerp(qa, Real(t), qb);
    const Eigen::Quaterniond want = qa.cast<double>().slerp(t, qb.cast<double>());
    // The same rotation: |dot| = 1 up to float rounding; and the same sign (shorter arc from a).
    EXPECT_NEAR(got.cast<double>().dot(want), 1.0, 4e-6) << i << " t " << t;
    EXPECT_NEAR(double(got.norm()), 1.0, 4e-6) << i;
    if (t == 0) {
      EXPECT_NEAR(got.cast<double>().dot(qa.cast<double>()), 1.0, 4e-6) << i;
    }
    if (t == 1) {
      EXPECT_NEAR(std::abs(got.cast<double>().dot(qb.cast<double>())), 1.0, 4e-6) << i;
    }
  }
}

}  // namespace fixed_math_test
}  // namespace elan::detail
