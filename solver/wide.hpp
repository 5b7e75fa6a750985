// SPDX-License-Identifier: MIT
// Lane-parallel arithmetic for the contact solver: kLanes constraints at once in a GCC/Clang
// vector type. The compiler maps it to one AVX-512 or AVX register (or several narrower ones),
// and the values stay in registers across a whole constraint, which per-loop `omp simd` would
// not give. Each lane does the same operations whatever the width, so built with the same flags,
// 8 and 16 lanes give the same state hashes.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

// The lane count as a macro too, for the #if of the intrinsic paths below and in body_lanes.hpp.
// ELAN_LANES (the CMake cache option of that name) overrides the ISA's default.
#if defined(ELAN_LANES)
#define ELAN_WIDE_LANES ELAN_LANES
#elif defined(__AVX512F__) || (defined(ELAN_DISPATCH) && !defined(ELAN_DOUBLE))
#define ELAN_WIDE_LANES 16
#else
#define ELAN_WIDE_LANES 8
#endif
#if ELAN_WIDE_LANES != 8 && ELAN_WIDE_LANES != 16
#error "ELAN_LANES must be 8 or 16"
#endif
// The AVX-512 intrinsic paths: sixteen float lanes in one zmm register.
#if defined(__AVX512F__) && !defined(ELAN_DOUBLE) && ELAN_WIDE_LANES == 16
#define ELAN_WIDE_AVX512 1
#include <immintrin.h>
#endif

#include "elan/math.hpp"

namespace elan::detail {

// perf: a pass over a bundle is bound by the chain of dependent updates (each point row reads the
// velocities the row before it wrote), not by arithmetic width, so a wider bundle does more
// work per step of that chain. With AVX-512, 16 lanes in one register do better than 8, though
// the later, smaller colours carry more padding. Without it (Box2D v3 bundles 8 on AVX2), 16 lanes
// would take two registers each and spill.
// A portable build that dispatches at run time (ELAN_DISPATCH, core/base/isa.hpp) has one bundle
// layout for all its paths, so 16 lanes on each (ELAN_WIDE_LANES above): the SSE2 and AVX2 paths
// take four or two registers per value.
inline constexpr int kLanes = ELAN_WIDE_LANES;

// Aligned to its size whatever the instruction set (GCC aligns a 64-byte vector to 16 bytes
// without AVX-512), so the bundles have one layout on every path of a dispatching build.
typedef Real Wide
    __attribute__((vector_size(kLanes * sizeof(Real)), aligned(kLanes * sizeof(Real))));
static_assert(alignof(Wide) == sizeof(Wide));
// A Wide as a container's element: a template argument drops the typedef's alignment, a struct
// member keeps it.
struct WideValue {
  Wide v{};
};
static_assert(alignof(WideValue) == sizeof(Wide));

// Lane masks, as comparisons of Wide values give them (all bits set where true).
typedef decltype(Wide{} < Wide{}) WideMask;

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

// Lane-wise square root. IEEE square roots are correctly rounded, so these are the bits of
// std::sqrt lane by lane; the lane loop compiles to scalar calls (errno), the intrinsic to one
// instruction.
inline Wide wide_sqrt(Wide x) {
#if defined(ELAN_WIDE_AVX512)
  // A zeroing mask of all lanes: _mm512_sqrt_ps passes GCC 12 an undefined merge operand, which it
  // reports as used uninitialized in some callers (GCC bug 105593; see body_lanes.hpp).
  return Wide(_mm512_maskz_sqrt_ps(__mmask16(0xFFFF), __m512(x)));
#else
  for (int l = 0; l < kLanes; ++l) x[l] = std::sqrt(x[l]);
  return x;
#endif
}

// Whether any lane of the mask is set: one OR over its words, not a branch per lane.
inline bool any_lane(WideMask m) {
  uint64_t words[sizeof(WideMask) / sizeof(uint64_t)];
  std::memcpy(words, &m, sizeof(m));
  uint64_t any = 0;
  for (const uint64_t w : words) any |= w;
  return any != 0;
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

// Per lane: a where the mask is set, else b.
inline WideVec3 select(WideMask m, const WideVec3& a, const WideVec3& b) {
  return {m ? a.x : b.x, m ? a.y : b.y, m ? a.z : b.z};
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
