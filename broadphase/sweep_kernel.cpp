// SPDX-License-Identifier: MIT
// The sweep's kernel, compiled once per instruction set (broadphase/CMakeLists.txt): with AVX2 a
// chunk of eight candidates is one set of vector compares and its hits are packed by one permute;
// without it the same test runs as an `omp simd` loop and the hits are emitted one by one.
#include "broadphase/sweep_kernel.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <type_traits>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include "broadphase/closed_runs.hpp"
#include "broadphase/deep_sieve.hpp"
#include "broadphase/find_pairs.hpp"
#include "core/base/pair_key.hpp"

namespace elan::detail {
ELAN_ISA_BEGIN

namespace {

// Candidates tested at a time: the strips' sentinels make every chunk whole.
constexpr std::size_t kChunk = SweepAndPrune::kStripPad;

// One entry's side of the sweep test and the strip's candidate columns. A template so the float
// SIMD path is discarded, not compiled, when Real is double.
template <class R>
struct ChunkTest {
  const R *key, *lo1, *hi1, *lo2, *hi2;
  const uint32_t *first, *category, *mask;
  const uint8_t* kind;
  R hi = 0, l1 = 0, h1 = 0, l2 = 0, h2 = 0;
  uint32_t f = 0, strip = 0, cat = 0, msk = 0;
  uint32_t partner_kinds = 0;  // bit c set when should_pair(this kind, c)
  // The shut-out test (closed_runs.hpp): the candidates' balls, runs and shifts, this entry's.
  const R *bx = nullptr, *by = nullptr, *bz = nullptr, *br = nullptr;
  const uint32_t *runs = nullptr, *shifts = nullptr;
  R x = 0, y = 0, z = 0, r = 0;
  uint32_t run = 0, shift = 0;
};

uint32_t partner_kinds(BroadKind k) {
  uint32_t bits = 0;
  for (uint32_t c = 0; c < 4; ++c) bits |= uint32_t(should_pair(k, BroadKind(c))) << c;
  return bits;
}

// Bit q set when candidate j + q overlaps on all three axes (closed intervals), the pair's strip
// is this one and accept_pair passes; `more` is false once the chunk's last key is past hi.
template <class R>
uint32_t chunk_hits(const ChunkTest<R>& t, std::size_t j, bool& more) {
  static_assert(kChunk == 8);
#if defined(__AVX2__)
  if constexpr (std::is_same_v<R, float>) {
    // perf: eight lanes, one movemask; ordered compares are false on NaN like <= is.
    const __m256 below =
        _mm256_cmp_ps(_mm256_loadu_ps(t.key + j), _mm256_set1_ps(t.hi), _CMP_LE_OQ);
    __m256 m = _mm256_and_ps(
        below, _mm256_cmp_ps(_mm256_loadu_ps(t.lo1 + j), _mm256_set1_ps(t.h1), _CMP_LE_OQ));
    m = _mm256_and_ps(m,
                      _mm256_cmp_ps(_mm256_set1_ps(t.l1), _mm256_loadu_ps(t.hi1 + j), _CMP_LE_OQ));
    m = _mm256_and_ps(m,
                      _mm256_cmp_ps(_mm256_loadu_ps(t.lo2 + j), _mm256_set1_ps(t.h2), _CMP_LE_OQ));
    m = _mm256_and_ps(m,
                      _mm256_cmp_ps(_mm256_set1_ps(t.l2), _mm256_loadu_ps(t.hi2 + j), _CMP_LE_OQ));
    const auto load = [](const uint32_t* p) {
      return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
    };
    const __m256i zero = _mm256_setzero_si256(), one = _mm256_set1_epi32(1);
    const __m256i same =
        _mm256_cmpeq_epi32(_mm256_max_epu32(load(t.first + j), _mm256_set1_epi32(int(t.f))),
                           _mm256_set1_epi32(int(t.strip)));
    const __m256i kinds =
        _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(t.kind + j)));
    const __m256i pairable = _mm256_cmpeq_epi32(
        _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(t.partner_kinds)), kinds), one),
        one);
    const __m256i filtered = _mm256_or_si256(
        _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(t.cat)), load(t.mask + j)), zero),
        _mm256_cmpeq_epi32(_mm256_and_si256(load(t.category + j), _mm256_set1_epi32(int(t.msk))),
                           zero));
    const __m256i accept = _mm256_andnot_si256(filtered, _mm256_and_si256(same, pairable));
    m = _mm256_and_ps(m, _mm256_castsi256_ps(accept));
    more = _mm256_movemask_ps(below) == 0xFF;
    return uint32_t(_mm256_movemask_ps(m));
  }
#endif
  uint32_t hits = 0;
#pragma omp simd reduction(| : hits)
  for (std::size_t q = 0; q < 8; ++q) {
    const std::size_t c = j + q;
    const bool hit = (t.key[c] <= t.hi) & (t.lo1[c] <= t.h1) & (t.l1 <= t.hi1[c]) &
                     (t.lo2[c] <= t.h2) & (t.l2 <= t.hi2[c]) &
                     (std::max(t.f, t.first[c]) == t.strip) &
                     (((t.partner_kinds >> t.kind[c]) & 1u) != 0) & ((t.cat & t.mask[c]) != 0) &
                     ((t.category[c] & t.msk) != 0);
    hits |= uint32_t(hit) << q;
  }
  more = t.key[j + 7] <= t.hi;
  return hits;
}

// Bit q set when the sieve would turn candidate j + q away (closed_runs.hpp: shut_out, and the
// sieve's deep test deep_balls_inline), the same operations in the same order in each lane
// (rule 10; the differences may have the other sign, their squares and the radii's sum do not
// change), so a lane and the scalar test agree on every pair. This entry is closed.
template <class R>
uint32_t chunk_shut_out(const ChunkTest<R>& t, std::size_t j) {
#if defined(__AVX2__)
  if constexpr (std::is_same_v<R, float>) {
    const __m256 dx = _mm256_sub_ps(_mm256_set1_ps(t.x), _mm256_loadu_ps(t.bx + j));
    const __m256 dy = _mm256_sub_ps(_mm256_set1_ps(t.y), _mm256_loadu_ps(t.by + j));
    const __m256 dz = _mm256_sub_ps(_mm256_set1_ps(t.z), _mm256_loadu_ps(t.bz + j));
    const __m256 d2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                    _mm256_mul_ps(dz, dz));
    const __m256 reach =
        _mm256_mul_ps(_mm256_set1_ps(kDeepFraction),
                      _mm256_add_ps(_mm256_set1_ps(t.r), _mm256_loadu_ps(t.br + j)));
    const __m256 deep = _mm256_cmp_ps(d2, _mm256_mul_ps(reach, reach), _CMP_LT_OQ);
    // A shift of 32 or more (open) shifts every bit out, so an open lane is never shut.
    const auto load = [](const uint32_t* p) {
      return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
    };
    const __m256i shift = _mm256_max_epu32(load(t.shifts + j), _mm256_set1_epi32(int(t.shift)));
    const __m256i apart =
        _mm256_srlv_epi32(_mm256_xor_si256(load(t.runs + j), _mm256_set1_epi32(int(t.run))), shift);
    const __m256i same = _mm256_cmpeq_epi32(apart, _mm256_setzero_si256());
    return uint32_t(_mm256_movemask_ps(_mm256_andnot_ps(_mm256_castsi256_ps(same), deep)));
  }
#endif
  uint32_t shut = 0;
#pragma omp simd reduction(| : shut)
  for (std::size_t q = 0; q < 8; ++q) {
    const std::size_t c = j + q;
    const R dx = t.x - t.bx[c], dy = t.y - t.by[c], dz = t.z - t.bz[c];
    const R d2 = dx * dx + dy * dy + dz * dz;
    const R reach = kDeepFraction * (t.r + t.br[c]);
    const uint32_t sh = std::max(t.shift, t.shifts[c]);
    const bool hit =
        (d2 < reach * reach) & (sh < kOpenShift) & (((t.run ^ t.runs[c]) >> (sh & 31u)) != 0);
    shut |= uint32_t(hit) << q;
  }
  return shut;
}

#if defined(__AVX2__)
// Per 8-bit hit mask, the lanes of its set bits in order, a nibble each: the shuffle that packs
// hits to the front.
constexpr std::array<uint32_t, 256> make_compress_table() {
  std::array<uint32_t, 256> table{};
  for (uint32_t m = 0; m < 256; ++m) {
    uint32_t lanes = 0, count = 0;
    for (uint32_t q = 0; q < 8; ++q) {
      if ((m >> q) & 1u) lanes |= q << (4 * count++);
    }
    table[m] = lanes;
  }
  return table;
}
constexpr std::array<uint32_t, 256> kCompress = make_compress_table();
#endif

// Writes the keys of body i0 with body[q] for every set bit q of hits to dst[0, popcount), and
// may write anything to dst[popcount, 8). Returns popcount.
inline uint32_t emit_pairs(uint32_t hits, uint32_t i0, const uint32_t* body, uint64_t* dst) {
#if defined(__AVX2__)
  // perf: branch-free: hits are as likely as not in a chunk, so a loop over them mispredicts.
  const __m256i lanes =
      _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(kCompress[hits])),
                                         _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28)),
                       _mm256_set1_epi32(7));
  const __m256i b = _mm256_permutevar8x32_epi32(
      _mm256_loadu_si256(reinterpret_cast<const __m256i*>(body)), lanes);
  const __m256i a = _mm256_set1_epi32(int(i0));
  const __m256i lo = _mm256_min_epu32(a, b), hi = _mm256_max_epu32(a, b);
  const auto keys = [](__m128i l, __m128i h) {
    return _mm256_or_si256(_mm256_slli_epi64(_mm256_cvtepu32_epi64(l), 32),
                           _mm256_cvtepu32_epi64(h));
  };
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst),
                      keys(_mm256_castsi256_si128(lo), _mm256_castsi256_si128(hi)));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + 4),
                      keys(_mm256_extracti128_si256(lo, 1), _mm256_extracti128_si256(hi, 1)));
  return uint32_t(std::popcount(hits));
#else
  uint32_t count = 0;
  while (hits != 0) {
    dst[count++] = make_pair_key(i0, body[std::countr_zero(hits)]);
    hits &= hits - 1;
  }
  return count;
#endif
}

// Pairs of each entry in [begin, end) with the later entries of its strip. Within a strip a pair
// is met once, from whichever box comes first (ties in min included: key_j == key_i <= max_i). A
// pair overlapping on the strip axis shares every strip holding m = max(lo_a, lo_b), and is kept
// only in strip_of(m), so it is reported once; strip_of is monotonic, so
// strip_of(m) = max(strip_of(lo_a), strip_of(lo_b)) = max(first).
// kClosed: the strips carry closed levels (closed_runs.hpp), whose shut-out pairs are passed by.
template <bool kClosed>
void sweep(const SweepStrips& s, std::size_t begin, std::size_t end, DeepSieve* deep,
           ScratchVector<uint64_t>& out) {
  ChunkTest<Real> t{s.min, s.lo1, s.hi1, s.lo2, s.hi2, s.first, s.category, s.mask, s.kind};
  if constexpr (kClosed) {
    t.bx = s.ball_x;
    t.by = s.ball_y;
    t.bz = s.ball_z;
    t.br = s.ball_r;
    t.runs = s.run;
    t.shifts = s.shift;
  }
  const uint32_t* body = s.body;
  const std::span<const uint32_t> strip_begin = s.strip_begin;
  // perf: pairs gather in a small local buffer, 8 slots of slack for emit_pairs.
  constexpr std::size_t kBuffer = 512;
  uint64_t buffer[kBuffer + 8];
  std::size_t used = 0, passed_by = 0;
  std::size_t strip =
      std::size_t(std::upper_bound(strip_begin.begin(), strip_begin.end(), uint32_t(begin)) -
                  strip_begin.begin() - 1);
  for (std::size_t k = begin; k < end; ++strip) {
    const std::size_t stop = strip_begin[strip + 1] - kChunk;
    t.strip = uint32_t(strip);
    for (; k < std::min(end, stop); ++k) {
      t.hi = s.max[k];
      t.l1 = s.lo1[k];
      t.h1 = s.hi1[k];
      t.l2 = s.lo2[k];
      t.h2 = s.hi2[k];
      t.f = s.first[k];
      t.cat = s.category[k];
      t.msk = s.mask[k];
      t.partner_kinds = partner_kinds(BroadKind(s.kind[k]));
      bool closed = false;
      if constexpr (kClosed) {
        t.x = s.ball_x[k];
        t.y = s.ball_y[k];
        t.z = s.ball_z[k];
        t.r = s.ball_r[k];
        t.run = s.run[k];
        t.shift = s.shift[k];
        closed = t.shift < kOpenShift;
      }
      // perf: candidates in chunks of kChunk with a branch-free test; a chunk may run into
      // the strip's sentinels, which fail it. Sorted keys: once the chunk's last key is past
      // hi, so is every later one.
      for (std::size_t j = k + 1; j < stop; j += kChunk) {
        bool more;
        uint32_t hits = chunk_hits(t, j, more);
        if (kClosed && closed && hits != 0) {
          // The sieve would turn these away (closed_runs.hpp): never written out.
          const uint32_t shut = hits & chunk_shut_out(t, j);
          hits &= ~shut;
          passed_by += uint32_t(std::popcount(shut));
          // perf: in a closed crowd nearly every chunk is left empty; skip its write.
          if (hits == 0) {
            if (!more) break;
            continue;
          }
        }
        used += emit_pairs(hits, body[k], body + j, buffer + used);
        if (used > kBuffer) {
          // The sieve takes the deep pairs as they come: a crowd's are never stored.
          if (deep != nullptr) used = deep->sieve(buffer, used);
          out.insert(out.end(), buffer, buffer + used);
          used = 0;
        }
        if (!more) break;
      }
    }
    k = std::max<std::size_t>(k, strip_begin[strip + 1]);
  }
  if (deep != nullptr) {
    used = deep->sieve(buffer, used);
    if (passed_by != 0) deep->count_taken(passed_by);
  }
  out.insert(out.end(), buffer, buffer + used);
}

}  // namespace

void sweep_strips(const SweepStrips& s, std::size_t begin, std::size_t end, DeepSieve* deep,
                  ScratchVector<uint64_t>& out) {
  if (deep != nullptr && s.shift != nullptr) {
    sweep<true>(s, begin, end, deep, out);
  } else {
    sweep<false>(s, begin, end, deep, out);
  }
}

ELAN_ISA_END
}  // namespace elan::detail
