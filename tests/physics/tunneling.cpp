// SPDX-License-Identifier: MIT
// No tunneling: a small fast sphere must never end up beyond a thin wall (static) or a thin
// plate (dynamic), though it travels several times their thickness in one step.
#include <gtest/gtest.h>

#include "physics/physics_util.hpp"

namespace elan {
namespace tunneling_test {

using test::add_body;
using test::at;
using test::kDt;
using test::zero_gravity_world;

// 150 m/s is 2.5 m per step against a 4 cm wall: without continuous handling the sphere
// (5 cm radius) jumps over it in one step. The centre must stay before the wall's mid-plane,
// x < 0, at every step.
TEST(Tunneling, FastSphereStopsAtThinStaticWall) {
  World world = zero_gravity_world();
  add_body(world, test::box_shape(Vec3(Real(0.02), 2, 2)), at(Vec3::Zero(), MotionType::Static));
  BodyDef d = at(Vec3(-3, Real(0.1), 0));
  d.linear_velocity = Vec3(150, 0, 0);
  const BodyId ball = add_body(world, test::sphere_shape(Real(0.05)), d);
  for (int n = 1; n <= 60; ++n) {
    world.step(kDt);
    ASSERT_LT(world.center_of_mass(ball).x(), Real(0))
        << "sphere passed the wall at step " << n << ", v " << world.linear_velocity(ball).x();
  }
  EXPECT_LE(world.linear_velocity(ball).x(), Real(0)) << "sphere still moving into the wall";
}

// A free 1 m x 1 m x 2 cm plate (20 kg) hit at 120 m/s by a 0.52 kg sphere: the plate is pushed
// but the sphere's centre must stay on the near side of the plate's mid-plane, measured in the
// plate's frame, at every step.
TEST(Tunneling, FastSphereStaysInFrontOfThinDynamicPlate) {
  World world = zero_gravity_world();
  const BodyId plate =
      add_body(world, test::box_shape(Vec3(Real(0.01), Real(0.5), Real(0.5))), at(Vec3::Zero()));
  BodyDef d = at(Vec3(-3, Real(0.1), Real(-0.05)));
  d.linear_velocity = Vec3(120, 0, 0);
  const BodyId ball = add_body(world, test::sphere_shape(Real(0.05)), d);
  for (int n = 1; n <= 60; ++n) {
    world.step(kDt);
    const Transform plate_pose{world.position(plate), world.orientation(plate)};
    const Vec3 local = plate_pose.apply_inverse(world.center_of_mass(ball));
    const bool beside = std::abs(local.y()) > Real(0.55) || std::abs(local.z()) > Real(0.55);
    ASSERT_TRUE(local.x() < 0 || beside)
        << "sphere passed through the plate at step " << n << ", local " << local.transpose();
  }
  EXPECT_GT(world.linear_velocity(plate).x(), Real(0)) << "the plate was never hit";
}

// The reproducer physics_fast_1e4_embeds_in_ground_and_wall.json (issue 42): a 0.2 m ball fired
// at 1e4 m/s (167 m a step) along x, 0.5 m over a static floor (top face y = 0), hits a stack of
// boxes that bends its path down. The broadphase swept its box along its starting velocity only,
// so the floor was no pair of it: it ended 0.9 m inside the floor after step 1, and later inside
// the static wall (x in [9.5, 10.5], y in [0, 10], z in [-5, 5]). The continuous stage now looks
// for static bodies along the path taken. Bound: the ball's surface never more than 5 cm (a
// quarter of its radius) inside the floor or the wall, at every step; a soft contact resting or
// hit hard gives a few millimetres.
TEST(Tunneling, FastBallBentDownByABoxStaysOutOfTheFloorAndTheWall) {
  WorldDef def;
  def.threads = 1;
  World world(def);
  add_body(world, test::box_shape(Vec3(50, 1, 50)), at(Vec3(0, -1, 0), MotionType::Static));
  const Vec3 wall_centre(10, 5, 0), wall_half(Real(0.5), 5, 5);
  add_body(world, test::box_shape(wall_half), at(wall_centre, MotionType::Static));
  const ShapeDef cube = test::box_shape(Vec3::Constant(Real(0.5)));
  auto fired = [&](const ShapeDef& shape, const Vec3& p, const Vec3& v) {
    BodyDef d = at(p);
    d.linear_velocity = v;
    return add_body(world, shape, d);
  };
  fired(cube, Vec3(0, 1, 0), Vec3(1e4, 0, 0));
  const Real radius = Real(0.2);
  const BodyId ball = fired(test::sphere_shape(radius), Vec3(-5, Real(0.7), 2), Vec3(1e4, 0, 0));
  fired(cube, Vec3(3, 20, -2), Vec3(0, -1e4, 0));
  fired(cube, Vec3(-20, Real(0.5), -5), Vec3(1e4, 0, 0));
  fired(cube, Vec3(20, Real(0.5), -5), Vec3(-1e4, 0, 0));
  for (int i = 0; i < 5; ++i) add_body(world, cube, at(Vec3(5, Real(0.5) + Real(i), 2)));
  const Real allowed = Real(0.05);
  for (int n = 1; n <= 120; ++n) {
    world.step(kDt);
    ASSERT_TRUE(test::all_finite(world));
    const Vec3 c = world.center_of_mass(ball);
    ASSERT_GE(c.y() - radius, -allowed)
        << "ball inside the floor at step " << n << ": " << c.transpose();
    // Distance from the ball's centre to the wall's box (0 inside it).
    const Vec3 outside = ((c - wall_centre).cwiseAbs() - wall_half).cwiseMax(Real(0));
    ASSERT_GE(outside.norm(), radius - allowed)
        << "ball inside the wall at step " << n << ": " << c.transpose();
  }
}

}  // namespace tunneling_test
}  // namespace elan
