// SPDX-License-Identifier: MIT
// color_contacts(): the solver's groups and their colourings (see color_contacts.hpp).
#include "solver/color_contacts.hpp"

#include <algorithm>
#include <cassert>

#include "core/base/grow.hpp"

namespace elan::detail {

ColorStats color_contacts(const BodyStore& bodies, std::span<ManifoldHead> contacts,
                          [[maybe_unused]] std::span<const ManifoldTail> tails, SolverState& st,
                          StepScratch& scratch, int participants, Real deep_separation) {
  const std::size_t count = st.packets.size();
  auto half_of = [&](uint32_t packet) { return packet >= st.half_start[1] ? 1u : 0u; };
  auto group_of = [&](const ManifoldHead& mf, ColorInput& in) {
    const uint32_t pa = st.packet_of[mf.body_a], pb = st.packet_of[mf.body_b];
    in = {pa, pb, pa != 0 && bodies.is_dynamic(mf.body_a), pb != 0 && bodies.is_dynamic(mf.body_b)};
    if (mf.point_count == 0 || !(in.dynamic_a || in.dynamic_b)) return kGroups;
    if (in.dynamic_a && in.dynamic_b && half_of(pa) != half_of(pb)) return kCutGroup;
    return half_of(in.dynamic_a ? pa : pb);
  };
  // One pass counts each group's candidates and the points, and gives each head with more than
  // one point its tail's index (the tails are in key order, as the heads).
  uint32_t group_size[kGroups + 1] = {};
  std::size_t points = 0;
  uint32_t next_tail = 0;
  st.deep_count.assign(count, 0);
  uint32_t most_deep = 0;
  for (ManifoldHead& mf : contacts) {
    ColorInput in;
    const uint32_t g = group_of(mf, in);
    ++group_size[g];
    points += mf.point_count;
    if (g != kGroups && mf.first.separation < deep_separation) {
      if (in.dynamic_a) most_deep = std::max(most_deep, ++st.deep_count[in.packet_a]);
      if (in.dynamic_b) most_deep = std::max(most_deep, ++st.deep_count[in.packet_b]);
    }
    if (mf.point_count > 1) {
      assert(next_tail < tails.size() && tails[next_tail].key == mf.key() && "its tail is next");
      mf.tail = next_tail++;
    }
  }
  assert(next_tail == tails.size() && "every tail has its head");
  st.most_deep = most_deep;
  st.group_start[0] = 0;
  for (uint32_t g = 0; g < kGroups; ++g) st.group_start[g + 1] = st.group_start[g] + group_size[g];
  const uint32_t candidate_count = st.group_start[kGroups];
  take_from(st.candidates, scratch, candidate_count);
  take_from(st.color_input, scratch, candidate_count);
  uint32_t cursor[kGroups + 1] = {st.group_start[0], st.group_start[1], st.group_start[2], 0};
  for (std::size_t m = 0; m < contacts.size(); ++m) {
    ColorInput in;
    const uint32_t g = group_of(contacts[m], in);
    if (g == kGroups) continue;
    if (g < kHalves) {
      in.packet_a = in.dynamic_a ? in.packet_a - st.half_start[g] : 0;
      in.packet_b = in.dynamic_b ? in.packet_b - st.half_start[g] : 0;
    }
    st.candidates[cursor[g]] = uint32_t(m);
    st.color_input[cursor[g]++] = in;
  }
  grow_to(st.order, candidate_count);
  take_from(st.order_scratch, scratch, candidate_count);
  // The colourings' arrays with their room, taken here in a fixed order so that they go back
  // last taken first (below), whichever thread colours which group.
  for (uint32_t g = 0; g < kGroups; ++g) {
    const std::size_t packets = g < kHalves ? st.half_start[g + 1] - st.half_start[g] : count;
    ColorScratch& c = st.color_scratch[g];
    take_room(c.bits, scratch, color_words(packets));
    take_room(c.color_of, scratch, st.group_start[g + 1] - st.group_start[g]);
    take_room(c.cursor, scratch, kColorCount + 1);
  }
  st.segment_start.resize(kSegments + 1);
  st.segment_start[kSegments] = candidate_count;
  auto point_count = [&](uint32_t k) { return contacts[st.order[k]].point_count; };

  // Colours group g, then orders each of its segments by point count, most first. perf: within
  // a colour the order is free (its constraints share no dynamic body, so any order gives the
  // same bits). Grouped by point count, manifolds of one or two points (spheres, capsules) share
  // bundles, which then skip the empty point rows that a single four-point lane would make the
  // whole bundle read: a pile's manifolds have about 1.4 points on average.
  auto color_group = [&](uint32_t g) {
    const uint32_t first = st.group_start[g], size = st.group_start[g + 1] - first;
    const std::size_t packets = g < kHalves ? st.half_start[g + 1] - st.half_start[g] : count;
    uint32_t start[kColorCount + 2];
    build_colors(std::span(st.color_input).subspan(first, size), packets, st.color_scratch[g],
                 std::span(st.order).subspan(first, size), start);
    for (uint32_t k = first; k < first + size; ++k)
      st.order[k] = st.candidates[first + st.order[k]];
    for (uint32_t c = 0; c <= kColorCount; ++c) {
      st.segment_start[g * kSegmentsPerGroup + c] = first + start[c];
    }
    for (uint32_t c = 0; c <= kColorCount; ++c) {
      const uint32_t begin = first + start[c], end = first + start[c + 1];
      uint32_t at[kMaxManifoldPoints + 1] = {};
      for (uint32_t k = begin; k < end; ++k) ++at[kMaxManifoldPoints - point_count(k)];
      uint32_t running = begin;
      for (uint32_t& a : at) {
        const uint32_t n = a;
        a = running;
        running += n;
      }
      for (uint32_t k = begin; k < end; ++k) {
        st.order_scratch[at[kMaxManifoldPoints - point_count(k)]++] = st.order[k];
      }
      std::copy(st.order_scratch.begin() + begin, st.order_scratch.begin() + end,
                st.order.begin() + begin);
    }
  };

  // determinism: group g writes only its own ranges of st.order, st.order_scratch and
  // st.segment_start and its own colouring arrays, so which thread colours it does not matter.
  std::vector<StageSpec>& stages = st.stages;
  stages.assign({{kGroups, 0, 0}});
  st.executor.run(stages, std::min(participants, int(kHalves)),
                  [&](const StageSpec&, uint32_t group) { color_group(group); });

  // The colouring is done: its arrays go back, the last taken first, so the bundles start where
  // they did.
  for (uint32_t g = kGroups; g-- > 0;) {
    release(st.color_scratch[g].cursor);
    release(st.color_scratch[g].color_of);
    release(st.color_scratch[g].bits);
  }
  release(st.order_scratch);
  release(st.color_input);
  release(st.candidates);

  ColorStats stats;
  stats.points = points;
  for (uint32_t g = 0; g < kGroups; ++g) {
    std::size_t used = 0;
    for (uint32_t c = 0; c < kColorCount; ++c) {
      const uint32_t s = g * kSegmentsPerGroup + c;
      if (st.segment_start[s + 1] > st.segment_start[s]) ++used;
    }
    const uint32_t s = g * kSegmentsPerGroup + kColorCount;
    stats.colors = std::max(stats.colors, used);
    stats.overflow += st.segment_start[s + 1] - st.segment_start[s];
  }
  return stats;
}

}  // namespace elan::detail
