// SPDX-License-Identifier: MIT
// Sweep-and-prune: boxes sorted by min on the axis of largest spread, order kept between updates
// so the re-sort is an insertion sort of nearly sorted input, then dealt into strips along the
// axis of second spread; the strips' sweep runs in parallel chunks.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "broadphase/closed_runs.hpp"
#include "broadphase/find_pairs.hpp"
#include "broadphase/pair_test.hpp"
#include "broadphase/sweep_kernel.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"

namespace elan::detail {

namespace {

constexpr std::size_t kStatsGrain = 4096;
constexpr std::size_t kSweepGrain = 512;
constexpr std::size_t kDealGrain = 4096;
constexpr std::size_t kPlaneGrain = 4096;
constexpr std::size_t kPlaneRun = 256;
// Switch axis only when another one spreads clearly more, so a scene near a tie does not pay a
// full re-sort every update.
constexpr double kAxisHysteresis = 1.25;
// Insertion sort costs n + inversions; past this many moves per body a full sort is cheaper.
constexpr std::size_t kMaxMovesPerBody = 8;
constexpr uint32_t kSkipAfterFailure = 4;
// Strips twice the mean box size wide: a box lands in one or two. At least 16 boxes per strip on
// average, so sparse scenes do not pay for many empty strips.
constexpr double kStripWidthInBoxes = 2;
constexpr std::size_t kMinBoxesPerStrip = 16;
constexpr std::size_t kStats = 16;  // count, sum[3], sum of squares[3], size[3], min[3], max[3]

const Real* axis_min(const BoundsColumns& b, int axis) {
  return axis == 0 ? b.min_x.data() : axis == 1 ? b.min_y.data() : b.min_z.data();
}
const Real* axis_max(const BoundsColumns& b, int axis) {
  return axis == 0 ? b.max_x.data() : axis == 1 ? b.max_y.data() : b.max_z.data();
}

// Planes are outside the sweep and NaN boxes never overlap: both sort last, as +inf.
Real sweep_key(const BroadphaseInput& in, const Real* mins, uint32_t i) {
  const Real v = mins[i];
  return (in.is_plane[i] || std::isnan(v)) ? std::numeric_limits<Real>::infinity() : v;
}

}  // namespace

// Picks the sweep axis (largest variance of box centres) and the strips on the axis of second
// variance. Returns true when the sweep axis changed (the kept order is then useless).
bool SweepAndPrune::choose_axis(const BroadphaseInput& in) {
  const BoundsColumns& b = *in.bounds;
  const std::size_t n = b.size();
  const std::size_t blocks = block_count(n, kStatsGrain);
  constexpr double kHuge = std::numeric_limits<double>::infinity();
  axis_partials_.resize(blocks * kStats);
  // determinism: block partials in double, summed in block order (rule 3).
  for_blocks(n, kStatsGrain, [&](std::size_t begin, std::size_t end, std::size_t blk) {
    double acc[kStats] = {};
    for (int a = 0; a < 3; ++a) {
      acc[10 + a] = kHuge;
      acc[13 + a] = -kHuge;
    }
    const Real* mins[3] = {b.min_x.data(), b.min_y.data(), b.min_z.data()};
    const Real* maxs[3] = {b.max_x.data(), b.max_y.data(), b.max_z.data()};
    for (std::size_t i = begin; i < end; ++i) {
      if (in.is_plane[i]) continue;
      double c[3], e[3];
      for (int a = 0; a < 3; ++a) {
        c[a] = 0.5 * (double(mins[a][i]) + double(maxs[a][i]));
        e[a] = double(maxs[a][i]) - double(mins[a][i]);
      }
      if (!(std::isfinite(e[0]) && std::isfinite(e[1]) && std::isfinite(e[2]))) continue;
      acc[0] += 1;
      for (int a = 0; a < 3; ++a) {
        acc[1 + a] += c[a];
        acc[4 + a] += c[a] * c[a];
        acc[7 + a] += e[a];
        acc[10 + a] = std::min(acc[10 + a], c[a]);
        acc[13 + a] = std::max(acc[13 + a], c[a]);
      }
    }
    std::copy(acc, acc + kStats, axis_partials_.begin() + std::ptrdiff_t(blk * kStats));
  });
  double acc[kStats] = {};
  for (int a = 0; a < 3; ++a) {
    acc[10 + a] = kHuge;
    acc[13 + a] = -kHuge;
  }
  for (std::size_t blk = 0; blk < blocks; ++blk) {
    const double* p = axis_partials_.data() + blk * kStats;
    for (std::size_t k = 0; k < 10; ++k) acc[k] += p[k];
    for (int a = 0; a < 3; ++a) {
      acc[10 + a] = std::min(acc[10 + a], p[10 + a]);
      acc[13 + a] = std::max(acc[13 + a], p[13 + a]);
    }
  }
  strip_count_ = 1;
  if (acc[0] < 2) return false;
  double var[3];
  for (int a = 0; a < 3; ++a) {
    const double mean = acc[1 + a] / acc[0];
    var[a] = acc[4 + a] / acc[0] - mean * mean;
  }
  int best = axis_;
  for (int a = 0; a < 3; ++a) {
    if (var[a] > var[best]) best = a;
  }
  const bool changed = best != axis_ && var[best] > kAxisHysteresis * var[axis_];
  if (changed) axis_ = best;

  const int a1 = (axis_ + 1) % 3, a2 = (axis_ + 2) % 3;
  strip_axis_ = var[a1] >= var[a2] ? 1 : 2;
  const int sa = strip_axis_ == 1 ? a1 : a2;
  const double spread = acc[13 + sa] - acc[10 + sa];
  const double width = kStripWidthInBoxes * acc[7 + sa] / acc[0];
  if (width > 0 && spread > width) {
    const double most = double(std::max<std::size_t>(1, n / kMinBoxesPerStrip));
    const double count = std::min(std::floor(spread / width) + 1, most);
    strip_count_ = uint32_t(count);
    strip_lo_ = Real(acc[10 + sa]);
    strip_width_ = Real(std::max(width, spread / count));
  }
  return changed;
}

void SweepAndPrune::sort_full(const BroadphaseInput& in, StepScratch& scratch) {
  const std::size_t n = in.bounds->size();
  const Real* mins = axis_min(*in.bounds, axis_);
  order_.resize(n);
  sorted_min_.resize(n);
  // perf: the sort runs on (rank, index) words, the rank a monotonic 32-bit quantisation of the
  // key over the scene's finite range, so the parallel sort's top digit spreads the boxes
  // evenly. Distinct keys that share a rank are rare; the insertion pass below puts them in
  // order, and the index in the low bits breaks ties, so the order is a function of the boxes.
  const std::size_t blocks = block_count(n, kStatsGrain);
  range_partials_.resize(2 * blocks);
  constexpr double kHuge = std::numeric_limits<double>::infinity();
  // determinism: per-block min/max, combined in block order (rule 3, exact anyway).
  for_blocks(n, kStatsGrain, [&](std::size_t begin, std::size_t end, std::size_t blk) {
    double lo = kHuge, hi = -kHuge;
    for (std::size_t i = begin; i < end; ++i) {
      const double v = sweep_key(in, mins, uint32_t(i));
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
    range_partials_[2 * blk] = lo;
    range_partials_[2 * blk + 1] = hi;
  });
  double lo = kHuge, hi = -kHuge;
  for (std::size_t blk = 0; blk < blocks; ++blk) {
    lo = std::min(lo, range_partials_[2 * blk]);
    hi = std::max(hi, range_partials_[2 * blk + 1]);
  }
  constexpr uint64_t kTopRank = 0xFFFFFFFFu;  // +inf; -inf ranks 0 with the smallest key
  const double scale = hi > lo ? double(kTopRank - 1) / (hi - lo) : 0.0;
  const int index_bits = int(std::bit_width(std::max<std::size_t>(n, 2) - 1));
  const uint64_t index_mask = (uint64_t{1} << index_bits) - 1;
  sort_keys_.resize(n);
  // determinism: indexed writes (rule 1).
  for_blocks(n, kStatsGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      const double v = sweep_key(in, mins, uint32_t(i));
      const uint64_t rank = std::isfinite(v) ? std::min(uint64_t((v - lo) * scale), kTopRank - 1)
                            : v > 0          ? kTopRank
                                             : 0;
      sort_keys_[i] = (rank << index_bits) | i;
    }
  });
  sort_keys(sort_keys_, (kTopRank << index_bits) | index_mask, key_sort_, &scratch);
  // determinism: indexed writes (rule 1).
  for_blocks(n, kStatsGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t k = begin; k < end; ++k) {
      order_[k] = uint32_t(sort_keys_[k] & index_mask);
      sorted_min_[k] = sweep_key(in, mins, order_[k]);
    }
  });
  if (!sort_incremental()) {
    // Reached only when very many distinct keys share ranks: a plain comparison sort.
    for (uint32_t i = 0; i < n; ++i) order_[i] = i;
    std::sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) {
      const Real ka = sweep_key(in, mins, a), kb = sweep_key(in, mins, b);
      return ka < kb || (ka == kb && a < b);
    });
    for (std::size_t k = 0; k < n; ++k) sorted_min_[k] = sweep_key(in, mins, order_[k]);
  }
}

// Insertion sort of the refreshed keys in last update's order. Returns false (order partly
// moved, still a permutation) when the input turned out too far from sorted.
bool SweepAndPrune::sort_incremental() {
  const std::size_t n = order_.size();
  const std::size_t budget = kMaxMovesPerBody * n;
  std::size_t moves = 0;
  Real* key = sorted_min_.data();
  uint32_t* ord = order_.data();
  for (std::size_t k = 1; k < n; ++k) {
    const Real v = key[k];
    if (!(v < key[k - 1])) continue;
    const uint32_t id = ord[k];
    std::size_t j = k;
    while (j > 0 && v < key[j - 1]) {
      key[j] = key[j - 1];
      ord[j] = ord[j - 1];
      --j;
    }
    key[j] = v;
    ord[j] = id;
    moves += k - j;
    if (moves > budget) return false;
  }
  return true;
}

// Gathers the sorted boxes and deals them into strips in sweep order (a stable counting sort),
// so every strip comes out sorted without a sort of its own. Planes and boxes with a NaN bound
// never overlap anything and get no entry.
void SweepAndPrune::deal_strips(const BroadphaseInput& in, StepScratch& scratch) {
  const std::size_t n = order_.size();
  const std::size_t strips = strip_count_;
  // determinism: the block layout is a function of n and the strip count alone (rule 2); blocks
  // at least 4 boxes per strip long keep the per-block counts below n/4.
  const std::size_t grain = std::max(kDealGrain, 4 * strips);
  const std::size_t blocks = block_count(n, grain);
  const BoundsColumns& b = *in.bounds;
  const int a1 = (axis_ + 1) % 3, a2 = (axis_ + 2) % 3;
  const Real *lo0 = axis_min(b, axis_), *hi0 = axis_max(b, axis_);
  const Real *lo1 = axis_min(b, a1), *hi1 = axis_max(b, a1);
  const Real *lo2 = axis_min(b, a2), *hi2 = axis_max(b, a2);
  take_from(sorted_max_, scratch, n);
  take_from(sorted_lo1_, scratch, n);
  take_from(sorted_hi1_, scratch, n);
  take_from(sorted_lo2_, scratch, n);
  take_from(sorted_hi2_, scratch, n);
  take_from(sorted_strips_, scratch, 2 * n);
  closed_count_ = 0;
  if (in.deep != nullptr && in.deep->balls().size() == n) {
    take_from(body_order_, scratch, n);
    take_from(body_shift_, scratch, n);
    closed_count_ =
        find_closed_runs(in, in.deep->balls(), in.deep->crowded(), body_order_, body_shift_);
  }
  // Room for the most any spread of these n boxes can need (blocks * strips <= n / 4 + strips,
  // strips <= n / kMinBoxesPerStrip), so a scene that spreads out does not grow it in a warm step.
  const std::size_t most_strips = n / kMinBoxesPerStrip + 1;
  if (deal_counts_.capacity() < n / 4 + most_strips + 1)
    deal_counts_.reserve(n / 4 + most_strips + 1);
  if (strip_begin_.capacity() < most_strips + 1) strip_begin_.reserve(most_strips + 1);
  deal_counts_.assign(blocks * strips, 0);
  // The rest of each box in sweep order, its strips, and per block the entries per strip.
  // determinism: indexed writes, and each block counts into its own row (rule 1).
  for_blocks(n, grain, [&](std::size_t begin, std::size_t end, std::size_t blk) {
    uint32_t* count = deal_counts_.data() + blk * strips;
    for (std::size_t k = begin; k < end; ++k) {
      const uint32_t i = order_[k];
      const Real v[5] = {hi0[i], lo1[i], hi1[i], lo2[i], hi2[i]};
      sorted_max_[k] = v[0];
      sorted_lo1_[k] = v[1];
      sorted_hi1_[k] = v[2];
      sorted_lo2_[k] = v[3];
      sorted_hi2_[k] = v[4];
      // Planes are paired in their own pass and a NaN box never overlaps: no entry.
      const bool valid =
          !(in.is_plane[i] || std::isnan(lo0[i]) || std::isnan(v[0]) || std::isnan(v[1]) ||
            std::isnan(v[2]) || std::isnan(v[3]) || std::isnan(v[4]));
      const Real slo = strip_axis_ == 1 ? v[1] : v[3], shi = strip_axis_ == 1 ? v[2] : v[4];
      const uint32_t s0 = valid ? strip_of(slo) : 1, s1 = valid ? strip_of(shi) : 0;
      sorted_strips_[2 * k] = s0;
      sorted_strips_[2 * k + 1] = s1;
      for (uint32_t s = s0; s <= s1; ++s) ++count[s];
    }
  });
  // Strip-major, block-minor offsets: block b's entries in a strip follow block b-1's, so each
  // strip keeps sweep order.
  strip_begin_.resize(strips + 1);
  const std::size_t entries = bin_major_offsets(deal_counts_.data(), blocks, strips,
                                                strip_begin_.data(), uint32_t(kStripPad));
  take_pair_blocks(in, entries, scratch);
  take_from(entry_min_, scratch, entries);
  take_from(entry_max_, scratch, entries);
  take_from(entry_lo1_, scratch, entries);
  take_from(entry_hi1_, scratch, entries);
  take_from(entry_lo2_, scratch, entries);
  take_from(entry_hi2_, scratch, entries);
  take_from(entry_body_, scratch, entries);
  take_from(entry_first_, scratch, entries);
  take_from(entry_kind_, scratch, entries);
  take_from(entry_category_, scratch, entries);
  take_from(entry_mask_, scratch, entries);
  const bool closed = closed_count_ != 0;
  if (closed) {
    take_from(entry_ball_x_, scratch, entries);
    take_from(entry_ball_y_, scratch, entries);
    take_from(entry_ball_z_, scratch, entries);
    take_from(entry_ball_r_, scratch, entries);
    take_from(entry_run_, scratch, entries);
    take_from(entry_shift_, scratch, entries);
  }
  const DeepBall* balls = in.deep != nullptr ? in.deep->balls().data() : nullptr;
  // determinism: every block writes the entries its offsets reserve (rule 1).
  for_blocks(n, grain, [&](std::size_t begin, std::size_t end, std::size_t blk) {
    uint32_t* cursor = deal_counts_.data() + blk * strips;
    for (std::size_t k = begin; k < end; ++k) {
      const uint32_t s0 = sorted_strips_[2 * k], s1 = sorted_strips_[2 * k + 1];
      const uint32_t i = order_[k];
      for (uint32_t s = s0; s <= s1; ++s) {
        const uint32_t e = cursor[s]++;
        entry_min_[e] = sorted_min_[k];
        entry_max_[e] = sorted_max_[k];
        entry_lo1_[e] = sorted_lo1_[k];
        entry_hi1_[e] = sorted_hi1_[k];
        entry_lo2_[e] = sorted_lo2_[k];
        entry_hi2_[e] = sorted_hi2_[k];
        entry_body_[e] = i;
        entry_first_[e] = s0;
        entry_kind_[e] = in.kind[i];
        const BodyTraits& traits = in.trait_table[in.traits[i]];
        entry_category_[e] = traits.category;
        entry_mask_[e] = traits.mask;
        if (closed) {
          entry_ball_x_[e] = balls[i].x;
          entry_ball_y_[e] = balls[i].y;
          entry_ball_z_[e] = balls[i].z;
          entry_ball_r_[e] = balls[i].r;
          entry_run_[e] = balls[i].run;
          entry_shift_[e] = body_shift_[i];
        }
      }
    }
  });
  constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();
  for (std::size_t s = 0; s < strips; ++s) {
    for (std::size_t e = strip_begin_[s + 1] - kStripPad; e < strip_begin_[s + 1]; ++e) {
      entry_min_[e] = std::numeric_limits<Real>::infinity();
      entry_max_[e] = kNaN;
      entry_lo1_[e] = kNaN;
      entry_hi1_[e] = kNaN;
      entry_lo2_[e] = kNaN;
      entry_hi2_[e] = kNaN;
      entry_body_[e] = 0;
      entry_first_[e] = 0;
      entry_kind_[e] = 0;
      entry_category_[e] = 0;
      entry_mask_[e] = 0;
      if (closed) {
        entry_ball_x_[e] = kNaN;
        entry_ball_y_[e] = kNaN;
        entry_ball_z_[e] = kNaN;
        entry_ball_r_[e] = 0;
        entry_run_[e] = 0;
        entry_shift_[e] = kOpenShift;
      }
    }
  }
}

void SweepAndPrune::take_pair_blocks(const BroadphaseInput& in, std::size_t entries,
                                     StepScratch& scratch) {
  const std::size_t n = in.bounds->size();
  planes_.clear();
  for (uint32_t i = 0; i < n; ++i) {
    if (in.is_plane[i]) planes_.push_back(i);
  }
  sweep_blocks_ = block_count(entries, kSweepGrain);
  plane_blocks_ = planes_.empty() ? 0 : block_count(n, kPlaneGrain);
  const std::size_t blocks = sweep_blocks_ + plane_blocks_;
  // Each block's buffer starts with room for a quarter more than the block found last update, so
  // once the scene has settled no buffer grows (a grown one leaves its old bytes unused in the
  // scratch until the phase ends).
  if (block_pairs_.size() < blocks) block_pairs_.resize(blocks);
  block_room_.resize(block_pairs_.size());
  for (std::size_t t = 0; t < block_pairs_.size(); ++t) {
    take_from(block_pairs_[t], scratch);
    if (t < blocks) block_pairs_[t].reserve(block_room_[t] + block_room_[t] / 4 + 16);
  }
}

void SweepAndPrune::release_entries() {
  // The last taken first, so that the scratch's next buffers start where the entries did.
  release(entry_shift_);
  release(entry_run_);
  release(entry_ball_r_);
  release(entry_ball_z_);
  release(entry_ball_y_);
  release(entry_ball_x_);
  release(entry_mask_);
  release(entry_category_);
  release(entry_kind_);
  release(entry_first_);
  release(entry_body_);
  release(entry_hi2_);
  release(entry_lo2_);
  release(entry_hi1_);
  release(entry_lo1_);
  release(entry_max_);
  release(entry_min_);
}

void SweepAndPrune::release_update_buffers() {
  for (std::size_t t = block_pairs_.size(); t-- > 0;) release(block_pairs_[t]);
  release(body_shift_);
  release(body_order_);
  release(sorted_strips_);
  release(sorted_hi2_);
  release(sorted_lo2_);
  release(sorted_hi1_);
  release(sorted_lo1_);
  release(sorted_max_);
}

template <class Pairs>
void SweepAndPrune::find_pairs(const BroadphaseInput& in, Pairs& out_pairs, StepScratch& scratch) {
  const BoundsColumns& b = *in.bounds;
  const std::size_t n = b.size();

  const bool axis_changed = choose_axis(in);
  bool sorted = false;
  if (!axis_changed && order_.size() == n) {
    const Real* mins = axis_min(b, axis_);
    // determinism: indexed writes (rule 1).
    for_blocks(n, kStatsGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t k = begin; k < end; ++k) sorted_min_[k] = sweep_key(in, mins, order_[k]);
    });
    // perf: after the insertion sort gave up, the next few updates go straight to the full
    // sort rather than paying for the attempt again.
    if (skip_incremental_ == 0) {
      sorted = sort_incremental();
      if (!sorted) skip_incremental_ = kSkipAfterFailure;
    } else {
      --skip_incremental_;
    }
  }
  if (!sorted) sort_full(in, scratch);

  deal_strips(in, scratch);

  const std::size_t entries = entry_body_.size();

  // Each chunk scans forward from its own entries to the end of their strip, possibly past the
  // chunk's end.
  // determinism: one buffer per chunk, joined in chunk order, then sorted (rule 1).
  SweepStrips strips{entry_min_.data(),  entry_max_.data(),   entry_lo1_.data(),
                     entry_hi1_.data(),  entry_lo2_.data(),   entry_hi2_.data(),
                     entry_body_.data(), entry_first_.data(), entry_category_.data(),
                     entry_mask_.data(), entry_kind_.data(),  strip_begin_};
  if (closed_count_ != 0) {
    strips.ball_x = entry_ball_x_.data();
    strips.ball_y = entry_ball_y_.data();
    strips.ball_z = entry_ball_z_.data();
    strips.ball_r = entry_ball_r_.data();
    strips.run = entry_run_.data();
    strips.shift = entry_shift_.data();
  }
  const SweepKernel sweep = sweep_kernel(in.simd);
  for_blocks(entries, kSweepGrain, [&](std::size_t begin, std::size_t end, std::size_t blk) {
    sweep(strips, begin, end, in.deep, block_pairs_[blk]);
  });

  // Planes against every other body; a plane-plane pair once, from the lower index.
  if (plane_blocks_ != 0) {
    for_blocks(n, kPlaneGrain, [&](std::size_t begin, std::size_t end, std::size_t blk) {
      ScratchVector<uint64_t>& out = block_pairs_[sweep_blocks_ + blk];
      const Real *min_x = b.min_x.data(), *min_y = b.min_y.data(), *min_z = b.min_z.data();
      const Real *max_x = b.max_x.data(), *max_y = b.max_y.data(), *max_z = b.max_z.data();
      for (uint32_t p : planes_) {
        const Real ax = min_x[p], ay = min_y[p], az = min_z[p];
        const Real bx = max_x[p], by = max_y[p], bz = max_z[p];
        for (std::size_t j0 = begin; j0 < end; j0 += kPlaneRun) {
          const std::size_t m = std::min(kPlaneRun, end - j0);
          // perf: branch-free overlap test over a run of bodies, so it vectorises; the rare
          // hits then take the exact rule of boxes_overlap + accept_pair.
          alignas(64) uint8_t hit[kPlaneRun];
#pragma omp simd
          for (std::size_t k = 0; k < m; ++k) {
            const std::size_t j = j0 + k;
            hit[k] = uint8_t((min_x[j] <= bx) & (ax <= max_x[j]) & (min_y[j] <= by) &
                             (ay <= max_y[j]) & (min_z[j] <= bz) & (az <= max_z[j]));
          }
          for (std::size_t k = 0; k < m; ++k) {
            if (!hit[k]) continue;
            const uint32_t q = uint32_t(j0 + k);
            if (q == p || (in.is_plane[q] && q < p)) continue;
            if (accept_pair(in, p, q)) out.push_back(make_pair_key(p, q));
          }
        }
      }
    });
  }

  // memory: the entries are dead once swept. Taken after the pair blocks, they go back first, so
  // the sort and the pair list it writes reuse their bytes instead of adding to the peak.
  release_entries();
  // The sweep yields each pair once and the plane pass covers only pairs with a plane, so the
  // sorted list is already unique.
  const uint64_t max_key = n < 2 ? 0 : make_pair_key(uint32_t(n - 2), uint32_t(n - 1));
  sort_key_blocks(block_pairs_, max_key, out_pairs, pair_sort_, &scratch);
  for (std::size_t t = 0; t < sweep_blocks_ + plane_blocks_; ++t) {
    block_room_[t] = uint32_t(block_pairs_[t].size());
  }
  release_update_buffers();
}
template void SweepAndPrune::find_pairs(const BroadphaseInput&, std::vector<uint64_t>&,
                                        StepScratch&);
template void SweepAndPrune::find_pairs(const BroadphaseInput&, ScratchVector<uint64_t>&,
                                        StepScratch&);

std::size_t SweepAndPrune::heap_bytes() const {
  using detail::heap_bytes;
  return heap_bytes(order_) + heap_bytes(sorted_min_) + heap_bytes(sorted_max_) +
         heap_bytes(sorted_lo1_) + heap_bytes(sorted_hi1_) + heap_bytes(sorted_lo2_) +
         heap_bytes(sorted_hi2_) + heap_bytes(entry_min_) + heap_bytes(entry_max_) +
         heap_bytes(entry_lo1_) + heap_bytes(entry_hi1_) + heap_bytes(entry_lo2_) +
         heap_bytes(entry_hi2_) + heap_bytes(entry_body_) + heap_bytes(entry_first_) +
         heap_bytes(entry_kind_) + heap_bytes(entry_category_) + heap_bytes(entry_mask_) +
         heap_bytes(body_order_) + heap_bytes(body_shift_) + heap_bytes(entry_ball_x_) +
         heap_bytes(entry_ball_y_) + heap_bytes(entry_ball_z_) + heap_bytes(entry_ball_r_) +
         heap_bytes(entry_run_) + heap_bytes(entry_shift_) + heap_bytes(strip_begin_) +
         heap_bytes(sorted_strips_) + heap_bytes(deal_counts_) + heap_bytes(axis_partials_) +
         heap_bytes(planes_) + heap_bytes(block_pairs_) + heap_bytes(sort_keys_) +
         heap_bytes(range_partials_) + heap_bytes(key_sort_) + heap_bytes(pair_sort_) +
         heap_bytes(block_room_) + (own_scratch_ ? own_scratch_->heap_bytes() : 0);
}

}  // namespace elan::detail
