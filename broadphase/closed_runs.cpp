// SPDX-License-Identifier: MIT
// find_closed_runs() (closed_runs.hpp).
#include "broadphase/closed_runs.hpp"

#include <algorithm>

#include "broadphase/pair_test.hpp"
#include "core/base/parallel.hpp"

namespace elan::detail {

namespace {

constexpr uint32_t kRun = DeepSieve::kRun;
constexpr uint32_t kWanted = DeepSieve::kCandidates;
constexpr std::size_t kClosedGrain = 512;

// The ordinals [begin, end) of the bodies with r > 0 in the group of level `level` of ordinal o's
// run, clipped to the m ordinals there are.
struct Range {
  std::size_t begin, end;
};
Range group_of(std::size_t o, uint32_t level, std::size_t m) {
  const std::size_t s = kLevelShift * (level - 1);
  const std::size_t first_run = ((o / kRun) >> s) << s;
  const std::size_t begin = first_run * kRun;
  return {begin, std::min(m, begin + (kRun << s))};
}

}  // namespace

std::size_t find_closed_runs(const BroadphaseInput& in, std::span<const DeepBall> balls,
                             std::span<const uint8_t> deepen, std::span<uint32_t> order,
                             std::span<uint32_t> shift) {
  std::fill(shift.begin(), shift.end(), kOpenShift);
  // The bodies with r > 0 in index order; their runs must be their ordinals over kRun.
  std::size_t m = 0;
  for (uint32_t i = 0; i < balls.size(); ++i) {
    if (!(balls[i].r > 0)) continue;
    if (balls[i].run != m / kRun) {
      std::fill(shift.begin(), shift.end(), kOpenShift);
      return 0;
    }
    order[m++] = i;
  }
  const auto paired_deep = [&](uint32_t a, uint32_t b) {
    return deep_balls_inline(balls[a], balls[b]) && boxes_overlap(*in.bounds, a, b) &&
           accept_pair(in, a, b);
  };
  // determinism: each block writes its own bodies' shifts (rule 1).
  for_blocks(m, kClosedGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t o = begin; o < end; ++o) {
      const uint32_t a = order[o];
      const uint32_t top = !deepen.empty() && deepen[a] != 0 ? kMaxClosedLevel : 1;
      uint32_t count = 0;
      Range seen{o, o};
      for (uint32_t level = 1; level <= top && count < kWanted; ++level) {
        const Range g = group_of(o, level, m);
        // perf: level 1 alone (no hint) stops at the first run-mate apart, as in an ordinary
        // scene the first one is.
        for (std::size_t p = g.begin; p < g.end && count < kWanted; ++p) {
          if (p == o || (p >= seen.begin && p < seen.end)) continue;
          if (paired_deep(a, order[p])) {
            ++count;
          } else if (top == 1) {
            break;
          }
        }
        seen = g;
        if (count >= kWanted) shift[a] = kLevelShift * (level - 1);
      }
    }
  });
  std::size_t found = 0;
  for (std::size_t o = 0; o < m; ++o) found += shift[order[o]] != kOpenShift ? 1 : 0;
  return found;
}

}  // namespace elan::detail
