// SPDX-License-Identifier: MIT
// Sensor pairs and overlap events (see sensors.hpp).
#include "core/world/sensors.hpp"

#include <algorithm>

#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"
#include "core/world/events.hpp"
#include "core/world/world_access.hpp"
#include "narrowphase/collide.hpp"

namespace elan::detail {

namespace {

// perf: an overlap test is one exact collide; 64 pairs a block as the collide stage's blocks.
constexpr std::size_t kSensorGrain = 64;

bool is_sensor(const BodyStore& b, uint32_t i) {
  return (b.traits_of(i).flags & kTraitSensor) != 0;
}

// The pair as a (sensor, visitor) overlap: the sensor is the one with the flag (divert_sensor_pairs
// keeps no pair of two sensors).
SensorOverlap overlap_of(const BodyStore& b, uint64_t key) {
  const uint32_t x = pair_first(key), y = pair_second(key);
  return is_sensor(b, x) ? SensorOverlap{x, y} : SensorOverlap{y, x};
}

// Do the two bodies' shapes overlap at their current poses? The static or kinematic body, if any,
// is B, as in the collide stage (collide() takes planes and surfaces on that side).
bool shapes_overlap(const WorldState& w, uint32_t a, uint32_t b, PolyhedronCache& cache) {
  const BodyStore& bodies = w.bodies;
  if (!bodies.is_dynamic(a) && bodies.is_dynamic(b)) std::swap(a, b);
  const Transform xa{bodies.position(a), bodies.orientation(a)};
  const Transform xb{bodies.position(b), bodies.orientation(b)};
  Manifold m;
  Separation separation;
  return collide(w.shapes[bodies.shape[a]], xa, w.shapes[bodies.shape[b]], xb, 0, m, cache,
                 separation);
}

}  // namespace

bool any_sensor(const BodyStore& bodies) {
  for (const BodyTraits& t : bodies.trait_table.entries()) {
    if (t.flags & kTraitSensor) return true;
  }
  return false;
}

void divert_sensor_pairs(WorldState& w) {
  std::vector<uint64_t>& out = w.api.sensor_pairs;
  out.clear();
  if (!any_sensor(w.bodies)) return;
  const BodyStore& b = w.bodies;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < w.pairs.size(); ++k) {
    const uint64_t key = w.pairs[k];
    const bool sa = is_sensor(b, pair_first(key)), sb = is_sensor(b, pair_second(key));
    if (!sa && !sb) {
      w.pairs[kept++] = key;
    } else if (sa != sb) {
      out.push_back(key);
    }
  }
  w.pairs.resize(kept);
}

void update_sensors(WorldState& w) {
  ApiState& api = w.api;
  api.sensor_begin_events.clear();
  api.sensor_end_events.clear();
  const std::vector<uint64_t>& pairs = api.sensor_pairs;
  if (pairs.empty() && api.sensor_overlaps.empty()) return;
  const BodyStore& b = w.bodies;
  // determinism: a flag per pair from fixed blocks (rule 1); the lists below are built serially.
  api.sensor_hit.resize(pairs.size());
  for_blocks(pairs.size(), kSensorGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
    PolyhedronCache cache;
    for (std::size_t k = begin; k < end; ++k) {
      api.sensor_hit[k] =
          shapes_overlap(w, pair_first(pairs[k]), pair_second(pairs[k]), cache) ? 1 : 0;
    }
  });
  std::vector<SensorOverlap>& now = api.sensor_scratch;
  now.clear();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (api.sensor_hit[k]) now.push_back(overlap_of(b, pairs[k]));
  }
  // Last step's overlaps of two bodies idle at the step's start had no pair to test: kept.
  for (const SensorOverlap& o : api.sensor_overlaps) {
    if (o.sensor < w.idle.size() && o.visitor < w.idle.size() && w.idle[o.sensor] &&
        w.idle[o.visitor]) {
      now.push_back(o);
    }
  }
  std::sort(now.begin(), now.end());
  now.erase(std::unique(now.begin(), now.end()), now.end());
  // The difference of the two sorted lists, in (sensor, visitor) order.
  const std::vector<SensorOverlap>& before = api.sensor_overlaps;
  std::size_t i = 0, j = 0;
  while (i < before.size() || j < now.size()) {
    if (j == now.size() || (i < before.size() && before[i] < now[j])) {
      api.sensor_end_events.push_back(
          {body_id_at(w, before[i].sensor), body_id_at(w, before[i].visitor)});
      ++i;
    } else if (i == before.size() || now[j] < before[i]) {
      api.sensor_begin_events.push_back(
          {body_id_at(w, now[j].sensor), body_id_at(w, now[j].visitor)});
      ++j;
    } else {
      ++i;
      ++j;
    }
  }
  std::swap(api.sensor_overlaps, now);
  api.sensor_pairs.clear();
}

void sensor_remove_body(WorldState& w, uint32_t index, uint32_t last) {
  std::vector<SensorOverlap>& list = w.api.sensor_overlaps;
  std::size_t kept = 0;
  bool renamed = false;
  for (const SensorOverlap& o : list) {
    if (o.sensor == index || o.visitor == index) {
      w.api.sensor_end_events.push_back({body_id_at(w, o.sensor), body_id_at(w, o.visitor)});
      continue;
    }
    SensorOverlap r = o;
    if (index != last) {
      if (r.sensor == last) r.sensor = index, renamed = true;
      if (r.visitor == last) r.visitor = index, renamed = true;
    }
    list[kept++] = r;
  }
  list.resize(kept);
  if (renamed) std::sort(list.begin(), list.end());
}

void wake_sensor_partners(WorldState& w, uint32_t index) {
  for (const SensorOverlap& o : w.api.sensor_overlaps) {
    if (o.sensor != index && o.visitor != index) continue;
    for (const uint32_t i : {o.sensor, o.visitor}) {
      if (w.bodies.is_dynamic(i)) wake_index(w, i);
    }
  }
}

}  // namespace elan::detail
