// SPDX-License-Identifier: MIT
// The engine's own access to a World's state (for its source files, tools, tests and benchmarks;
// the public header keeps it private), and the checks shared by the World API's source files:
// id lookup and argument validation.
#pragma once

#include <string>

#include "core/base/id_slots.hpp"
#include "core/world/world_state.hpp"
#include "elan/error.hpp"
#include "elan/world.hpp"

namespace elan::detail {

struct WorldAccess {
  static WorldState& state(World& world) { return *world.state_; }
  static const WorldState& state(const World& world) { return *world.state_; }
};

inline WorldState& state_of(World& world) {
  return WorldAccess::state(world);
}
inline const WorldState& state_of(const World& world) {
  return WorldAccess::state(world);
}

inline void check_arg(bool ok, const char* field, const std::string& message) {
  if (!ok) throw Error(field, message);
}

// Dense index of a live body; elan::Error "body" for a stale, destroyed or foreign id.
inline std::size_t index_of(const WorldState& s, BodyId id) {
  if (!slot_live(s.slot_index, s.slot_generation, id.slot, id.generation)) {
    throw Error("body", "invalid or destroyed body id");
  }
  return s.slot_index[id.slot];
}

inline bool shape_live(const WorldState& s, ShapeId id) {
  return !id.is_null() && id.index < s.shapes.size() &&
         !(id.index < s.api.shape_destroyed.size() && s.api.shape_destroyed[id.index]);
}

// The extras of the body in id slot `slot` (see BodyExtra), grown to hold it.
inline BodyExtra& body_extra(WorldState& s, uint32_t slot) {
  if (slot >= s.api.body_extra.size()) s.api.body_extra.resize(std::size_t(slot) + 1);
  return s.api.body_extra[slot];
}
inline BodyExtra body_extra(const WorldState& s, uint32_t slot) {
  return slot < s.api.body_extra.size() ? s.api.body_extra[slot] : BodyExtra{};
}

// The caller's value on shape `index` (0 for a shape made before the list grew to it).
inline uint64_t shape_user_data(const WorldState& s, uint32_t index) {
  return index < s.api.shape_user_data.size() ? s.api.shape_user_data[index] : 0;
}

// A non-static body was moved or pushed: simulate it again from this step on.
inline void wake_index(WorldState& s, std::size_t i) {
  if (s.bodies.is_static(i)) return;
  s.bodies.flags[i] |= kAwake;
  s.bodies.sleep_time[i] = 0;
}

}  // namespace elan::detail
