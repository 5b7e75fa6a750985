// SPDX-License-Identifier: MIT
// Loads and stores of the bodies on one side of a contact bundle: lane l of the wide values is
// the solver body packets[l]. gather_velocity reads v and w, gather_pose dp and dtheta,
// gather_mass the inverse mass and inertia, and scatter_velocity writes v and w back to the
// lanes whose packet is written (written_packet: static, kinematic and unused sides are
// read-only). The packets of a bundle are scattered in memory. gather_packets and
// scatter_packets move all of kLanes consecutive packets, for the substep integration, and
// gather_rows any kLanes rows of sixteen floats.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "solver/solver_types.hpp"
#include "solver/wide.hpp"

#if defined(ELAN_WIDE_AVX512) && defined(__AVX512VL__)
#include <immintrin.h>
#define ELAN_TRANSPOSED_LANES 1
#endif

namespace elan::detail {

// Velocities of the kLanes bodies on one side of a bundle.
struct WideBody {
  WideVec3 v, w;
};

// Inverse masses and world inverse inertias of the kLanes bodies on one side of a bundle.
struct WideMass {
  Wide inv_mass{};
  WideSym3 inv_inertia;
};

// A packet's sixteen floats: v, w, dp, dtheta, then dq's x, y, z and w (Eigen's storage order).
static_assert(sizeof(SolverBody) == 16 * sizeof(Real) &&
              offsetof(SolverBody, dq) == 12 * sizeof(Real));
inline const Real* floats_of(const SolverBody& b) {
  return reinterpret_cast<const Real*>(&b);
}
inline Real* floats_of(SolverBody& b) {
  return reinterpret_cast<Real*>(&b);
}

#if defined(ELAN_TRANSPOSED_LANES)
// perf: the 6 velocity components are not inserted lane by lane, a store each that the first
// vector read waits for (see gather_packets). A body's v and w are its first six floats, so each
// lane loads them (and two more) as one 8-float row; rows l and l + 8 share a register, and an 8x8
// transpose within each 256-bit half (unpack, shuffle, then a two-source permute for the 128-bit
// blocks) leaves component j of all 16 lanes in register j. The transpose is its own inverse, which
// gives the stores. Data movement only: the same bits as the lane loop.
static_assert(kLanes == 16 && sizeof(SolverBody) == 64);
static_assert(offsetof(SolverBody, w) == offsetof(SolverBody, v) + 3 * sizeof(Real) &&
              offsetof(SolverBody, dtheta) == offsetof(SolverBody, dp) + 3 * sizeof(Real) &&
              offsetof(SolverBody, dp) + 8 * sizeof(Real) <= sizeof(SolverBody));
static_assert(sizeof(SolverBodyMass) == 8 * sizeof(Real) &&
              offsetof(SolverBodyMass, inv_mass) == 0 &&
              offsetof(SolverBodyMass, inv_inertia) == sizeof(Real) &&
              sizeof(SymMat3) == 6 * sizeof(Real));

// GCC 12 warns that the AVX-512 intrinsics' deliberately undefined merge operand (`__m512 __Y =
// __Y`) is used uninitialized wherever they are inlined into a caller it analyses whole (GCC bug
// 105593, fixed in 13); -Werror turns that into an error in some callers, so it is silenced here.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ < 13
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

inline void transpose_8x8_halves(const __m512 in[8], __m512 out[8]) {
  __m512 t[8], u[8];
  for (int i = 0; i < 4; ++i) {
    t[2 * i] = _mm512_unpacklo_ps(in[2 * i], in[2 * i + 1]);
    t[2 * i + 1] = _mm512_unpackhi_ps(in[2 * i], in[2 * i + 1]);
  }
  for (int i = 0; i < 2; ++i) {
    u[4 * i + 0] = _mm512_shuffle_ps(t[4 * i + 0], t[4 * i + 2], 0x44);
    u[4 * i + 1] = _mm512_shuffle_ps(t[4 * i + 0], t[4 * i + 2], 0xEE);
    u[4 * i + 2] = _mm512_shuffle_ps(t[4 * i + 1], t[4 * i + 3], 0x44);
    u[4 * i + 3] = _mm512_shuffle_ps(t[4 * i + 1], t[4 * i + 3], 0xEE);
  }
  // 128-bit blocks [a0 b0 a2 b2] and [a1 b1 a3 b3].
  const __m512i low = _mm512_setr_epi32(0, 1, 2, 3, 16, 17, 18, 19, 8, 9, 10, 11, 24, 25, 26, 27);
  const __m512i high =
      _mm512_setr_epi32(4, 5, 6, 7, 20, 21, 22, 23, 12, 13, 14, 15, 28, 29, 30, 31);
  for (int j = 0; j < 4; ++j) {
    out[j] = _mm512_permutex2var_ps(u[j], low, u[j + 4]);
    out[j + 4] = _mm512_permutex2var_ps(u[j], high, u[j + 4]);
  }
}

// Two lanes' rows of 8 floats, from `lo` and `hi`, one in each 256-bit half.
inline __m512 two_rows(const Real* lo, const Real* hi) {
  const __m512d low = _mm512_castps_pd(_mm512_castps256_ps512(_mm256_loadu_ps(lo)));
  return _mm512_castpd_ps(_mm512_insertf64x4(low, _mm256_castps_pd(_mm256_loadu_ps(hi)), 1));
}

// The row in the upper 256-bit half of `rows`: two_rows' `hi`, as a transpose leaves it.
inline __m256 upper_row(__m512 rows) {
  return _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(rows), 1));
}

// Components of two consecutive Vec3 members of the bundle's bodies, from `first` on: six
// floats, and the two that follow are read and dropped (SolverBody is 64 bytes, so they exist).
template <Vec3 SolverBody::*first>
inline void gather_two(const SolverBody* bodies, const uint32_t* packets, WideVec3& p,
                       WideVec3& q) {
  __m512 rows[8], cols[8];
  for (int l = 0; l < 8; ++l) {
    rows[l] = two_rows((bodies[packets[l]].*first).data(), (bodies[packets[l + 8]].*first).data());
  }
  transpose_8x8_halves(rows, cols);
  p = {Wide(cols[0]), Wide(cols[1]), Wide(cols[2])};
  q = {Wide(cols[3]), Wide(cols[4]), Wide(cols[5])};
}

inline void gather_velocity(const SolverBody* bodies, const uint32_t* packets, WideBody& out) {
  gather_two<&SolverBody::v>(bodies, packets, out.v, out.w);
}

inline void gather_pose(const SolverBody* bodies, const uint32_t* packets, WideVec3& dp,
                        WideVec3& dtheta) {
  gather_two<&SolverBody::dp>(bodies, packets, dp, dtheta);
}

// A packet's mass is one 8-float row: inv_mass, then xx, yy, zz, xy, xz, yz.
inline void gather_mass(const SolverBodyMass* masses, const uint32_t* packets, WideMass& out) {
  __m512 rows[8], cols[8];
  for (int l = 0; l < 8; ++l) {
    rows[l] = two_rows(&masses[packets[l]].inv_mass, &masses[packets[l + 8]].inv_mass);
  }
  transpose_8x8_halves(rows, cols);
  out.inv_mass = Wide(cols[0]);
  out.inv_inertia = {Wide(cols[1]), Wide(cols[2]), Wide(cols[3]),
                     Wide(cols[4]), Wide(cols[5]), Wide(cols[6])};
}

inline void scatter_velocity(SolverBody* bodies, const uint32_t* packets, uint32_t written_end,
                             const WideBody& in) {
  // Lane l is written when packet - 1 < written_end - 1, unsigned (written_packet).
  const __m512i one = _mm512_set1_epi32(1);
  const __mmask16 write = _mm512_cmplt_epu32_mask(
      _mm512_sub_epi32(_mm512_loadu_si512(packets), one), _mm512_set1_epi32(int(written_end - 1)));
  const __m512 cols[8] = {__m512(in.v.x), __m512(in.v.y), __m512(in.v.z),      __m512(in.w.x),
                          __m512(in.w.y), __m512(in.w.z), _mm512_setzero_ps(), _mm512_setzero_ps()};
  __m512 rows[8];
  transpose_8x8_halves(cols, rows);
  for (int l = 0; l < 8; ++l) {
    // The first six floats of the row, v and w. perf: a lane not written (most often the static
    // dummy, packet 0, which every bundle against the ground names) is skipped by a branch rather
    // than issued with an empty mask, which still costs a store.
    if ((write >> l) & 1) {
      _mm256_mask_storeu_ps(bodies[packets[l]].v.data(), 0x3F, _mm512_castps512_ps256(rows[l]));
    }
    if ((write >> (l + 8)) & 1) {
      _mm256_mask_storeu_ps(bodies[packets[l + 8]].v.data(), 0x3F, upper_row(rows[l]));
    }
  }
}

// Float j of the sixteen floats at row[l] in lane l of cols[j], for the kLanes rows.
// perf: two 8x8 transposes instead of 256 lane inserts. Each insert is a store into the vector
// on the stack, and its first read as a vector waits for all of them (a failed store-to-load
// forward).
inline void gather_rows(const Real* const row[kLanes], Wide cols[16]) {
  for (int half = 0; half < 2; ++half) {
    __m512 rows[8], out[8];
    for (int l = 0; l < 8; ++l) rows[l] = two_rows(row[l] + 8 * half, row[l + 8] + 8 * half);
    transpose_8x8_halves(rows, out);
    for (int j = 0; j < 8; ++j) cols[8 * half + j] = Wide(out[j]);
  }
}

// Stores lanes 0 to count - 1 of cols back into the packets from `first` on. perf: with the
// transposes of gather_packets, not lane by lane.
inline void scatter_packets(SolverBody* first, int count, const Wide cols[16]) {
  for (int half = 0; half < 2; ++half) {
    __m512 in[8], rows[8];
    for (int j = 0; j < 8; ++j) in[j] = __m512(cols[8 * half + j]);
    transpose_8x8_halves(in, rows);
    for (int l = 0; l < 8 && l < count; ++l) {
      _mm256_storeu_ps(floats_of(first[l]) + 8 * half, _mm512_castps512_ps256(rows[l]));
      if (l + 8 < count) {
        _mm256_storeu_ps(floats_of(first[l + 8]) + 8 * half, upper_row(rows[l]));
      }
    }
  }
}
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ < 13
#pragma GCC diagnostic pop
#endif
#else
inline void gather_velocity(const SolverBody* bodies, const uint32_t* packets, WideBody& out) {
  for (int l = 0; l < kLanes; ++l) {
    const SolverBody& b = bodies[packets[l]];
    set_lane(out.v, l, b.v);
    set_lane(out.w, l, b.w);
  }
}

inline void gather_pose(const SolverBody* bodies, const uint32_t* packets, WideVec3& dp,
                        WideVec3& dtheta) {
  for (int l = 0; l < kLanes; ++l) {
    const SolverBody& b = bodies[packets[l]];
    set_lane(dp, l, b.dp);
    set_lane(dtheta, l, b.dtheta);
  }
}

inline void gather_mass(const SolverBodyMass* masses, const uint32_t* packets, WideMass& out) {
  for (int l = 0; l < kLanes; ++l) {
    const SolverBodyMass& m = masses[packets[l]];
    out.inv_mass[l] = m.inv_mass;
    set_lane(out.inv_inertia, l, m.inv_inertia);
  }
}

// perf: a lane that is not written stores into a local sink instead of branching over it.
inline void scatter_velocity(SolverBody* bodies, const uint32_t* packets, uint32_t written_end,
                             const WideBody& in) {
  SolverBody sink;
  for (int l = 0; l < kLanes; ++l) {
    SolverBody& b = written_packet(packets[l], written_end) ? bodies[packets[l]] : sink;
    b.v = lane(in.v, l);
    b.w = lane(in.w, l);
  }
}

inline void gather_rows(const Real* const row[kLanes], Wide cols[16]) {
  for (int l = 0; l < kLanes; ++l) {
    for (int j = 0; j < 16; ++j) cols[j][l] = row[l][j];
  }
}

inline void scatter_packets(SolverBody* first, int count, const Wide cols[16]) {
  for (int l = 0; l < count; ++l) {
    Real* f = floats_of(first[l]);
    for (int j = 0; j < 16; ++j) f[j] = cols[j][l];
  }
}
#endif

// Component j of the kLanes packets from `first` on in cols[j] (floats_of's order). Lanes from
// `count` on repeat the last packet, so their arithmetic stays finite; they are never stored.
inline void gather_packets(const SolverBody* first, int count, Wide cols[16]) {
  const Real* row[kLanes];
  for (int l = 0; l < kLanes; ++l) row[l] = floats_of(first[std::min(l, count - 1)]);
  gather_rows(row, cols);
}

}  // namespace elan::detail
