// SPDX-License-Identifier: MIT
// Checks of values against the supported ranges of elan/limits.hpp, each failure an elan::Error
// naming the field, the range with its unit, and the value.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include "elan/error.hpp"
#include "elan/limits.hpp"
#include "elan/math.hpp"

namespace elan::detail {

// %g of a value (inf and nan spelled as such).
inline std::string show_value(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// "must be in [lo, hi] unit, got v" (unit "" for a pure number) unless lo <= v <= hi. The bounds
// are compared as rounded to Real, so that a bound written in a file or in code (1e-4
// is 9.99999975e-5 as a float) is in.
inline void check_range(double v, double lo, double hi, const char* field, const char* unit) {
  if (!(v >= double(Real(lo)) && v <= double(Real(hi)))) {
    throw Error(field, "must be in [" + show_value(lo) + ", " + show_value(hi) + "]" +
                           (*unit ? " " : "") + unit + ", got " + show_value(v));
  }
}

// Each coordinate of p within [-max, max] (a position in the supported world box).
inline void check_coordinates(const Vec3& p, double max, const char* field, const char* unit) {
  static constexpr char kAxis[] = "xyz";
  for (int i = 0; i < 3; ++i) {
    if (!(std::fabs(double(p[i])) <= max)) {
      throw Error(field, "each coordinate must be in [" + show_value(-max) + ", " +
                             show_value(max) + "] " + unit + ", got " + kAxis[i] + " = " +
                             show_value(double(p[i])));
    }
  }
}

// The length of v (a speed or an acceleration) at most max; computed in double, so that a
// float vector of 1e20 is measured, not overflowed.
inline void check_length(const Vec3& v, double max, const char* field, const char* unit) {
  const double n = v.cast<double>().norm();
  if (!(n <= max)) {
    throw Error(
        field, "length must be at most " + show_value(max) + " " + unit + ", got " + show_value(n));
  }
}

// density x volume, refused (elan::Error "mass") unless within the mass range. In double, so
// that an overflow of the float product is reported as the mass it is; the product of two floats
// is exact in double, so its rounding to Real is the float product.
inline Real checked_mass(Real density, Real volume) {
  const double m = double(density) * double(volume);
  if (!(m >= double(Real(limits::kMinMass)) && m <= double(Real(limits::kMaxMass)))) {
    throw Error("mass", "computed mass is out of range: density " + show_value(density) +
                            " kg/m^3 x volume " + show_value(volume) + " m^3 = " + show_value(m) +
                            " kg, outside [" + show_value(limits::kMinMass) + ", " +
                            show_value(limits::kMaxMass) + "] kg");
  }
  return Real(m);
}

// The inverse principal inertia 1 / (mass * unit_inertia) of a dynamic body, refused unless
// finite and positive (the step divides by neither, so an infinite one would freeze the body).
inline Vec3 inverse_inertia(Real mass, const Vec3& unit_inertia) {
  const Vec3 inertia = mass * unit_inertia;
  const Vec3 inv(1 / inertia.x(), 1 / inertia.y(), 1 / inertia.z());
  if (!(inv.allFinite() && inv.x() > 0 && inv.y() > 0 && inv.z() > 0)) {
    throw Error("mass", "the inertia mass x (" + show_value(unit_inertia.x()) + ", " +
                            show_value(unit_inertia.y()) + ", " + show_value(unit_inertia.z()) +
                            ") m^2 is out of range: its inverse is not finite and positive");
  }
  return inv;
}

}  // namespace elan::detail
