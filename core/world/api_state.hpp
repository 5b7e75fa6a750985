// SPDX-License-Identifier: MIT
// ApiState: what the embedding API keeps beside the step's own data: events, the pair filter,
// destroyed shapes, and the cached bounds used by scene queries.
#pragma once

#include <cstdint>
#include <vector>

#include "broadphase/bounds.hpp"
#include "core/base/grow.hpp"
#include "elan/events.hpp"
#include "elan/ids.hpp"
#include "elan/joints.hpp"

namespace elan::detail {

struct ApiState {
  std::vector<ContactBeginEvent> begin_events;
  std::vector<ContactEndEvent> end_events;
  std::vector<JointRemovedEvent> joint_events;
  SpikeTrim begin_trim, end_trim;  // a pile's landing begins thousands of contacts in one step
  PairFilter pair_filter;
  std::vector<uint8_t> pair_keep;  // per broadphase pair: the filter's answer
  std::vector<uint64_t> pair_scratch;
  std::vector<uint8_t> shape_destroyed;  // per shape index; shorter than the shape list = live
  std::vector<BodyId> body_ids;          // dense index -> id, rebuilt on request
  // Query bounds: exact (no margin, no motion) boxes, rebuilt when stale.
  BoundsColumns query_bounds;
  uint64_t mutations = 0;  // bumped by every API call that changes a pose or the body set
  uint64_t query_mutations = UINT64_MAX;  // `mutations` and step count the cache was built at
  uint64_t query_step = UINT64_MAX;
};

}  // namespace elan::detail
