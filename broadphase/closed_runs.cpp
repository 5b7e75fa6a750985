// SPDX-License-Identifier: MIT
// find_closed_runs() (closed_runs.hpp).
#include "broadphase/closed_runs.hpp"

#include <algorithm>

#include "broadphase/pair_test.hpp"

namespace elan::detail {

namespace {

constexpr uint32_t kRun = DeepSieve::kRun;

// Marks the members of one run that are deep with, and paired with, every other member.
std::size_t close_run(const BroadphaseInput& in, std::span<const DeepBall> balls,
                      const uint32_t* members, uint32_t count, std::span<uint32_t> closed) {
  if (count != kRun) return 0;
  std::size_t found = 0;
  for (uint32_t p = 0; p < kRun; ++p) {
    const uint32_t a = members[p];
    bool all = true;
    // perf: in an ordinary scene the first run-mate is already apart.
    for (uint32_t q = 0; q < kRun && all; ++q) {
      const uint32_t b = members[q];
      all = q == p || (deep_balls_inline(balls[a], balls[b]) && boxes_overlap(*in.bounds, a, b) &&
                       accept_pair(in, a, b));
    }
    if (all) {
      closed[a] = balls[a].run;
      ++found;
    }
  }
  return found;
}

}  // namespace

std::size_t find_closed_runs(const BroadphaseInput& in, std::span<const DeepBall> balls,
                             std::span<uint32_t> closed) {
  std::fill(closed.begin(), closed.end(), kOpenRun);
  uint32_t members[kRun] = {};
  uint32_t count = 0, run = 0;
  bool ordered = true;
  std::size_t found = 0;
  for (uint32_t i = 0; i < balls.size(); ++i) {
    if (!(balls[i].r > 0)) continue;
    if (count > 0 && balls[i].run != run) {
      ordered = ordered && balls[i].run > run;
      found += close_run(in, balls, members, count, closed);
      count = 0;
    }
    run = balls[i].run;
    // A run of more than kRun bodies (not prepare_deep_sieve's) is never closed.
    if (count < kRun) members[count] = i;
    count = std::min(count + 1, kRun + 1);
  }
  found += close_run(in, balls, members, count, closed);
  // A run met in two places has members this pass did not see together: nothing is closed.
  if (!ordered) {
    std::fill(closed.begin(), closed.end(), kOpenRun);
    return 0;
  }
  return found;
}

}  // namespace elan::detail
