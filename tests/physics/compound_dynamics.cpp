// SPDX-License-Identifier: MIT
// Compound bodies in motion: torque-free tumbling conserves angular momentum and energy; a
// compound of one child moves as that child does as a plain body; a table rests on its legs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "physics/geometry_util.hpp"

namespace elan {
namespace compound_dynamics_test {

using test::add_body;
using test::at;
using test::kDt;
using test::zero_gravity_world;

// An L with a sphere off to one side: three principal moments that differ, and a centre of mass
// off the compound's frame, so the body turns about a point that is none of its children's.
ShapeDef lopsided() {
  ShapeDef s = test::l_shape();
  s.children.push_back(test::child(test::sphere_shape(Real(0.15)), Vec3(0, 0, Real(0.3))));
  return s;
}

// Torque-free: the world angular momentum is constant, and so is the energy L . w / 2. The
// integrator conserves L to rounding (the free-flight tests hold a box to 1e-3 over 10 s); the
// energy wanders by the rotation's truncation error only (the same tests allow 2 %).
TEST(CompoundDynamics, TumblingConservesAngularMomentumAndEnergy) {
  World world = zero_gravity_world();
  BodyDef d = at(Vec3(1, 2, 3));
  d.orientation = Quat(Eigen::AngleAxis<Real>(Real(0.5), Vec3(1, -1, 2).normalized()));
  d.angular_velocity = Vec3(2, Real(-1.5), 3);
  d.linear_velocity = Vec3(Real(0.3), 0, Real(-0.2));
  const BodyId body = add_body(world, lopsided(), d);
  const Vec3 l0 = world.angular_momentum() -
                  world.mass(body) * world.center_of_mass(body).cross(world.linear_velocity(body));
  const Real e0 = world.kinetic_energy();
  const Vec3 p0 = world.linear_momentum();
  ASSERT_GT(l0.norm(), Real(0));
  double worst_l = 0, worst_e = 0;
  for (int n = 0; n < 600; ++n) {  // 10 s
    world.step(kDt);
    // About the centre of mass: L_world - m c x v.
    const Vec3 l = world.angular_momentum() -
                   world.mass(body) * world.center_of_mass(body).cross(world.linear_velocity(body));
    worst_l = std::max(worst_l, double((l - l0).norm() / l0.norm()));
    worst_e = std::max(worst_e, double(std::abs(world.kinetic_energy() - e0) / e0));
  }
  EXPECT_LT(worst_l, 1e-3);
  EXPECT_LT(worst_e, 0.02);
  EXPECT_LT((world.linear_momentum() - p0).norm(), 1e-4 * p0.norm());
}

// A compound of one child is that child: the same mass, the same centre of mass, and the same
// motion. The child sits at an offset and a turn in the compound's frame, so the compound's frame
// is not the child's; the centre of mass and the child's orientation must still agree. The two
// bodies' principal frames may differ by a relabelling of equal-looking axes, so their bits
// differ by rounding: the runs chosen are not chaotic (a torque-free spin about a stable axis
// mix, and a box sliding flat to rest), and are compared to 1 mm and 1e-4 in the quaternion.
struct OneChild {
  ShapeDef box = test::box_shape(Vec3(Real(0.4), Real(0.2), Real(0.3)));
  Vec3 offset = Vec3(Real(0.7), Real(-0.2), Real(0.1));
  Quat turn = Quat(Eigen::AngleAxis<Real>(Real(0.6), Vec3::UnitY()));
  ShapeDef compound() const {
    ShapeDef s;
    s.type = ShapeType::Compound;
    s.children.push_back(test::child(box, offset, turn));
    return s;
  }
  // The compound's frame placed so that its child lands where `plain` puts the box.
  BodyDef placed(const BodyDef& plain) const {
    BodyDef d = plain;
    d.orientation = plain.orientation * turn.conjugate();
    d.position = plain.position - d.orientation * offset;
    return d;
  }
};

void expect_same_motion(World& plain_world, World& compound_world, const BodyDef& plain,
                        int steps) {
  const OneChild one;
  const BodyId a = test::add_body(plain_world, one.box, plain);
  const BodyId b = test::add_body(compound_world, one.compound(), one.placed(plain));
  EXPECT_NEAR(plain_world.mass(a), compound_world.mass(b), 1e-6 * plain_world.mass(a));
  double worst = 0, worst_q = 0;
  for (int n = 0; n <= steps; ++n) {
    if (n > 0) {
      plain_world.step(kDt);
      compound_world.step(kDt);
    }
    worst = std::max(
        worst, double((plain_world.center_of_mass(a) - compound_world.center_of_mass(b)).norm()));
    const Quat q_child = compound_world.orientation(b) * one.turn;
    worst_q = std::max(worst_q, 1 - std::abs(double(plain_world.orientation(a).dot(q_child))));
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(worst_q, 1e-4);
}

TEST(CompoundDynamics, OneChildSpinsAsThePlainBody) {
  World plain_world = zero_gravity_world(), compound_world = zero_gravity_world();
  BodyDef plain = at(Vec3(0, 2, 0));
  plain.orientation = Quat(Eigen::AngleAxis<Real>(Real(0.3), Vec3(1, 0, 1).normalized()));
  plain.angular_velocity = Vec3(Real(0.2), 3, Real(-0.1));  // mostly about the major axis
  plain.linear_velocity = Vec3(1, 0, 0);
  expect_same_motion(plain_world, compound_world, plain, 120);
}

TEST(CompoundDynamics, OneChildSlidesToRestAsThePlainBody) {
  WorldDef def;
  def.threads = 1;
  World plain_world(def), compound_world(def);
  test::add_ground(plain_world);
  test::add_ground(compound_world);
  BodyDef plain = at(Vec3(0, Real(0.2), 0));  // resting on its face
  plain.orientation = Quat(Eigen::AngleAxis<Real>(Real(0.4), Vec3::UnitY()));
  plain.linear_velocity = Vec3(2, 0, 1);
  expect_same_motion(plain_world, compound_world, plain, 120);
}

// A table dropped upright on the ground stands on its four legs: its frame's height is the legs'
// length above the ground (feet at y = -0.3 in its frame), within the solver's resting
// penetration (a few mm), and it falls asleep.
TEST(CompoundDynamics, TableRestsOnItsLegs) {
  WorldDef def;
  def.threads = 1;
  World world(def);
  test::add_ground(world);
  const BodyId table = add_body(world, test::table_shape(), at(Vec3(0, 1, 0)));
  for (int n = 0; n < 300; ++n) world.step(kDt);
  EXPECT_NEAR(world.position(table).y(), 0.3, 0.005);
  const Vec3 up = world.orientation(table) * Vec3::UnitY();
  EXPECT_GT(up.y(), 1 - 1e-4) << "level";
  EXPECT_FALSE(world.is_awake(table));
}

}  // namespace compound_dynamics_test
}  // namespace elan
