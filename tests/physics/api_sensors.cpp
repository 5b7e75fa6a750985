// SPDX-License-Identifier: MIT
// Sensors: a body falls through a sensor exactly as through empty space, and the sensor reports
// one begin and one end; static, kinematic and dynamic sensors; a sleeping visitor stays inside;
// destroying either body ends the overlap; sensors see no sensor and push nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "physics/physics_util.hpp"

namespace elan {
namespace api_sensors_test {

using test::kDt;

bool same_bits(const Vec3& a, const Vec3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(Real) * 3) == 0;
}

BodyId add(World& w, const ShapeDef& shape, const Vec3& p, MotionType motion, bool sensor) {
  BodyDef d;
  d.shape = w.create_shape(shape);
  d.position = p;
  d.motion = motion;
  d.sensor = sensor;
  return w.create_body(d);
}

struct Counts {
  int begins = 0, ends = 0;
  int begin_step = -1, end_step = -1;
};

void count(const World& w, BodyId sensor, BodyId visitor, int step, Counts& c) {
  for (const SensorBeginEvent& e : w.sensor_begin_events()) {
    EXPECT_EQ(e.sensor, sensor);
    EXPECT_EQ(e.visitor, visitor);
    ++c.begins;
    c.begin_step = step;
  }
  for (const SensorEndEvent& e : w.sensor_end_events()) {
    EXPECT_EQ(e.sensor, sensor);
    EXPECT_EQ(e.visitor, visitor);
    ++c.ends;
    c.end_step = step;
  }
}

// A ball of radius r dropped from rest at y0 through a static sensor box [-1, 1]^3. Free fall
// with k substeps of h: the centre after N substeps is y0 - g h^2 N (N + 1) / 2 (free_flight.cpp's
// closed form); the ball overlaps the box while |y| < 1 + r. The world without the sensor gives
// the ball the same bits: the sensor changes nothing of its motion.
TEST(Sensor, BallFallsThroughAStaticSensorAsInFreeFallWithOneBeginAndOneEnd) {
  const Real r = Real(0.25), y0 = 3;
  WorldDef def;
  def.threads = 1;
  World with(def), without(def);
  const BodyId sensor =
      add(with, test::box_shape(Vec3::Ones()), Vec3::Zero(), MotionType::Static, true);
  const BodyId ball = add(with, test::sphere_shape(r), Vec3(0, y0, 0), MotionType::Dynamic, false);
  const BodyId free_ball =
      add(without, test::sphere_shape(r), Vec3(0, y0, 0), MotionType::Dynamic, false);
  const double g = 9.81, h = double(kDt) / def.substeps;
  Counts c;
  for (int n = 1; n <= 90; ++n) {
    with.step(kDt);
    without.step(kDt);
    count(with, sensor, ball, n, c);
    ASSERT_TRUE(same_bits(with.center_of_mass(ball), without.center_of_mass(free_ball)));
    ASSERT_TRUE(same_bits(with.linear_velocity(ball), without.linear_velocity(free_ball)));
    EXPECT_TRUE(with.contact_begin_events().empty());
    EXPECT_EQ(with.contact_count(), 0u);
    const double substeps = double(n) * def.substeps;
    const double y = double(y0) - g * h * h * substeps * (substeps + 1) / 2;
    // Float: each of N substeps rounds y (|y| <= 30) and v once.
    ASSERT_NEAR(double(with.center_of_mass(ball).y()), y, 1e-5 * (1 + substeps * 0.01) * 30);
  }
  EXPECT_EQ(c.begins, 1);
  EXPECT_EQ(c.ends, 1);
  // The first step ending with the ball's bottom below the top (y < 1 + r), and the first ending
  // with its top below the bottom (y < -1 - r), by the closed form.
  auto first_step_below = [&](double level) {
    for (int n = 1;; ++n) {
      const double substeps = double(n) * def.substeps;
      if (double(y0) - g * h * h * substeps * (substeps + 1) / 2 < level) return n;
    }
  };
  EXPECT_EQ(c.begin_step, first_step_below(1 + double(r)));
  EXPECT_EQ(c.end_step, first_step_below(-1 - double(r)));
}

// A kinematic sensor sweeps over a ball resting (asleep) on the ground; a dynamic sensor falls
// onto (and through) a resting box. Each reports one begin and one end and moves nothing.
TEST(Sensor, KinematicAndDynamicSensorsReportAndPushNothing) {
  World w;
  add(w, test::plane_shape(Vec3::UnitY(), 0), Vec3::Zero(), MotionType::Static, false);
  const BodyId ball =
      add(w, test::sphere_shape(Real(0.5)), Vec3(0, Real(0.5), 0), MotionType::Dynamic, false);
  const BodyId block = add(w, test::box_shape(Vec3::Constant(Real(0.5))), Vec3(10, Real(0.5), 0),
                           MotionType::Dynamic, false);
  for (int n = 0; n < 120; ++n) w.step(kDt);
  ASSERT_FALSE(w.is_awake(ball));
  const Vec3 ball_at = w.center_of_mass(ball);
  const Vec3 block_at = w.center_of_mass(block);

  const BodyId sweeper =
      add(w, test::box_shape(Vec3(Real(0.3), 2, 2)), Vec3(-3, 1, 0), MotionType::Kinematic, true);
  w.set_linear_velocity(sweeper, Vec3(3, 0, 0));
  BodyDef drop;
  drop.shape = w.create_shape(test::sphere_shape(Real(0.4)));
  drop.position = Vec3(10, 3, 0);
  drop.sensor = true;
  const BodyId dropper = w.create_body(drop);
  int sweep_begin = 0, sweep_end = 0, drop_begin = 0, drop_end = 0;
  for (int n = 0; n < 150; ++n) {
    w.step(kDt);
    for (const SensorBeginEvent& e : w.sensor_begin_events()) {
      if (e.sensor == sweeper) {
        EXPECT_EQ(e.visitor, ball);
        ++sweep_begin;
      } else {
        EXPECT_EQ(e.sensor, dropper);
        // The dynamic sensor sees the box, and the static plane while it is awake.
        ++drop_begin;
      }
    }
    for (const SensorEndEvent& e : w.sensor_end_events()) {
      if (e.sensor == sweeper) {
        EXPECT_EQ(e.visitor, ball);
        ++sweep_end;
      } else {
        ++drop_end;
      }
    }
  }
  EXPECT_EQ(sweep_begin, 1);
  EXPECT_EQ(sweep_end, 1);
  EXPECT_EQ(drop_begin, 2);  // the box, then the plane
  EXPECT_EQ(drop_end, 1);    // left the box; it is still in the plane's half-space
  // Nothing was pushed: the ball and the box are where they were, bit for bit.
  EXPECT_TRUE(same_bits(w.center_of_mass(ball), ball_at));
  EXPECT_TRUE(same_bits(w.center_of_mass(block), block_at));
  EXPECT_LT(w.center_of_mass(dropper).y(), Real(-5));  // the dynamic sensor fell through
}

// A ball falls onto the ground inside a static sensor and goes to sleep there: the overlap
// holds while it sleeps (no end event); destroying the ball ends it at once.
TEST(Sensor, SleepingVisitorStaysInsideAndDestroyEndsTheOverlap) {
  World w;
  add(w, test::plane_shape(Vec3::UnitY(), 0), Vec3::Zero(), MotionType::Static, false);
  const BodyId sensor =
      add(w, test::box_shape(Vec3(2, 1, 2)), Vec3::Zero(), MotionType::Static, true);
  const BodyId ball =
      add(w, test::sphere_shape(Real(0.5)), Vec3(0, 2, 0), MotionType::Dynamic, false);
  Counts c;
  for (int n = 0; n < 240; ++n) {
    w.step(kDt);
    count(w, sensor, ball, n, c);
  }
  EXPECT_FALSE(w.is_awake(ball));
  EXPECT_EQ(c.begins, 1);
  EXPECT_EQ(c.ends, 0);
  w.destroy_body(ball);
  ASSERT_EQ(w.sensor_end_events().size(), 1u);
  EXPECT_EQ(w.sensor_end_events()[0].sensor, sensor);
  EXPECT_EQ(w.sensor_end_events()[0].visitor, ball);
  w.step(kDt);
  EXPECT_TRUE(w.sensor_end_events().empty());
  EXPECT_TRUE(w.sensor_begin_events().empty());
}

// Destroying the sensor ends its overlaps; a body that becomes a sensor ends its contacts and
// falls through; two sensors do not see each other.
TEST(Sensor, DestroyingTheSensorAndSetSensor) {
  World w;
  add(w, test::plane_shape(Vec3::UnitY(), 0), Vec3::Zero(), MotionType::Static, false);
  const BodyId sensor =
      add(w, test::box_shape(Vec3(2, 1, 2)), Vec3::Zero(), MotionType::Static, true);
  const BodyId other_sensor =
      add(w, test::box_shape(Vec3(2, 1, 2)), Vec3(1, 0, 0), MotionType::Kinematic, true);
  const BodyId box = add(w, test::box_shape(Vec3::Constant(Real(0.5))), Vec3(0, Real(0.5), 0),
                         MotionType::Dynamic, false);
  for (int n = 0; n < 30; ++n) w.step(kDt);
  EXPECT_TRUE(w.is_sensor(sensor));
  EXPECT_FALSE(w.is_sensor(box));
  EXPECT_EQ(w.contact_count(), 1u);  // the box on the plane
  w.destroy_body(sensor);
  ASSERT_EQ(w.sensor_end_events().size(), 1u);
  EXPECT_EQ(w.sensor_end_events()[0].visitor, box);

  w.set_sensor(box, true);
  EXPECT_TRUE(w.is_sensor(box));
  EXPECT_EQ(w.contact_count(), 0u);
  EXPECT_EQ(w.contact_end_events().size(), 1u);
  const Real y = w.center_of_mass(box).y();
  for (int n = 0; n < 30; ++n) {
    w.step(kDt);
    // The other sensor overlaps the box but sensors do not see sensors; the box now sees the
    // plane (it is an awake dynamic sensor).
    for (const SensorBeginEvent& e : w.sensor_begin_events()) EXPECT_NE(e.sensor, other_sensor);
  }
  EXPECT_LT(w.center_of_mass(box).y(), y - Real(0.5));  // falls through the plane
  w.set_sensor(box, false);
  EXPECT_FALSE(w.is_sensor(box));
}

}  // namespace api_sensors_test
}  // namespace elan
