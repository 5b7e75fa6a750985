// SPDX-License-Identifier: MIT
// Jointed piles settle: a heap of ragdolls dropped on a floor ends asleep or slow, and a joint
// grid hanging from its pins loses its swing; both end finite, with every joint within its limits
// and its anchors together.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "physics/physics_util.hpp"

namespace elan {
namespace joint_settling_test {

// How far a joint may be outside its limits (rad) and its anchors apart (m) once settled: the
// joints' soft rows settle a few mm and a few hundredths of a radian under the loads of a heap.
constexpr Real kAngleTolerance = Real(0.05);
constexpr Real kAnchorTolerance = Real(0.02);

struct Frames {
  Quat a0, b0;              // the bodies' orientations at creation (identity for the world)
  Vec3 anchor_a, anchor_b;  // each anchor in its body's shape frame
};

Quat orientation_or_identity(const World& world, BodyId id) {
  return id.is_null() ? Quat::Identity() : world.orientation(id);
}
Vec3 position_or_zero(const World& world, BodyId id) {
  return id.is_null() ? Vec3::Zero() : world.position(id);
}

std::vector<Frames> frames_at_creation(const World& world) {
  std::vector<Frames> out;
  for (std::size_t k = 0; k < world.joint_count(); ++k) {
    const JointDef& d = world.joint_def(world.joint_at(k));
    const Quat qa = orientation_or_identity(world, d.body_a);
    const Quat qb = orientation_or_identity(world, d.body_b);
    const Vec3 anchor_b = d.type == JointType::Distance ? d.anchor_b : d.anchor;
    out.push_back({qa, qb, qa.conjugate() * (d.anchor - position_or_zero(world, d.body_a)),
                   qb.conjugate() * (anchor_b - position_or_zero(world, d.body_b))});
  }
  return out;
}

// Checks every joint against its limits and its anchors, with the tolerances above.
void expect_joints_hold(const World& world, const std::vector<Frames>& frames) {
  for (std::size_t k = 0; k < world.joint_count(); ++k) {
    const JointId id = world.joint_at(k);
    const JointDef& d = world.joint_def(id);
    const Frames& f = frames[k];
    SCOPED_TRACE(testing::Message() << "joint " << k);
    const Quat qa = orientation_or_identity(world, d.body_a);
    const Quat qb = orientation_or_identity(world, d.body_b);
    if (d.type != JointType::Distance && d.type != JointType::Slider) {
      const Vec3 wa = position_or_zero(world, d.body_a) + qa * f.anchor_a;
      const Vec3 wb = position_or_zero(world, d.body_b) + qb * f.anchor_b;
      EXPECT_LT((wa - wb).norm(), kAnchorTolerance);
    }
    if (d.limits.enabled && (d.type == JointType::Hinge || d.type == JointType::Cone)) {
      const Real angle = world.joint_coordinate(id);
      EXPECT_GE(angle, d.limits.lower - kAngleTolerance);
      EXPECT_LE(angle, d.limits.upper + kAngleTolerance);
    }
    if (d.type == JointType::Cone) {
      // The swing: the angle between the axis as A carries it and as B carries it.
      const Vec3 axis_a = qa * (f.a0.conjugate() * d.axis);
      const Vec3 axis_b = qb * (f.b0.conjugate() * d.axis);
      const Real swing = std::acos(std::clamp(axis_a.dot(axis_b), Real(-1), Real(1)));
      EXPECT_LE(swing, d.swing_limit + kAngleTolerance);
    }
  }
}

// Every dynamic body asleep, or slower than `speed` (m/s, and rad/s times 0.3 m).
void expect_asleep_or_slow(const World& world, Real speed) {
  std::size_t slow = 0, dynamic = 0;
  for (std::size_t i = 0; i < world.body_count(); ++i) {
    const BodyId id = world.body_at(i);
    if (world.motion_type(id) != MotionType::Dynamic) continue;
    ++dynamic;
    const Real v =
        std::max(world.linear_velocity(id).norm(), Real(0.3) * world.angular_velocity(id).norm());
    if (!world.is_awake(id) || v < speed) {
      ++slow;
    } else {
      ADD_FAILURE() << "body " << i << " at " << world.position(id).transpose() << " moves at "
                    << world.linear_velocity(id).norm() << " m/s, "
                    << world.angular_velocity(id).norm() << " rad/s";
    }
  }
  EXPECT_EQ(slow, dynamic);
}

// Twelve ragdolls (192 bodies, 180 joints) in three crossed layers, dropped onto a floor.
TEST(JointSettling, RagdollHeapSettlesWithinItsLimits) {
  const std::string text = R"j({"bodies": [{"motion": "static",
      "shape": {"type": "box", "half_extents": [20, 1, 20]}, "position": [0, -1, 0]}],
    "generators": [
      {"type": "ragdoll", "origin": [-2, 0.5, 0.9], "orientation": [0.70710678, -0.70710678, 0, 0],
       "count": [3, 1, 2], "spacing": [2, 0, 2.2]},
      {"type": "ragdoll", "origin": [-2.1, 1.6, -1], "orientation": [0.5, -0.5, 0.5, 0.5],
       "count": [2, 1, 2], "spacing": [2.2, 0, 2.05]},
      {"type": "ragdoll", "origin": [0, 3.5, -1], "orientation": [0.70710678, 0, 0.70710678, 0],
       "count": [1, 1, 2], "spacing": [0, 0, 2.2]}]})j";
  const Scene scene = parse_scene(text, "heap");
  WorldDef def = scene.world;
  def.threads = 2;
  World world(def);
  load_into(scene, world, "heap");
  ASSERT_EQ(world.joint_count(), 12u * 15u);
  const std::vector<Frames> frames = frames_at_creation(world);
  const int steps = 600;
  for (int s = 0; s < steps; ++s) {
    world.step(scene.timestep);
    ASSERT_TRUE(test::all_finite(world)) << "step " << s;
  }
  expect_joints_hold(world, frames);
  expect_asleep_or_slow(world, Real(0.1));
}

// J: m g y summed over the dynamic bodies (gravity along -y).
double potential(const World& world) {
  double e = 0;
  for (std::size_t i = 0; i < world.body_count(); ++i) {
    const BodyId id = world.body_at(i);
    if (world.motion_type(id) != MotionType::Dynamic) continue;
    e += double(world.mass(id)) * 9.81 * double(world.center_of_mass(id).y());
  }
  return e;
}

// A 30 x 30 joint grid hanging from its seven middle pins (Box2D's joint_grid, smaller): it
// swings down and comes to hang, its joints together and its swinging dying away.
TEST(JointSettling, JointGridHangsFromItsPins) {
  const std::string text = R"j({"generators": [
      {"type": "joint_grid", "count": 30, "origin": [0, 30, 0]}]})j";
  const Scene scene = parse_scene(text, "grid");
  WorldDef def = scene.world;
  def.threads = 2;
  World world(def);
  load_into(scene, world, "grid");
  const std::vector<Frames> frames = frames_at_creation(world);
  double mass = 0;
  for (std::size_t i = 0; i < world.body_count(); ++i) mass += double(world.mass(world.body_at(i)));
  const double start = double(world.kinetic_energy()) + potential(world);
  double peak = 0;
  const int steps = 1200;
  for (int s = 0; s < steps; ++s) {
    world.step(scene.timestep);
    ASSERT_TRUE(test::all_finite(world)) << "step " << s;
    peak = std::max(peak, double(world.kinetic_energy()));
  }
  expect_joints_hold(world, frames);
  // No damping but the soft rows': the curtain swings down and its swinging dies away slowly.
  // Energy is only lost (kinetic plus potential below the start), the kinetic energy is under 5 %
  // of its peak, and the bodies' rms speed under 0.15 m/s.
  const double ke = double(world.kinetic_energy());
  EXPECT_LT(ke + potential(world), start);
  EXPECT_LT(ke, 0.05 * peak);
  EXPECT_LT(std::sqrt(2 * ke / mass), 0.15);
}

}  // namespace joint_settling_test
}  // namespace elan
