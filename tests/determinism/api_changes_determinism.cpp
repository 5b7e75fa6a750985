// SPDX-License-Identifier: MIT
// The body changes of issue 39 keep determinism: motion types, gravity (world and per body),
// shapes, damping and sensor flags changed between steps of a pile with sensors give the same
// bits and the same sensor events at 1 and 2 threads and with either broadphase, and a snapshot
// taken mid-run continues with the same bits and keeps the user data.
#include <gtest/gtest.h>

#include <vector>

#include "elan/elan.hpp"

namespace elan {
namespace api_changes_determinism_test {

constexpr Real kDt = Real(1.0 / 60.0);

struct ChangeRun {
  std::vector<uint64_t> hashes;
  // Per step: the sensor events as (sensor slot, visitor slot, begin?) triples, flattened.
  std::vector<uint32_t> sensor_events;
  std::vector<uint64_t> hashes_after_snapshot;
};

constexpr int kSteps = 240;
constexpr int kSnapshotStep = 130;

struct Pile {
  ShapeId box, ball, big_ball;
  std::vector<BodyId> bodies;
  BodyId sensor, kinematic_sensor;
};

Pile build(World& w) {
  Pile p;
  ShapeDef ground;
  ground.type = ShapeType::Box;
  ground.half_extents = Vec3(20, 1, 20);
  ShapeDef box;
  box.type = ShapeType::Box;
  box.half_extents = Vec3(Real(0.4), Real(0.3), Real(0.5));
  ShapeDef ball;
  ball.type = ShapeType::Sphere;
  ball.radius = Real(0.35);
  ShapeDef big = ball;
  big.radius = Real(0.6);
  const ShapeId g = w.create_shape(ground);
  p.box = w.create_shape(box);
  p.ball = w.create_shape(ball);
  p.big_ball = w.create_shape(big);
  BodyDef floor;
  floor.motion = MotionType::Static;
  floor.shape = g;
  floor.position = Vec3(0, -1, 0);
  floor.user_data = 1000;
  p.bodies.push_back(w.create_body(floor));
  for (int k = 0; k < 24; ++k) {
    BodyDef d;
    d.shape = k % 3 == 0 ? p.ball : p.box;
    d.position = Vec3(Real((k % 4) - 1.5) * Real(1.1), Real(0.5 + 0.8 * (k / 4)),
                      Real(((k / 2) % 3) - 1) * Real(0.2));
    d.orientation = Quat(Eigen::AngleAxis<Real>(Real(0.1) * Real(k), Vec3::UnitY()));
    d.user_data = uint64_t(k);
    p.bodies.push_back(w.create_body(d));
  }
  BodyDef sensor;
  sensor.motion = MotionType::Static;
  sensor.shape = w.create_shape([] {
    ShapeDef s;
    s.type = ShapeType::Box;
    s.half_extents = Vec3(1, 1, 1);
    return s;
  }());
  sensor.position = Vec3(0, 1, 0);
  sensor.sensor = true;
  p.sensor = w.create_body(sensor);
  sensor.motion = MotionType::Kinematic;
  sensor.position = Vec3(-6, 1, 0);
  sensor.linear_velocity = Vec3(3, 0, 0);
  p.kinematic_sensor = w.create_body(sensor);
  return p;
}

void changes(World& w, Pile& p, int step) {
  if (step == 20) w.set_gravity_scale(p.bodies[4], -1);
  if (step == 35) w.set_motion_type(p.bodies[5], MotionType::Kinematic);
  if (step == 50) w.set_shape(p.bodies[6], p.big_ball);
  if (step == 60) w.set_gravity(Vec3(Real(0.5), Real(-9.81), 0));
  if (step == 70) w.set_motion_type(p.bodies[7], MotionType::Static);
  if (step == 80) w.set_damping(p.bodies[8], Real(0.3), Real(0.2));
  if (step == 90) w.set_sensor(p.bodies[9], true);
  if (step == 100) w.set_motion_type(p.bodies[5], MotionType::Dynamic);
  if (step == 110) w.set_gravity_scale(p.bodies[4], Real(0.5));
  if (step == 120) w.set_shape(p.bodies[10], p.ball);
  if (step == 140) w.set_motion_type(p.bodies[7], MotionType::Dynamic);
  if (step == 150) w.set_sensor(p.bodies[9], false);
  if (step == 160) w.destroy_body(p.bodies[2]);  // the last body (a sensor) moves into its index
  if (step == 170) w.set_motion_type(p.bodies[11], MotionType::Kinematic);
}

void record_events(const World& w, std::vector<uint32_t>& out) {
  for (const SensorBeginEvent& e : w.sensor_begin_events()) {
    out.insert(out.end(), {e.sensor.slot, e.visitor.slot, 1});
  }
  for (const SensorEndEvent& e : w.sensor_end_events()) {
    out.insert(out.end(), {e.sensor.slot, e.visitor.slot, 0});
  }
  out.push_back(UINT32_MAX);  // step separator
}

ChangeRun run(int threads, BroadphaseType broadphase) {
  WorldDef def;
  def.threads = threads;
  def.broadphase = broadphase;
  World w(def);
  Pile p = build(w);
  ChangeRun r;
  std::vector<uint8_t> snapshot;
  for (int step = 0; step < kSteps; ++step) {
    changes(w, p, step);
    if (step == kSnapshotStep) snapshot = save_snapshot(w);
    w.step(kDt);
    r.hashes.push_back(w.state_hash());
    record_events(w, r.sensor_events);
  }
  // The snapshot continues with the same bits, user data kept.
  World again = load_snapshot(snapshot);
  again.set_threads(threads);
  for (BodyId b : p.bodies) {
    if (!again.is_valid(b) || !w.is_valid(b)) continue;
    EXPECT_EQ(again.user_data(b), w.user_data(b));
  }
  EXPECT_TRUE(again.is_sensor(p.sensor));
  EXPECT_EQ(again.gravity_scale(p.bodies[4]), Real(0.5));  // set at step 110
  EXPECT_EQ(again.settings().gravity, Vec3(Real(0.5), Real(-9.81), 0));
  for (int step = kSnapshotStep; step < kSteps; ++step) {
    changes(again, p, step);
    again.step(kDt);
    r.hashes_after_snapshot.push_back(again.state_hash());
  }
  return r;
}

TEST(ApiChanges, SameBitsAndSensorEventsAtOneAndTwoThreadsAndBothBroadphases) {
  const ChangeRun base = run(1, BroadphaseType::SweepAndPrune);
  // The run did something: sensor events came, the bodies moved.
  std::size_t events = 0;
  for (uint32_t v : base.sensor_events) events += v != UINT32_MAX;
  EXPECT_GT(events, 6u);
  for (const auto& [threads, broadphase] :
       {std::pair{2, BroadphaseType::SweepAndPrune}, std::pair{2, BroadphaseType::AllPairs},
        std::pair{1, BroadphaseType::AllPairs}}) {
    const ChangeRun other = run(threads, broadphase);
    EXPECT_EQ(other.hashes, base.hashes) << threads << " threads";
    EXPECT_EQ(other.sensor_events, base.sensor_events) << threads << " threads";
  }
  // After the snapshot: the same bits as the uninterrupted run.
  EXPECT_EQ(base.hashes_after_snapshot,
            std::vector<uint64_t>(base.hashes.begin() + kSnapshotStep, base.hashes.end()));
}

TEST(ApiChanges, SnapshotRoundTripKeepsUserDataSensorsAndOverlaps) {
  World w;
  Pile p = build(w);
  for (int step = 0; step < 60; ++step) w.step(kDt);
  ShapeId shape = w.shape(p.bodies[1]);
  w.set_user_data(shape, 77);
  JointDef j;
  j.body_a = p.bodies[3];
  j.user_data = 88;
  const JointId joint = w.create_joint(j);
  w.set_hit_event_threshold(Real(2.5));
  const std::vector<uint8_t> bytes = save_snapshot(w);
  World back = load_snapshot(bytes);
  EXPECT_EQ(save_snapshot(back), bytes);
  EXPECT_EQ(back.user_data(shape), 77u);
  EXPECT_EQ(back.user_data(joint), 88u);
  EXPECT_EQ(back.user_data(p.bodies[0]), 1000u);
  EXPECT_EQ(back.user_data(p.bodies[20]), 19u);
  EXPECT_EQ(back.shape_def(shape).type, w.shape_def(shape).type);
  // The overlaps came along: stepping both gives the same events and bits.
  for (int step = 0; step < 60; ++step) {
    w.step(kDt);
    back.step(kDt);
    ASSERT_EQ(w.state_hash(), back.state_hash());
    ASSERT_EQ(w.sensor_begin_events().size(), back.sensor_begin_events().size());
    ASSERT_EQ(w.sensor_end_events().size(), back.sensor_end_events().size());
  }
  // Rollback restores the overlaps too.
  const std::vector<uint8_t> state = save_rollback(w);
  std::vector<uint32_t> first, second;
  for (int step = 0; step < 40; ++step) {
    w.step(kDt);
    record_events(w, first);
  }
  restore_rollback(w, state);
  for (int step = 0; step < 40; ++step) {
    w.step(kDt);
    record_events(w, second);
  }
  EXPECT_EQ(first, second);
}

}  // namespace api_changes_determinism_test
}  // namespace elan
