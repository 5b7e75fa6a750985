// Lane-parallel arithmetic for the contact solver: kLanes constraints at once in a GCC/Clang
// vector type. The compiler maps it to one AVX register (or two SSE ones without AVX), and the
// values stay in registers across a whole constraint, which per-loop `omp simd` would not give.
#pragma once

#include <cmath>
#include <cstdint>

#include "elan/math.hpp"

namespace elan::detail {

// Box2D v3 bundles 8 constraints on AVX2 as well; 16 lanes would leave the later, smaller
// colours mostly padding.
inline constexpr int kLanes = 8;

typedef Real Wide __attribute__((vector_size(kLanes * sizeof(Real))));

struct WideVec3 {
  Wide x{}, y{}, z{};
};

inline Wide splat(Real v) {
  return Wide{} + v;
}
inline Wide wide_max(Wide a, Wide b) {
  return a > b ? a : b;
}
inline Wide wide_min(Wide a, Wide b) {
  return a < b ? a : b;
}

inline Wide dot(const WideVec3& a, const WideVec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline WideVec3 operator+(const WideVec3& a, const WideVec3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline WideVec3 operator-(const WideVec3& a, const WideVec3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline WideVec3 operator*(Wide s, const WideVec3& a) {
  return {s * a.x, s * a.y, s * a.z};
}

inline WideVec3 cross(const WideVec3& a, const WideVec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// One lane of a WideVec3 as a Vec3, and back.
inline Vec3 lane(const WideVec3& v, int l) {
  return {v.x[l], v.y[l], v.z[l]};
}
inline void set_lane(WideVec3& v, int l, const Vec3& value) {
  v.x[l] = value.x();
  v.y[l] = value.y();
  v.z[l] = value.z();
}

}  // namespace elan::detail
