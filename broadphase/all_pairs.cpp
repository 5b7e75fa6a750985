// SPDX-License-Identifier: MIT
// All-pairs broadphase: every box tested against every other, in parallel over square tiles of
// the pair space so one task streams two short runs of boxes from cache.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "broadphase/find_pairs.hpp"
#include "broadphase/pair_test.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"

namespace elan::detail {

namespace {

// determinism: the tile edge is a function of n alone (rule 2). Small scenes get small tiles so
// there are enough tasks to share; large ones get tiles whose j-run (6 columns x 256 x 4 bytes)
// stays in L1 while the i-loop passes over it.
std::size_t tile_edge(std::size_t n) {
  return n <= 4096 ? 64 : 256;
}

// Tiles (bi, bj) with bi <= bj, numbered row by row: row bi starts at bi*nb - bi*(bi-1)/2.
std::size_t row_start(std::size_t bi, std::size_t nb) {
  return bi * nb - bi * (bi - 1) / 2;
}

void tile_of(std::size_t t, std::size_t nb, std::size_t& bi, std::size_t& bj) {
  std::size_t lo = 0, hi = nb;  // largest bi with row_start(bi) <= t
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    if (row_start(mid, nb) <= t) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  bi = lo;
  bj = bi + (t - row_start(bi, nb));
}

constexpr std::size_t kMaxTile = 256;

void scan_tile(const BroadphaseInput& in, std::size_t i0, std::size_t i1, std::size_t j0,
               std::size_t j1, ScratchVector<uint64_t>& out) {
  const BoundsColumns& b = *in.bounds;
  const Real* min_x = b.min_x.data();
  const Real* min_y = b.min_y.data();
  const Real* min_z = b.min_z.data();
  const Real* max_x = b.max_x.data();
  const Real* max_y = b.max_y.data();
  const Real* max_z = b.max_z.data();
  alignas(64) uint8_t hit[kMaxTile + 8];
  for (std::size_t i = i0; i < i1; ++i) {
    const std::size_t jb = std::max(j0, i + 1);  // diagonal tiles: only j > i
    if (jb >= j1) continue;
    const std::size_t m = j1 - jb;
    const std::size_t row = out.size();
    const Real ax = min_x[i], ay = min_y[i], az = min_z[i];
    const Real bx = max_x[i], by = max_y[i], bz = max_z[i];
    // perf: branch-free test over the whole j-run, so the loop vectorises; hits are rare.
#pragma omp simd
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t j = jb + k;
      hit[k] = uint8_t((min_x[j] <= bx) & (ax <= max_x[j]) & (min_y[j] <= by) & (ay <= max_y[j]) &
                       (min_z[j] <= bz) & (az <= max_z[j]));
    }
    std::memset(hit + m, 0, 8);
    for (std::size_t k = 0; k < m; k += 8) {
      uint64_t word;
      std::memcpy(&word, hit + k, 8);
      if (word == 0) continue;
      for (std::size_t q = k; q < std::min(m, k + 8); ++q) {
        const uint32_t j = uint32_t(jb + q);
        if (hit[q] && accept_pair(in, uint32_t(i), j)) out.push_back(make_pair_key(uint32_t(i), j));
      }
    }
    // The sieve takes the row's deep pairs as they come: a crowd's are never all stored.
    if (in.deep != nullptr) {
      out.resize(row + in.deep->sieve(out.data() + row, out.size() - row));
    }
  }
}

}  // namespace

template <class Pairs>
void AllPairs::find_pairs(const BroadphaseInput& in, Pairs& out_pairs) {
  const std::size_t n = in.bounds->size();
  const std::size_t edge = tile_edge(n);
  const std::size_t nb = block_count(n, edge);
  const std::size_t tiles = nb * (nb + 1) / 2;
  // perf: buffers only grow, so after warm-up an update allocates nothing.
  if (block_pairs_.size() < tiles) block_pairs_.resize(tiles);
  for (std::size_t t = tiles; t < block_pairs_.size(); ++t) block_pairs_[t].clear();

  // determinism: one output buffer per tile, joined in tile order, then sorted (rule 1).
  for_blocks(tiles, 1, [&](std::size_t t, std::size_t, std::size_t) {
    std::size_t bi, bj;
    tile_of(t, nb, bi, bj);
    ScratchVector<uint64_t>& out = block_pairs_[t];
    out.clear();
    scan_tile(in, bi * edge, std::min(n, (bi + 1) * edge), bj * edge, std::min(n, (bj + 1) * edge),
              out);
  });
  const uint64_t max_key = n < 2 ? 0 : make_pair_key(uint32_t(n - 2), uint32_t(n - 1));
  sort_key_blocks(block_pairs_, max_key, out_pairs, pair_sort_);
}
template void AllPairs::find_pairs(const BroadphaseInput&, std::vector<uint64_t>&);
template void AllPairs::find_pairs(const BroadphaseInput&, ScratchVector<uint64_t>&);

std::size_t AllPairs::heap_bytes() const {
  return detail::heap_bytes(block_pairs_) + detail::heap_bytes(pair_sort_);
}

}  // namespace elan::detail
