// SPDX-License-Identifier: MIT
// Sensors: bodies whose shape reports overlap begin and end events and takes no part in contact
// response. Their broadphase pairs never reach the collide stage: divert_sensor_pairs moves them
// out of the step's pair list, and update_sensors tests each for overlap at the step's end poses
// and compares the result with the overlaps of the last step.
#pragma once

#include <cstdint>

#include "core/world/world_state.hpp"

namespace elan::detail {

// Whether any body may be a sensor: some entry of the trait table has the flag (an entry no body
// uses may keep it; then the step only walks its pairs once for nothing).
bool any_sensor(const BodyStore& bodies);

// Moves the pairs of w.pairs with a sensor on either side into w.api.sensor_pairs (both lists stay
// sorted); a pair of two sensors is dropped (sensors do not see sensors). Serial, in pair order.
void divert_sensor_pairs(WorldState& w);

// Clears last step's sensor events and, from w.api.sensor_pairs, finds this step's overlaps at the
// bodies' poses after the step (collide() with no speculative distance: touching counts) in
// parallel fixed blocks, a flag per pair. An overlap of last step whose pair the broadphase did
// not report because both bodies were idle at the step's start (static or asleep: w.idle) is kept
// as it is, as the contact store keeps such manifolds. Begin and end events are the difference of
// the two sorted lists, in (sensor, visitor) dense index order. Takes w.api.sensor_pairs's
// contents (leaves it empty).
void update_sensors(WorldState& w);

// Body `index` is removed and the last body takes its index: its overlaps end (an end event each,
// ids taken before the slot is released), the last body's are renamed and the list re-sorted.
// With last == index the body's overlaps end and nothing is renamed (set_sensor,
// set_motion_type: the next step finds them again if they last).
void sensor_remove_body(WorldState& w, uint32_t index, uint32_t last);

// A body in an overlap was moved, reshaped or changed motion type between steps: its dynamic
// partners, and itself if dynamic, are woken, so that the next step tests the overlap again
// rather than keep it as an overlap of idle bodies.
void wake_sensor_partners(WorldState& w, uint32_t index);

}  // namespace elan::detail
