// SPDX-License-Identifier: MIT
// ApiState: what the embedding API keeps beside the step's own data: events, the pair filter,
// destroyed shapes, and the cached bounds used by scene queries.
#pragma once

#include <compare>
#include <cstdint>
#include <memory>
#include <vector>

#include "broadphase/bounds.hpp"
#include "core/base/grow.hpp"
#include "elan/defs.hpp"
#include "elan/events.hpp"
#include "elan/ids.hpp"
#include "elan/joints.hpp"

namespace elan::detail {

// What a body keeps beside the store's columns, by id slot (a swap-remove moves none of it): the
// caller's value, and what a change of shape or of motion type derives its mass from.
struct BodyExtra {
  uint64_t user_data = 0;
  Real density = 1000;  // kg/m^3
  Real given_mass = 0;  // kg: BodyDef::mass or the last set_mass; 0 when the density decides
};

// A sensor and a body whose shapes overlap: dense indices, sensor first. Sorted, unique.
struct SensorOverlap {
  uint32_t sensor = 0;
  uint32_t visitor = 0;
  friend bool operator==(const SensorOverlap&, const SensorOverlap&) = default;
  friend auto operator<=>(const SensorOverlap&, const SensorOverlap&) = default;
};

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
  // Issue 39: the caller's value per shape index; per-slot body extras; sensor overlaps and
  // events; hit events.
  std::vector<uint64_t> shape_user_data;
  // Per shape index, the definition World::shape_def returns, derived on first request (a mesh's
  // or heightfield's copy would double its memory in every world that never draws it). Filled
  // from const calls: World is used from one thread at a time (queries do not read it).
  mutable std::vector<std::unique_ptr<ShapeDef>> shape_defs;
  std::vector<BodyExtra> body_extra;           // per id slot; shorter than the slots = defaults
  std::vector<SensorOverlap> sensor_overlaps;  // after the last step, sorted
  // The step's pairs with a sensor (sorted keys), their overlap flags and the new overlap list:
  // kept from step to step so that a warm step allocates nothing.
  std::vector<uint64_t> sensor_pairs;
  std::vector<uint8_t> sensor_hit;
  std::vector<SensorOverlap> sensor_scratch;
  std::vector<SensorBeginEvent> sensor_begin_events;
  std::vector<SensorEndEvent> sensor_end_events;
  std::vector<ContactHitEvent> hit_events;
  Real hit_threshold = 1;  // m/s
  uint64_t mutations = 0;  // bumped by every API call that changes a pose or the body set
  uint64_t query_mutations = UINT64_MAX;  // `mutations` and step count the cache was built at
  uint64_t query_step = UINT64_MAX;
};

}  // namespace elan::detail
