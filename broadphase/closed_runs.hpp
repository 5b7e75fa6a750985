// SPDX-License-Identifier: MIT
// Closed sets: the deep pairs the sieve would turn away, known before the finder meets them.
//
// The sieve (deep_sieve.hpp) ranks a body's deep partners level by level: first those of its run
// (level 1, rank below 2^32), then those of its run's group of level 2 (8 runs), of level 3 (64
// runs), and so on, each level's ranks below the next one's. A body that has at least kCandidates
// deep partners within its group of level C, each a pair the finder reports (boxes overlapping,
// kinds and filters accepting), keeps kCandidates of them whatever else it meets: no partner from
// outside that group can enter its set. Its set is closed at level C. A deep pair of two bodies
// closed at levels Ca and Cb whose runs are in different groups of level max(Ca, Cb) enters
// neither set, so a finder may pass it by without offering it, only counting it as taken
// (DeepSieve::count_taken): the sieve's candidates, the stored pairs and whether a crowd was found
// are the same as if it had been offered.
//
// Why: 10,000 boxes spawned at one point overlap in 50 million pairs, nearly all deep; the sweep's
// kernel (sweep_kernel.hpp) tests the shut-out ones eight at a time in its vector lanes and never
// writes them out, where the sieve took them one by one (a key, a hash, two compares each). Bodies
// of an ordinary scene are never closed: a body with eight deep partners is a crowd's.
#pragma once

#include <cstdint>
#include <span>

#include "broadphase/deep_sieve.hpp"
#include "broadphase/find_pairs.hpp"

namespace elan::detail {

// A body's closed level as the shift of its run's number that gives its group at that level
// (kLevelShift (C - 1)); kOpenShift: not closed.
inline constexpr uint32_t kOpenShift = 32;
// The highest level a body is closed at: its group has kRun 8^(kMaxClosedLevel - 1) = 576 bodies,
// so finding a body's closed level costs at most 575 deep tests.
inline constexpr uint32_t kMaxClosedLevel = 3;

// shift[i] gets body i's closed level as a shift, or kOpenShift. Levels above 1 are looked for
// only for bodies with deepen[i] != 0 (an empty span: none; a hint, as DeepSieve::crowded:
// the sieve's result is the same whichever bodies are found closed). Runs as prepare_deep_sieve
// makes them (DeepBall::run the ordinal among the bodies with r > 0, over kRun); with others,
// nothing is closed. `order` is scratch, one entry per body. Returns the closed bodies' count.
// Parallel over fixed blocks of bodies, each writing its own (rule 1).
std::size_t find_closed_runs(const BroadphaseInput& in, std::span<const DeepBall> balls,
                             std::span<const uint8_t> deepen, std::span<uint32_t> order,
                             std::span<uint32_t> shift);

// Whether the sieve would turn the deep pair of bodies of runs ra, rb closed at shifts sa, sb away:
// their runs differ in the bits above the larger shift.
inline bool shut_out(uint32_t ra, uint32_t sa, uint32_t rb, uint32_t sb) {
  const uint32_t s = sa > sb ? sa : sb;
  return s < kOpenShift && ((ra ^ rb) >> s) != 0;
}

}  // namespace elan::detail
