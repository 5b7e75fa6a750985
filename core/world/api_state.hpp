// SPDX-License-Identifier: MIT
// ApiState: what the embedding API keeps beside the step's own data: events, the pair filter,
// destroyed shapes. (The scene queries read the query tree: core/world/query_tree.hpp.)
#pragma once

#include <cstdint>
#include <vector>

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
};

}  // namespace elan::detail
