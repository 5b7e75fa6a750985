// SPDX-License-Identifier: MIT
// The sweep of sweep-and-prune over its strips (find_pairs.hpp, SweepAndPrune): the broadphase's
// hot loop, compiled once per instruction set in a dispatching build (core/base/isa.hpp) and
// chosen per call by the input's SIMD path. Its tests are exact comparisons, so every path finds
// the same pairs.
#pragma once

#include <cstdint>
#include <span>

#include "core/base/isa.hpp"
#include "core/base/step_scratch.hpp"
#include "elan/defs.hpp"

namespace elan::detail {

class DeepSieve;

// The entries dealt into strips, as columns (SweepAndPrune's entry_*): strip s holds entries
// [strip_begin[s], strip_begin[s + 1] - kStripPad) in sweep order, then kStripPad sentinels.
struct SweepStrips {
  const Real *min, *max, *lo1, *hi1, *lo2, *hi2;
  const uint32_t* body;
  const uint32_t* first;  // strip of the box's low end on the strip axis
  const uint32_t *category, *mask;
  const uint8_t* kind;  // BroadKind
  std::span<const uint32_t> strip_begin;
  // With a deep sieve that has closed bodies (closed_runs.hpp), else null: the entries' inner
  // balls (DeepBall x, y, z, r), runs and closed levels as shifts. A shut-out pair is then passed
  // by in the kernel, counted as taken, and never written out.
  const Real *ball_x = nullptr, *ball_y = nullptr, *ball_z = nullptr, *ball_r = nullptr;
  const uint32_t *run = nullptr, *shift = nullptr;
};

// Appends to `out` the pair keys of each entry in [begin, end) with the later entries of its
// strip that overlap it on all three axes, belong to this strip (the pair's first strip is this
// one), and pass should_pair and the filter; with a sieve, only those it does not take.
using SweepKernel = void (*)(const SweepStrips& strips, std::size_t begin, std::size_t end,
                             DeepSieve* deep, ScratchVector<uint64_t>& out);

ELAN_ISA_BEGIN
void sweep_strips(const SweepStrips& strips, std::size_t begin, std::size_t end, DeepSieve* deep,
                  ScratchVector<uint64_t>& out);
ELAN_ISA_END

// The kernel of `path` (Best: process_simd_path()); the baseline one for a path this build lacks.
SweepKernel sweep_kernel(SimdPath path);

}  // namespace elan::detail
