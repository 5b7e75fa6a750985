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

}  // namespace tunneling_test
}  // namespace elan
