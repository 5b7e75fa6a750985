// SPDX-License-Identifier: MIT
// build_bundles() and prepare_contacts(): the solver's contact bundles (see bundles.hpp).
#include "solver/bundles.hpp"

#include <algorithm>

#include "core/base/grow.hpp"
#include "core/base/parallel.hpp"

namespace elan::detail {
ELAN_ISA_BEGIN

void build_bundles(std::span<const ManifoldHead> contacts, bool bouncy, SolverState& st,
                   StepScratch& scratch) {
  auto is_overflow = [](std::size_t segment) { return segment % kSegmentsPerGroup == kColorCount; };
  auto point_count = [&](uint32_t k) { return contacts[st.order[k]].point_count; };
  const uint32_t candidate_count = st.segment_start[kSegments];
  st.bundle_start.resize(kSegments + 1);
  st.bundle_start[0] = 0;
  for (uint32_t s = 0; s < kSegments; ++s) {
    const uint32_t size = st.segment_start[s + 1] - st.segment_start[s];
    const uint32_t bundles = is_overflow(s) ? size : uint32_t(block_count(size, kLanes));
    st.bundle_start[s + 1] = st.bundle_start[s] + bundles;
  }
  const std::size_t bundle_count = st.bundle_start[kSegments];
  st.row_start.resize(bundle_count + 1);
  st.lane_start.resize(bundle_count + 1);
  st.row_start[0] = 0;
  for (uint32_t s = 0; s < kSegments; ++s) {
    const uint32_t per_bundle = is_overflow(s) ? 1 : kLanes;
    for (uint32_t j = st.bundle_start[s]; j < st.bundle_start[s + 1]; ++j) {
      const uint32_t first = st.segment_start[s] + (j - st.bundle_start[s]) * per_bundle;
      st.row_start[j + 1] = st.row_start[j] + uint32_t(point_count(first)) - 1;
      st.lane_start[j] = first;
    }
  }
  st.lane_start[bundle_count] = candidate_count;
  take_from(st.bundles, scratch, bundle_count);
  take_from(st.rows, scratch, st.row_start[bundle_count]);
  take_from(st.restitution, scratch, bouncy ? bundle_count : 0);
}

void prepare_contacts(const BodyStore& bodies, std::span<const ManifoldHead> contacts,
                      std::span<const ManifoldTail> tails, const SolveSettings& settings,
                      SolverState& st) {
  auto prepare_group = [&](uint32_t g) {
    const ContactSolverContext ctx = make_solver_context(settings, st);
    for (uint32_t s = g * kSegmentsPerGroup; s < (g + 1) * kSegmentsPerGroup; ++s) {
      for (uint32_t j = st.bundle_start[s]; j < st.bundle_start[s + 1]; ++j) {
        const uint32_t last = st.lane_start[j + 1];
        // perf: the next bundle's manifolds, while this one is prepared. They are scattered over
        // the contact list, and at 2 threads about half were last written by the other core's
        // collide blocks, so the first load of a lane's manifold is a cross-core round trip.
        const uint32_t next_last = j + 1 < st.bundle_start[s + 1] ? st.lane_start[j + 2] : last;
        for (uint32_t k = last; k < next_last; ++k) prefetch(contacts[st.order[k]]);
        // This bundle's tails: its heads, fetched while the last bundle was prepared, say where.
        for (uint32_t k = st.lane_start[j]; k < last; ++k) {
          const ManifoldHead& head = contacts[st.order[k]];
          if (head.point_count > 1) prefetch(tails[head.tail]);
        }
        prepare_bundle(ctx, bodies, contacts, tails, st.packet_of, j);
      }
    }
  };
  // determinism: group g writes only its own bundles and their rows (and loaded lanes).
  grow_to(st.direct.loaded_lanes, st.bundles.size());
  // The push-out share's caps, only while some body has more than one deep manifold.
  if (st.most_deep > kPushShare) {
    grow_to(st.push_cap, st.bundles.size());
  } else {
    st.push_cap.clear();
  }
  std::vector<StageSpec>& stages = st.stages;
  stages.assign({{kGroups, 0, 0}});
  st.executor.run(stages, std::min(settings.participants, int(kHalves)),
                  [&](const StageSpec&, uint32_t group) { prepare_group(group); });
}

void release_bundles(SolverState& st) {
  release(st.bundles);
  release(st.rows);
  release(st.restitution);
}

ELAN_ISA_END
}  // namespace elan::detail
