// SPDX-License-Identifier: MIT
// The scene the snapshot tests share: pile1k (boxes, spheres, capsules, hulls in a walled box)
// plus, outside the walls, resting boxes that fall asleep, a stack created asleep, and a ball
// dropped from high up that wakes the stack at about step 110, so a window of steps 100..130
// holds sleeping islands, carried contacts, warm-started contacts and a wake-up.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "elan/scene.hpp"
#include "elan/world.hpp"

namespace elan::test {

inline constexpr Real kSnapshotDt = Real(1.0 / 60.0);

inline World make_snapshot_world(int threads) {
  const std::string path = std::string(ELAN_SCENE_DIR) + "/pile1k.json";
  const Scene scene = load_scene(path);
  WorldDef def = scene.world;
  def.threads = threads;
  World world(def);
  load_into(scene, world, path);

  ShapeDef box;
  box.type = ShapeType::Box;
  box.half_extents = Vec3::Constant(Real(0.25));
  const ShapeId box_id = world.create_shape(box);
  // Resting exactly on the ground (its top face is y = 0) at x = 6.8, outside the wall.
  for (int k = 0; k < 6; ++k) {
    BodyDef b;
    b.shape = box_id;
    b.position = Vec3(Real(6.8), Real(0.25), Real(-5 + 1.5 * k));
    world.create_body(b);
  }
  // A stack of three created asleep, and a ball above it: free fall of 16.7 m takes
  // sqrt(2 * 16.7 / 9.81) = 1.85 s, about 111 steps.
  for (int k = 0; k < 3; ++k) {
    BodyDef b;
    b.shape = box_id;
    b.position = Vec3(Real(6.8), Real(0.25 + 0.5 * k), Real(6.5));
    b.awake = false;
    world.create_body(b);
  }
  ShapeDef ball;
  ball.radius = Real(0.3);
  BodyDef b;
  b.shape = world.create_shape(ball);
  b.position = Vec3(Real(6.8), Real(18), Real(6.5));
  world.create_body(b);
  return world;
}

}  // namespace elan::test
