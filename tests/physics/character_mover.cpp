// SPDX-License-Identifier: MIT
// The character mover on a flat ground: slides along a wall without entering it, climbs a step
// lower than its step height and stops at a higher one, climbs a gentle slope and not a steep
// one. The capsule: radius 0.3 m, segment half 0.6 m (0.9 m from centre to foot), skin 1 cm.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "elan/world.hpp"

namespace elan {
namespace character_mover_test {

constexpr Real kFoot = Real(0.9);            // centre to the lowest point of the capsule
constexpr Real kStand = kFoot + Real(0.01);  // centre height standing on y = 0 at the skin gap
// The casts stop between half the skin and the skin from a surface plus the advancement's
// tolerance (1e-4 of the ground box's 14 m radius): the gap kept is within 1 cm of the skin.
constexpr Real kGapTol = Real(0.01);

struct Scene {
  World w;
  BodyId ground;
  Scene() {
    ShapeDef slab;
    slab.type = ShapeType::Box;
    slab.half_extents = Vec3(10, 0.5f, 10);
    ground = box(slab.half_extents, Vec3(0, -0.5f, 0));
  }
  BodyId box(const Vec3& half, const Vec3& at, const Quat& q = Quat::Identity()) {
    ShapeDef d;
    d.type = ShapeType::Box;
    d.half_extents = half;
    BodyDef b;
    b.motion = MotionType::Static;
    b.shape = w.create_shape(d);
    b.position = at;
    b.orientation = q;
    return w.create_body(b);
  }
};

CharacterMoveDef mover() {
  CharacterMoveDef d;
  d.radius = 0.3f;
  d.half_height = 0.6f;
  d.step_height = 0.3f;
  d.max_slope = Real(M_PI / 4);
  d.skin = 0.01f;
  d.max_iterations = 4;
  return d;
}

TEST(CharacterMover, WalksOnFlatGround) {
  Scene s;
  const auto r = s.w.move_character(Vec3(0, kStand, 0), Vec3(2, 0, 1), mover());
  EXPECT_NEAR(r.position.x(), 2, 1e-4f);
  EXPECT_NEAR(r.position.z(), 1, 1e-4f);
  EXPECT_NEAR(r.position.y(), kStand, 1e-5f);
  EXPECT_TRUE(r.on_ground);
  EXPECT_EQ(r.ground_body, s.ground);
  EXPECT_NEAR(r.ground_normal.y(), 1, 1e-4f);
}

// Moving (3, 0, 2) towards a wall whose face is at x = 1.5: the capsule stops with its side
// the skin from the face (centre x = 1.5 - 0.3 - skin) and slides the whole 2 m along z.
TEST(CharacterMover, SlidesAlongAWallWithoutEnteringIt) {
  Scene s;
  s.box(Vec3(0.5f, 2, 5), Vec3(2, 2, 0));
  const CharacterMoveDef d = mover();
  const auto r = s.w.move_character(Vec3(0, kStand, 0), Vec3(3, 0, 2), d);
  EXPECT_LE(r.position.x(), 1.5f - 0.3f - 0.004f);
  EXPECT_GE(r.position.x(), 1.5f - 0.3f - 0.01f - kGapTol);
  EXPECT_NEAR(r.position.z(), 2, 0.02f);
  EXPECT_NEAR(r.position.y(), kStand, 0.005f);
  EXPECT_TRUE(r.on_ground);
  // Deterministic: the same call, the same bits.
  const auto again = s.w.move_character(Vec3(0, kStand, 0), Vec3(3, 0, 2), d);
  EXPECT_EQ(again.position, r.position);
}

// A 0.2 m step (lower than the 0.3 m step height) from x = 1.5 on: the capsule ends on it,
// 0.2 m higher, the whole 3 m along.
TEST(CharacterMover, ClimbsAStepLowerThanItsStepHeight) {
  Scene s;
  const BodyId step = s.box(Vec3(2, 0.1f, 5), Vec3(3.5f, 0.1f, 0));
  const auto r = s.w.move_character(Vec3(0, kStand, 0), Vec3(3, 0, 0), mover());
  EXPECT_NEAR(r.position.x(), 3, 0.02f);
  EXPECT_NEAR(r.position.y(), kStand + 0.2f, kGapTol);
  EXPECT_TRUE(r.on_ground);
  EXPECT_EQ(r.ground_body, step);
}

// A 0.45 m step is higher than the step height: the capsule stops at its face.
TEST(CharacterMover, StopsAtAStepHigherThanItsStepHeight) {
  Scene s;
  s.box(Vec3(2, 0.225f, 5), Vec3(3.5f, 0.225f, 0));
  const auto r = s.w.move_character(Vec3(0, kStand, 0), Vec3(3, 0, 0), mover());
  EXPECT_LE(r.position.x(), 1.5f - 0.3f + 0.001f);
  EXPECT_GE(r.position.x(), 1.5f - 0.3f - 0.01f - kGapTol);
  EXPECT_NEAR(r.position.y(), kStand, 0.005f);
}

// A ramp rising from x = 1.5 at angle a: its top face has normal (-sin a, cos a, 0).
BodyId ramp(Scene& s, Real a) {
  const Vec3 n(-std::sin(a), std::cos(a), 0), u(std::cos(a), std::sin(a), 0);
  const Vec3 centre = Vec3(1.5f, 0, 0) + u * 2.9f - n * 0.1f;
  return s.box(Vec3(3, 0.1f, 5), centre, Quat(Eigen::AngleAxis<Real>(a, Vec3::UnitZ())));
}

// 20 degrees (under the 45 degree limit): walking 3 m into it takes the capsule up it.
TEST(CharacterMover, ClimbsAGentleSlope) {
  Scene s;
  const BodyId r20 = ramp(s, Real(20 * M_PI / 180));
  const auto r = s.w.move_character(Vec3(0, kStand, 0), Vec3(3, 0, 0), mover());
  EXPECT_GT(r.position.y(), kStand + 0.3f);
  EXPECT_GT(r.position.x(), 2);
  EXPECT_TRUE(r.on_ground);
  EXPECT_EQ(r.ground_body, r20);
}

// 60 degrees (over the limit) is a wall: the capsule rises no more than it may step, and goes no
// farther than where its side meets the slope's foot.
TEST(CharacterMover, DoesNotClimbASteepSlope) {
  Scene s;
  ramp(s, Real(60 * M_PI / 180));
  const auto r = s.w.move_character(Vec3(0, kStand, 0), Vec3(3, 0, 0), mover());
  EXPECT_LT(r.position.y(), kStand + 0.02f);
  EXPECT_LT(r.position.x(), 1.5f);
}

TEST(CharacterMover, BadSettingsNameTheField) {
  Scene s;
  CharacterMoveDef d = mover();
  d.radius = 0;
  EXPECT_THROW(s.w.move_character(Vec3::Zero(), Vec3::UnitX(), d), Error);
  d = mover();
  d.max_slope = 2;
  EXPECT_THROW(s.w.move_character(Vec3::Zero(), Vec3::UnitX(), d), Error);
  EXPECT_THROW(s.w.move_character(Vec3::Zero(), Vec3(NAN, 0, 0), mover()), Error);
}

}  // namespace character_mover_test
}  // namespace elan
