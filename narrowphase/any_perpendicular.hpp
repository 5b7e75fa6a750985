// SPDX-License-Identifier: MIT
// A unit vector perpendicular to a direction, for the contact normal of features that coincide
// (EPA's degenerate polytope, coincident segments, a sphere centred on a capsule's axis).
#pragma once

#include "elan/math.hpp"

namespace elan::detail {

// t × (the coordinate axis along which t is smallest): never near zero for a nonzero t, and a
// fixed function of t, so the normal it gives is the same on every build.
inline Vec3 any_perpendicular(const Vec3& t) {
  const Vec3 a = t.cwiseAbs();
  const Vec3 axis = a.x() <= a.y() && a.x() <= a.z() ? Vec3::UnitX()
                    : a.y() <= a.z()                 ? Vec3::UnitY()
                                                     : Vec3::UnitZ();
  return t.cross(axis).normalized();
}

}  // namespace elan::detail
