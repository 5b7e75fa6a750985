// SPDX-License-Identifier: MIT
// Closed runs: the deep pairs the sieve would turn away, known before the finder meets them.
//
// The sieve (deep_sieve.hpp) ranks a body's deep partners first by its run of kRun bodies (rank
// = index difference, below 2^32) and then by a hash (rank at least 2^32). A body whose run has
// kRun members, each deep with it and a pair the finder reports (boxes overlapping, kinds and
// filters accepting), has kCandidates = kRun - 1 partners of its own run: its set is those, and
// no partner from another run can enter it. Its set is closed. A deep pair of two closed bodies
// of different runs enters neither set, so a finder may pass it by without offering it, only
// counting it as taken (DeepSieve::count_taken): the sieve's candidates, the stored pairs and
// whether a crowd was found are the same as if it had been offered.
//
// Why: 10,000 boxes spawned at one point overlap in 50 million pairs, all deep and all between
// closed bodies in the first steps; the sweep's kernel (sweep_kernel.hpp) tests them eight at a
// time in its vector lanes and never writes them out, where the sieve took them one by one (a
// key, a hash, two compares each). Bodies of an ordinary scene are never closed: a body with
// eight deep partners is a crowd's.
#pragma once

#include <cstdint>
#include <span>

#include "broadphase/deep_sieve.hpp"
#include "broadphase/find_pairs.hpp"

namespace elan::detail {

// closed[i] gets body i's run (DeepBall::run) when its set is closed, else kOpenRun. Runs as
// prepare_deep_sieve makes them (each run's bodies consecutive among those with r > 0, runs in
// increasing order); balls whose runs are otherwise close nothing. Returns the closed bodies'
// count. Serial: one deep test for most bodies of an ordinary scene, at most kRun - 1 for any.
inline constexpr uint32_t kOpenRun = 0xFFFFFFFFu;
std::size_t find_closed_runs(const BroadphaseInput& in, std::span<const DeepBall> balls,
                             std::span<uint32_t> closed);

// Whether the sieve would turn the deep pair of bodies with closed[] values ca and cb away.
inline bool shut_out(uint32_t ca, uint32_t cb) {
  return ca != kOpenRun && cb != kOpenRun && ca != cb;
}

}  // namespace elan::detail
