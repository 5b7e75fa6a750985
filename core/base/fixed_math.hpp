// SPDX-License-Identifier: MIT
// The engine's own sine, cosine, arc tangent and arc cosine: only additions, multiplications,
// divisions, square roots and exact roundings (nearbyint), in double, each in a fixed order.
// determinism (rule 7): the C library's versions are not correctly rounded (glibc's float ones
// least of all), and their last bits change with the library, its version and the variant it
// picks at run time for the CPU (FMA or not); these give the same bits on every IEEE-754 target
// built without contraction (-ffp-contract=off), like Box2D v3's b2ComputeCosSin and b2Atan2.
// Error bounds, in double before the final rounding to Real (tests/unit/fixed_math.cpp checks
// them against long double): sin and cos within 1e-15 absolute for |x| <= 1e6 (the reduction
// by pi/2 loses |x| 2^-80 or so beyond that; the result is still in [-1, 1] and deterministic);
// atan2 within 2e-15 rad; acos within 2e-15 rad away from +-1 (sqrt(1 - c^2) there).
// So a float result is the correctly rounded one but for values within about 1e-8 ulp of a
// rounding boundary, and the same on every build either way.
#pragma once

#include <cmath>

namespace elan::detail {

struct FixedSinCos {
  double sin, cos;
};

// sin x and cos x. x = q pi/2 + r, |r| <= pi/4 (Cody-Waite: pi/2 in three parts, each product
// q * part exact for |q| < 2^20), then Taylor series in r^2 to r^17 and r^16: the first term left
// out is below 0.79^19 / 19! < 1.1e-19.
inline FixedSinCos fixed_sin_cos(double x) {
  if (!(std::abs(x) < 1e15)) {
    // Infinite or NaN: NaN, as the C library gives; beyond 1e15 the quadrant is meaningless.
    const double nan = x - x;
    return {std::isnan(nan) ? nan : 0.0, std::isnan(nan) ? nan : 1.0};
  }
  constexpr double kTwoOverPi = 0.63661977236758134308;
  constexpr double kPio2Hi = 1.57079632673412561417e+00;   // first 33 bits of pi/2
  constexpr double kPio2Mid = 6.07710050630396597660e-11;  // next 33 bits
  constexpr double kPio2Lo = 2.02226624879595063154e-21;   // the rest
  const double q = std::nearbyint(x * kTwoOverPi);
  const double r = ((x - q * kPio2Hi) - q * kPio2Mid) - q * kPio2Lo;
  const double r2 = r * r;
  // sin r = r (1 - r^2/3! + r^4/5! - ...), cos r = 1 - r^2/2! + r^4/4! - ...
  const double s =
      r + r * r2 *
              (-1.0 / 6 +
               r2 * (1.0 / 120 + r2 * (-1.0 / 5040 +
                                       r2 * (1.0 / 362880 +
                                             r2 * (-1.0 / 39916800 +
                                                   r2 * (1.0 / 6227020800 +
                                                         r2 * (-1.0 / 1307674368000 +
                                                               r2 * (1.0 / 355687428096000))))))));
  const double c =
      1 + r2 * (-1.0 / 2 +
                r2 * (1.0 / 24 +
                      r2 * (-1.0 / 720 + r2 * (1.0 / 40320 +
                                               r2 * (-1.0 / 3628800 +
                                                     r2 * (1.0 / 479001600 +
                                                           r2 * (-1.0 / 87178291200 +
                                                                 r2 * (1.0 / 20922789888000))))))));
  // The quadrant, q mod 4, from q's exact value (|q| < 2^50 here).
  const double quarter = q - 4 * std::floor(q * 0.25);
  switch (int(quarter)) {
    case 0:
      return {s, c};
    case 1:
      return {c, -s};
    case 2:
      return {-s, -c};
    default:
      return {-c, s};
  }
}

inline double fixed_sin(double x) {
  return fixed_sin_cos(x).sin;
}
inline double fixed_cos(double x) {
  return fixed_sin_cos(x).cos;
}

// atan2(y, x) in [-pi, pi], with the C library's signs for zeros (atan2(+-0, +x) = +-0,
// atan2(+-0, -x) = +-pi) and its values at infinities. The ratio a = min / max of |x|, |y| is in
// [0, 1]; above tan(pi/8), atan a = pi/4 + atan((a - 1) / (a + 1)), so the series runs on
// |t| <= tan(pi/8): atan t = t - t^3/3 + t^5/5 - ... - t^35/35, an alternating series whose
// remainder is below its first term left out, 0.4143^37 / 37 < 2e-16.
inline double fixed_atan2(double y, double x) {
  constexpr double kPi = 3.14159265358979311600;
  constexpr double kPio2 = 1.57079632679489655800;
  constexpr double kPio4 = 0.78539816339744827900;
  constexpr double kTanPio8 = 0.41421356237309503;
  if (std::isnan(x) || std::isnan(y)) return x + y;
  const double ax = std::abs(x), ay = std::abs(y);
  double angle;  // in [0, pi/2], for |x| and |y|
  if (ay == 0) {
    angle = 0;
  } else if (ax == 0) {
    angle = kPio2;
  } else if (std::isinf(ax) || std::isinf(ay)) {
    angle = std::isinf(ax) ? (std::isinf(ay) ? kPio4 : 0.0) : kPio2;
  } else {
    const bool steep = ay > ax;
    const double a = steep ? ax / ay : ay / ax;
    const bool high = a > kTanPio8;
    const double t = high ? (a - 1) / (a + 1) : a;
    const double t2 = t * t;
    // Horner over the odd terms: t (1 - t^2/3 + t^4/5 - ... - t^34/35).
    double p = -1.0 / 35;
    for (int k = 33; k >= 3; k -= 2) p = (k % 4 == 1 ? 1.0 : -1.0) / k + t2 * p;
    double atan_a = t + t * t2 * p;
    if (high) atan_a = kPio4 + atan_a;
    angle = steep ? kPio2 - atan_a : atan_a;
  }
  // The quadrant: x < 0 (or -0) mirrors the angle about pi/2.
  if (std::signbit(x)) angle = kPi - angle;
  return std::signbit(y) ? -angle : angle;
}

// acos c for c in [-1, 1] (clamped; NaN stays NaN) as atan2(sqrt((1 - c)(1 + c)), c).
inline double fixed_acos(double c) {
  if (std::isnan(c)) return c;
  c = c < -1 ? -1 : (c > 1 ? 1 : c);
  return fixed_atan2(std::sqrt((1 - c) * (1 + c)), c);
}

}  // namespace elan::detail
