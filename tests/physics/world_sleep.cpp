// SPDX-License-Identifier: MIT
// World::set_sleep_enabled (Box2D's b2World_EnableSleeping): switched off it wakes every body
// and keeps them awake; back on, a body sleeps again only after resting the full time to sleep;
// snapshots keep the setting; the setter gives the bits of WorldDef::allow_sleep, and setting
// the value the world already has changes no bit.
#include <gtest/gtest.h>

#include <vector>

#include "physics/physics_util.hpp"

namespace elan {
namespace world_sleep_test {

using test::add_body;
using test::at;
using test::kDt;

// The solver's time to sleep (solver/solve.hpp): an island sleeps once it has been slower than
// the threshold for 0.5 s, i.e. after at least 0.5 / (1/60) = 30 steps of rest.
constexpr int kStepsToSleep = 30;

// Steps until `body` is asleep; -1 if it still is not after `limit` steps.
int steps_until_asleep(World& w, BodyId body, int limit) {
  for (int n = 1; n <= limit; ++n) {
    w.step(kDt);
    if (!w.is_awake(body)) return n;
  }
  return -1;
}

// A box resting on the ground from its first step.
World resting_box(BodyId& box, bool allow_sleep = true) {
  WorldDef def;
  def.threads = 1;
  def.allow_sleep = allow_sleep;
  World w(def);
  test::add_ground(w);
  box = add_body(w, test::box_shape(Vec3(Real(0.5), Real(0.5), Real(0.5))),
                 at(Vec3(0, Real(0.5), 0)));
  return w;
}

TEST(WorldSleep, OffWakesAndKeepsAwakeOnSleepsAgainAfterTheFullTime) {
  BodyId box;
  World w = resting_box(box);
  EXPECT_TRUE(w.sleep_enabled());
  const int first = steps_until_asleep(w, box, 240);
  ASSERT_GE(first, kStepsToSleep);

  w.set_sleep_enabled(false);
  EXPECT_FALSE(w.sleep_enabled());
  EXPECT_FALSE(w.settings().allow_sleep);
  EXPECT_TRUE(w.is_awake(box)) << "switching sleep off wakes every body";
  for (int n = 0; n < 4 * first; ++n) {
    w.step(kDt);
    ASSERT_TRUE(w.is_awake(box)) << "step " << n;
  }
  // Resting all that time counted for nothing: after switching on, the full time again.
  w.set_sleep_enabled(true);
  EXPECT_TRUE(w.is_awake(box));
  const int again = steps_until_asleep(w, box, 240);
  EXPECT_GE(again, kStepsToSleep);
  EXPECT_LE(again, first) << "it rests already, so it needs no longer than from the start";

  // A body put to sleep explicitly while sleep is off stays asleep until woken.
  w.set_sleep_enabled(false);
  w.sleep(box);
  for (int n = 0; n < 10; ++n) w.step(kDt);
  EXPECT_FALSE(w.is_awake(box));
  w.wake(box);
  w.step(kDt);
  EXPECT_TRUE(w.is_awake(box));
}

TEST(WorldSleep, SnapshotsKeepTheSetting) {
  BodyId box;
  World w = resting_box(box);
  w.set_sleep_enabled(false);
  const std::vector<uint8_t> off = save_snapshot(w);
  EXPECT_FALSE(load_snapshot(off).sleep_enabled());
  BodyId other;
  World on = resting_box(other);
  ASSERT_TRUE(on.sleep_enabled());
  restore_snapshot(on, off);
  EXPECT_FALSE(on.sleep_enabled());
  // And the restored world keeps its box awake, as the one it came from.
  for (int n = 0; n < 3 * kStepsToSleep; ++n) on.step(kDt);
  EXPECT_TRUE(on.is_awake(on.body_at(1)));
  w.set_sleep_enabled(true);
  restore_snapshot(w, save_snapshot(on));
  EXPECT_FALSE(w.sleep_enabled());
}

// A few boxes dropped on the ground, left to settle and sleep, with `each_step` called before
// every step; returns the state hash after each step.
template <class F>
std::vector<uint64_t> dropped_boxes(bool allow_sleep, F&& each_step) {
  WorldDef def;
  def.threads = 2;
  def.allow_sleep = allow_sleep;
  World w(def);
  test::add_ground(w);
  const ShapeDef box = test::box_shape(Vec3(Real(0.4), Real(0.3), Real(0.5)));
  for (int i = 0; i < 6; ++i) {
    BodyDef d = at(Vec3(Real(0.2) * Real(i % 3), Real(0.5) + Real(0.7) * Real(i), Real(0.1) * i));
    d.orientation = Quat(Eigen::AngleAxis<Real>(Real(0.3) * Real(i), Vec3::UnitY()));
    add_body(w, box, d);
  }
  std::vector<uint64_t> hashes;
  for (int n = 0; n < 240; ++n) {
    each_step(w);
    w.step(kDt);
    hashes.push_back(w.state_hash());
  }
  return hashes;
}

TEST(WorldSleep, TheSetterGivesTheBitsOfTheDefinitionAndTheSameValueChangesNothing) {
  const auto nothing = [](World&) {};
  const std::vector<uint64_t> on = dropped_boxes(true, nothing);
  const std::vector<uint64_t> off = dropped_boxes(false, nothing);
  ASSERT_NE(on, off) << "the boxes sleep within 240 steps, which changes the bits";
  // The default value set again before every step: the same bits as never calling it.
  EXPECT_EQ(dropped_boxes(true, [](World& w) { w.set_sleep_enabled(true); }), on);
  EXPECT_EQ(dropped_boxes(false, [](World& w) { w.set_sleep_enabled(false); }), off);
  // Switched off before the first step: the bits of a world made with sleep off.
  EXPECT_EQ(dropped_boxes(true,
                          [](World& w) {
                            if (w.sleep_enabled()) w.set_sleep_enabled(false);
                          }),
            off);
}

}  // namespace world_sleep_test
}  // namespace elan
