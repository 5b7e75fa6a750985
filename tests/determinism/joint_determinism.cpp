// SPDX-License-Identifier: MIT
// Joints and determinism: a scene of several hundred joints of every kind, falling onto a floor
// among loose boxes, gives the same state hash every step at 1 to 4 threads and with both
// broadphases; a snapshot restored, and a rollback state rolled back to, continue bit for bit,
// also across a joint that breaks and one destroyed after the save.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "elan/snapshot.hpp"
#include "physics/physics_util.hpp"

namespace elan {
namespace joint_determinism_test {

using test::add_body;
using test::at;
using test::kDt;

constexpr int kSteps = 90;

// A 16 x 16 grid of balls on ball joints to their right and lower neighbours, its top row pinned
// to the world (Box2D's joint_grid), laid out vertically above a floor; chains of hinged capsules
// with limits and motors, pairs on sliders with springs, ropes, welds and cone joints; loose boxes
// that the grid and chains land on. Joints with a break force break under the impacts.
World joint_world(int threads, BroadphaseType broadphase) {
  WorldDef def;
  def.threads = threads;
  def.broadphase = broadphase;
  World world(def);
  test::add_ground(world);
  const ShapeId ball = world.create_shape(test::sphere_shape(Real(0.2)));
  const ShapeId capsule = world.create_shape(test::capsule_shape(Real(0.1), Real(0.2)));
  const ShapeId box = world.create_shape(test::box_shape(Vec3::Constant(Real(0.25))));
  auto body = [&](ShapeId shape, const Vec3& p) {
    BodyDef d = at(p);
    d.shape = shape;
    return world.create_body(d);
  };
  auto joint = [&](JointType type, BodyId a, BodyId b, const Vec3& anchor) {
    JointDef j;
    j.type = type;
    j.body_a = a;
    j.body_b = b;
    j.anchor = anchor;
    j.axis = Vec3::UnitZ();
    return j;
  };
  // The grid: rows hang down from y = 9.
  const int n = 16;
  std::vector<BodyId> grid(n * n);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      grid[r * n + c] = body(ball, Vec3(Real(c) * Real(0.5) - 4, 9 - Real(r) * Real(0.5), 0));
    }
  }
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      const BodyId a = grid[r * n + c];
      const Vec3 p = world.position(a);
      if (r == 0 && c % 5 == 0) world.create_joint(joint(JointType::Ball, a, {}, p));
      if (c + 1 < n) {
        world.create_joint(
            joint(JointType::Ball, a, grid[r * n + c + 1], p + Vec3(Real(0.25), 0, 0)));
      }
      if (r + 1 < n) {
        JointDef j = joint(JointType::Ball, a, grid[(r + 1) * n + c], p - Vec3(0, Real(0.25), 0));
        if (r == n - 2) j.break_force = 3000;
        world.create_joint(j);
      }
    }
  }
  // Hinged chains with limits, one motorised at its root.
  for (int k = 0; k < 6; ++k) {
    BodyId previous;
    const Vec3 top(Real(k) - 3, 6, 3);
    for (int l = 0; l < 8; ++l) {
      const BodyId link = body(capsule, top - Vec3(0, Real(0.4) * Real(l) + Real(0.2), 0));
      JointDef j = joint(JointType::Hinge, link, previous, top - Vec3(0, Real(0.4) * Real(l), 0));
      j.axis = Vec3(1, 0, Real(k) * Real(0.1)).normalized();
      j.limits = {true, Real(-0.8), Real(0.8)};
      if (l == 0) j.motor = {true, Real(0.5), 20};
      world.create_joint(j);
      previous = link;
    }
  }
  // Sliders with springs, ropes, welds and cones between box pairs above the floor.
  for (int k = 0; k < 6; ++k) {
    const Vec3 p(Real(k) - 3, 3, -3);
    const BodyId a = body(box, p), b = body(box, p + Vec3(0, Real(0.7), 0));
    JointDef j = joint(JointType(k % 6), a, b, p + Vec3(0, Real(0.35), 0));
    j.axis = Vec3(0, 1, 0);
    j.limits = {k % 6 != 0 && k % 6 != 3 && k % 6 != 4, Real(-0.3), Real(0.3)};
    if (j.type == JointType::Slider) j.spring = {true, 2, Real(0.3), 0};
    if (j.type == JointType::Distance) {
      j.anchor = p;
      j.anchor_b = p + Vec3(0, Real(0.7), 0);
      j.min_length = Real(0.3);
    }
    if (j.type == JointType::Cone) j.swing_limit = Real(0.5);
    if (j.type == JointType::Fixed) j.has_anchor = false;
    world.create_joint(j);
  }
  for (int k = 0; k < 40; ++k) {
    body(box, Vec3(Real(k % 8) * Real(0.7) - 3, Real(0.3) + Real(k / 8) * Real(0.6), 1));
  }
  return world;
}

std::vector<uint64_t> run(World& world, int steps) {
  std::vector<uint64_t> out;
  for (int s = 0; s < steps; ++s) {
    world.step(kDt);
    out.push_back(world.state_hash());
  }
  return out;
}

TEST(JointDeterminism, SameHashesForAnyThreadCountAndBroadphase) {
  World reference_world = joint_world(1, BroadphaseType::SweepAndPrune);
  EXPECT_EQ(reference_world.joint_count(), 538u);
  const std::vector<uint64_t> reference = run(reference_world, kSteps);
  EXPECT_TRUE(test::all_finite(reference_world));
  for (BroadphaseType broadphase : {BroadphaseType::SweepAndPrune, BroadphaseType::AllPairs}) {
    for (int threads = 1; threads <= 4; ++threads) {
      // The sanitized run checks 2 and 4 threads (one thread runs no task a sanitizer could
      // catch racing; 3 runs the code of 2 and 4 with other block boundaries).
      if (test::kSanitized && (threads == 1 || threads == 3)) continue;
      SCOPED_TRACE(testing::Message() << threads << " threads, broadphase " << int(broadphase));
      World world = joint_world(threads, broadphase);
      EXPECT_EQ(run(world, kSteps), reference);
      EXPECT_EQ(world.joint_count(), reference_world.joint_count());
    }
  }
}

TEST(JointDeterminism, SnapshotAndRollbackContinueBitForBit) {
  World world = joint_world(2, BroadphaseType::SweepAndPrune);
  run(world, 30);
  const std::vector<uint8_t> snapshot = save_snapshot(world);
  const std::vector<uint8_t> rollback = save_rollback(world);
  const std::size_t joints_at_save = world.joint_count();
  // A pull on the grid's bottom corner breaks its joint (break_force 3000 N) after the save.
  const BodyId corner = world.body_at(1 + 16 * 16 - 1);
  auto pull_and_run = [&](World& w) {
    w.apply_force(corner, Vec3(0, -20000, 0));
    return run(w, 40);
  };
  const std::vector<uint64_t> expected = pull_and_run(world);
  ASSERT_LT(world.joint_count(), joints_at_save) << "a joint broke after the save";

  World loaded = load_snapshot(snapshot);
  EXPECT_EQ(loaded.joint_count(), joints_at_save);
  EXPECT_EQ(pull_and_run(loaded), expected);

  // Rolled back in the same world, after a joint was destroyed: the joints come back as saved.
  world.destroy_joint(world.joint_at(0));
  restore_rollback(world, rollback);
  EXPECT_EQ(world.joint_count(), joints_at_save);
  world.set_threads(1);
  EXPECT_EQ(pull_and_run(world), expected);
}

}  // namespace joint_determinism_test
}  // namespace elan
