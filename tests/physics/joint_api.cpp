// SPDX-License-Identifier: MIT
// The joint API's promises beyond the closed forms of joints.cpp: jointed bodies do not collide
// unless collide_connected, destroying a body removes its joints with events, runtime changes
// take effect, and every bad argument throws elan::Error naming its field.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "physics/physics_util.hpp"

namespace elan {
namespace joint_api_test {

using test::add_body;
using test::at;
using test::kDt;
using test::zero_gravity_world;

// Two unit spheres 0.8 m apart (overlapping 0.2 m) on a slack rope: without collide_connected
// no contact acts and they stay at rest; with it the contact pushes them apart, conserving their
// (zero) momentum.
TEST(JointApi, JointedBodiesCollideOnlyWhenConnectedCollisionIsAsked) {
  for (bool collide : {false, true}) {
    SCOPED_TRACE(collide);
    World world = zero_gravity_world();
    const BodyId a = add_body(world, test::sphere_shape(Real(0.5)), at(Vec3(0, 1, 0)));
    const BodyId b = add_body(world, test::sphere_shape(Real(0.5)), at(Vec3(Real(0.8), 1, 0)));
    JointDef j;
    j.type = JointType::Distance;
    j.body_a = a;
    j.body_b = b;
    j.anchor = world.position(a);
    j.anchor_b = world.position(b);
    j.min_length = 0;
    j.max_length = 5;
    j.collide_connected = collide;
    world.create_joint(j);
    bool touched = false;
    for (int s = 0; s < 30; ++s) {
      world.step(kDt);
      touched = touched || !world.contact_begin_events().empty();
    }
    const Real gap = (world.position(b) - world.position(a)).norm();
    if (collide) {
      EXPECT_TRUE(touched);
      EXPECT_GT(gap, Real(0.95));  // pushed out of the overlap
    } else {
      EXPECT_FALSE(touched);
      EXPECT_EQ(gap, Real(0.8));
      EXPECT_EQ(world.linear_velocity(a), Vec3::Zero());
    }
    EXPECT_LT(world.linear_momentum().norm(), Real(1e-3));
  }
}

// Destroying a body removes its joints, each with a BodyDestroyed event in joint order (the
// destroyed body's id already stale); the others stay; events clear at the next step.
TEST(JointApi, DestroyingABodyRemovesItsJointsWithEvents) {
  World world = zero_gravity_world();
  const BodyId a = add_body(world, test::sphere_shape(Real(0.2)), at(Vec3(0, 1, 0)));
  const BodyId b = add_body(world, test::sphere_shape(Real(0.2)), at(Vec3(1, 1, 0)));
  const BodyId c = add_body(world, test::sphere_shape(Real(0.2)), at(Vec3(2, 1, 0)));
  auto ball = [&](BodyId x, BodyId y, const Vec3& anchor) {
    JointDef j;
    j.body_a = x;
    j.body_b = y;
    j.anchor = anchor;
    return world.create_joint(j);
  };
  const JointId ab = ball(a, b, Vec3(Real(0.5), 1, 0));
  const JointId a_world = ball(a, {}, Vec3(0, 2, 0));
  const JointId bc = ball(c, b, Vec3(Real(1.5), 1, 0));
  world.destroy_body(b);
  EXPECT_FALSE(world.is_valid(ab));
  EXPECT_FALSE(world.is_valid(bc));
  EXPECT_TRUE(world.is_valid(a_world));
  EXPECT_EQ(world.joint_count(), 1u);
  ASSERT_EQ(world.joint_removed_events().size(), 2u);
  const JointRemovedEvent& first = world.joint_removed_events()[0];
  const JointRemovedEvent& second = world.joint_removed_events()[1];
  EXPECT_EQ(first.joint, ab);
  EXPECT_EQ(first.body_a, a);
  EXPECT_EQ(first.body_b, b);
  EXPECT_EQ(second.joint, bc);
  EXPECT_EQ(second.body_a, c);
  EXPECT_EQ(first.reason, JointRemoval::BodyDestroyed);
  EXPECT_EQ(second.reason, JointRemoval::BodyDestroyed);
  EXPECT_EQ(first.force, 0);
  world.step(kDt);
  EXPECT_TRUE(world.joint_removed_events().empty());
  EXPECT_THROW(world.joint_force(ab), Error);
}

// A rigid distance joint (1 m) lengthened to 2 m at runtime holds the body at the new length.
TEST(JointApi, LengthsChangedAtRuntimeHold) {
  WorldDef def;
  def.allow_sleep = false;
  def.threads = 1;
  World world(def);
  const BodyId ball = add_body(world, test::sphere_shape(Real(0.1)), at(Vec3(0, 4, 0)));
  JointDef j;
  j.type = JointType::Distance;
  j.body_a = ball;
  j.anchor = Vec3(0, 4, 0);
  j.anchor_b = Vec3(0, 5, 0);
  const JointId rod = world.create_joint(j);
  for (int s = 0; s < 30; ++s) world.step(kDt);
  EXPECT_NEAR(world.joint_coordinate(rod), 1, Real(0.005));
  world.set_joint_lengths(rod, 2, 2);
  for (int s = 0; s < 120; ++s) world.step(kDt);
  EXPECT_NEAR(world.joint_coordinate(rod), 2, Real(0.005));
}

// Each bad argument throws elan::Error whose field names it.
std::string field_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.field();
  }
  return "(no error)";
}

TEST(JointApi, BadArgumentsNameTheirField) {
  World world = zero_gravity_world();
  const BodyId a = add_body(world, test::sphere_shape(Real(0.2)), at(Vec3(0, 1, 0)));
  const BodyId ground = test::add_ground(world);
  JointDef good;
  good.type = JointType::Hinge;
  good.body_a = a;
  good.anchor = Vec3(0, 1, 0);
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  auto with = [&](auto change) {
    JointDef d = good;
    change(d);
    return field_of([&] { world.create_joint(d); });
  };
  EXPECT_EQ(with([](JointDef& d) { d.body_a = BodyId{}; }), "body_a");
  EXPECT_EQ(with([&](JointDef& d) { d.body_b = a; }), "body_b");
  EXPECT_EQ(with([&](JointDef& d) { d.body_a = ground; }), "bodies");
  EXPECT_EQ(with([](JointDef& d) { d.axis = Vec3::Zero(); }), "axis");
  EXPECT_EQ(with([&](JointDef& d) { d.anchor.x() = nan; }), "anchor");
  EXPECT_EQ(with([](JointDef& d) { d.limits = {true, 1, -1}; }), "limits");
  EXPECT_EQ(with([](JointDef& d) { d.limits = {true, -4, 0}; }), "limits");
  EXPECT_EQ(with([](JointDef& d) { d.motor = {true, 1, -1}; }), "motor.max_force");
  EXPECT_EQ(with([](JointDef& d) { d.spring = {true, 0, 0, 0}; }), "spring.frequency");
  EXPECT_EQ(with([](JointDef& d) { d.spring = {true, 1, -1, 0}; }), "spring.damping_ratio");
  EXPECT_EQ(with([](JointDef& d) { d.friction = -1; }), "friction");
  EXPECT_EQ(with([&](JointDef& d) { d.constraint_hertz = nan; }), "constraint_hertz");
  EXPECT_EQ(with([](JointDef& d) { d.constraint_damping_ratio = -1; }), "constraint_damping_ratio");
  EXPECT_EQ(with([](JointDef& d) { d.break_force = 0; }), "break_force");
  EXPECT_EQ(with([](JointDef& d) {
              d.type = JointType::Cone;
              d.swing_limit = 4;
            }),
            "swing_limit");
  EXPECT_EQ(with([](JointDef& d) {
              d.type = JointType::Distance;
              d.min_length = 2;
              d.max_length = 1;
            }),
            "min_length");

  const JointId id = world.create_joint(good);
  EXPECT_EQ(field_of([&] { world.set_joint_motor(id, {true, 1, -1}); }), "motor.max_force");
  EXPECT_EQ(field_of([&] { world.set_joint_spring(id, {true, -1, 0, 0}); }), "spring.frequency");
  EXPECT_EQ(field_of([&] { world.set_joint_limits(id, {true, 1, 0}); }), "limits");
  EXPECT_EQ(field_of([&] { world.set_joint_swing_limit(id, -1); }), "swing_limit");
  EXPECT_EQ(field_of([&] { world.set_joint_lengths(id, 2, 1); }), "min_length");
  EXPECT_EQ(field_of([&] { world.set_joint_lengths(id, 1, nan); }), "max_length");
  EXPECT_EQ(field_of([&] { world.set_joint_friction(id, nan); }), "friction");
  world.destroy_joint(id);
  EXPECT_EQ(field_of([&] { world.destroy_joint(id); }), "joint");
  EXPECT_EQ(field_of([&] { world.joint_coordinate(id); }), "joint");
  EXPECT_EQ(field_of([&] { world.joint_at(5); }), "index");
  EXPECT_EQ(world.joint_count(), 0u);
}

}  // namespace joint_api_test
}  // namespace elan
