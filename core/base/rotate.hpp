// SPDX-License-Identifier: MIT
// A vector turned by a unit quaternion, as Eigen's `q * v` computes it, always inline.
#pragma once

#include "elan/math.hpp"

namespace elan::detail {

// q v q^-1 by Eigen's own formula (QuaternionBase::_transformVector: uv = 2 (q.vec x v), then
// v + w uv + q.vec x uv), so the bits are those of `q * v`. perf: in a large function GCC may
// leave Eigen's out of line (it did in the collide stage's pair loop); it then returns the vector
// through memory, stored one float at a time, and the caller reads it back eight bytes at once, a
// failed store-to-load forwarding.
// The sum is written out coefficient by coefficient, in Eigen's order ((v + w uv) + c), since GCC
// outlined even the expression's assignment loop there.
[[gnu::always_inline]] inline Vec3 rotate(const Quat& q, const Vec3& v) {
  Vec3 uv = q.vec().cross(v);
  uv += uv;
  const Vec3 c = q.vec().cross(uv);
  const Real w = q.w();
  return Vec3(v.x() + w * uv.x() + c.x(), v.y() + w * uv.y() + c.y(), v.z() + w * uv.z() + c.z());
}

}  // namespace elan::detail
