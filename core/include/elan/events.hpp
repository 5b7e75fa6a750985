// SPDX-License-Identifier: MIT
// Contact events and the pair filter of the public API: what the world reports after a step and
// how the caller vetoes pairs.
#pragma once

#include <functional>

#include "elan/ids.hpp"
#include "elan/math.hpp"

namespace elan {

/// A pair started touching in the last step: its manifold went from 0 points (or no manifold)
/// to at least one. Speculative points (a small positive gap) count, as in Box2D.
struct ContactBeginEvent {
  BodyId body_a;  ///< the static or kinematic body, if any, is body_b
  BodyId body_b;
  Vec3 point = Vec3::Zero();    ///< m, world: mean of the manifold's points at the step's start
  Vec3 normal = Vec3::UnitY();  ///< unit, world, from body_a towards body_b
  Real normal_impulse = 0;      ///< N s: sum over the points of the impulse applied this step
};

/// A pair stopped touching: its manifold went from at least one point to none, the pair left
/// the broadphase, or one of the bodies was destroyed (then that id is already stale).
struct ContactEndEvent {
  BodyId body_a;
  BodyId body_b;
};

/// A contact that began in the last step with an approach speed (the relative normal velocity at
/// its deepest point before the solve) of at least World's hit threshold: for sounds and damage
/// (Box2D's b2ContactHitEvent). In pair-key order.
struct ContactHitEvent {
  BodyId body_a;
  BodyId body_b;
  Vec3 point = Vec3::Zero();    ///< m, world
  Vec3 normal = Vec3::UnitY();  ///< unit, world, from body_a towards body_b
  Real approach_speed = 0;      ///< m/s, > 0
};

/// A body's shape began (or ended) overlapping a sensor's shape in the last step. Sensors see
/// every non-sensor body their filter bits allow, asleep or awake; in (sensor, visitor) dense
/// index order. End events also come when either body is destroyed (then its id is stale).
struct SensorBeginEvent {
  BodyId sensor;
  BodyId visitor;
};
struct SensorEndEvent {
  BodyId sensor;
  BodyId visitor;
};

/// One point of a contact manifold, as World::contact returns it.
struct ContactPointView {
  Vec3 point = Vec3::Zero();  ///< m, world, midway between the surfaces
  Real separation = 0;        ///< m, negative when penetrating
  Real normal_impulse = 0;    ///< N s, over the last step
  Real tangent_impulse = 0;   ///< N s, magnitude of the friction impulse over the last step
};

/// A current contact manifold between two bodies.
struct ContactView {
  BodyId body_a;
  BodyId body_b;
  Vec3 normal = Vec3::UnitY();  ///< unit, world, from body_a towards body_b
  int point_count = 0;          ///< 0 to 4
  ContactPointView points[4];
};

/// Pair filter, called for every pair the broadphase finds (after the category/mask test);
/// return false to drop the pair (no contact, no events). threading: called from the step's
/// worker threads concurrently and in no fixed order, so it must be thread-safe and must not
/// throw; it must be deterministic (same answer for the same two ids), or the simulation is not.
using PairFilter = std::function<bool(BodyId, BodyId)>;

}  // namespace elan
