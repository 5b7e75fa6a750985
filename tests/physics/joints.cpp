// SPDX-License-Identifier: MIT
// Joints against closed forms: a physical pendulum's period and amplitude, a hinge limit under
// gravity, a torque-limited motor, a slider spring's frequency, a rope's free fall and hang, a
// weld tumbling as one body, a heavy chain's stretch, and break_force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "physics/physics_util.hpp"

namespace elan {
namespace joints_test {

using test::add_body;
using test::at;
using test::kDt;

constexpr Real kG = Real(9.81);
constexpr Real kPi = Real(3.14159265358979323846);

World make_world(const Vec3& gravity = Vec3(0, -kG, 0), int threads = 1) {
  WorldDef def;
  def.gravity = gravity;
  def.allow_sleep = false;
  def.threads = threads;
  return World(def);
}

// The hinge's world anchor as body A carries it (A's shape frame keeps it where it was).
Vec3 carried(const World& world, BodyId body, const Vec3& local) {
  return world.position(body) + world.orientation(body) * local;
}

// Rotates `body` about the world point `pivot` by `angle` about `axis`.
void turn_about(World& world, BodyId body, const Vec3& pivot, const Vec3& axis, Real angle) {
  const Quat r(Eigen::AngleAxis<Real>(angle, axis.normalized()));
  world.set_orientation(body, (r * world.orientation(body)).normalized());
  world.set_position(body, pivot + r * (world.position(body) - pivot));
}

// A rod of 1 m (a 0.1 x 1 x 0.1 box) hangs from a hinge at its top end, axis z; released from
// theta0 = 0.3 rad. Physical pendulum: T0 = 2 pi sqrt(I_p / (m g d)), I_p = m (w^2 + l^2) / 12
// + m d^2, d = 0.5 m, with the finite-amplitude series T = T0 (1 + theta0^2 / 16 +
// 11 theta0^4 / 3072) (error below 1e-5 at 0.3 rad). The period is timed over the zero
// crossings of 10 s (about 6 periods) to within a step (1/60 s over 6 periods: 0.17 %).
TEST(Joints, HingePendulumPeriodAmplitudeAndAnchor) {
  World world = make_world();
  const Vec3 pivot(0, 2, 0);
  const BodyId rod = add_body(world, test::box_shape(Vec3(Real(0.05), Real(0.5), Real(0.05))),
                              at(pivot - Vec3(0, Real(0.5), 0)));
  JointDef j;
  j.type = JointType::Hinge;
  j.body_a = rod;
  j.anchor = pivot;
  j.axis = Vec3::UnitZ();
  const JointId hinge = world.create_joint(j);
  const Vec3 local_anchor(0, Real(0.5), 0);
  const Real theta0 = Real(0.3);
  turn_about(world, rod, pivot, Vec3::UnitZ(), theta0);
  EXPECT_NEAR(world.joint_coordinate(hinge), theta0, 1e-5);

  const Real d = Real(0.5);
  const Real i_pivot = (Real(0.01) + Real(1)) / 12 + d * d;  // per kg
  const Real t0 = 2 * kPi * std::sqrt(i_pivot / (kG * d));
  const Real expected = t0 * (1 + theta0 * theta0 / 16 + 11 * std::pow(theta0, 4) / 3072);

  std::vector<Real> crossings;  // times of downward zero crossings, interpolated
  Real previous = world.joint_coordinate(hinge);
  Real last_amplitude = 0, max_anchor_error = 0;
  const int steps = 600;
  for (int s = 1; s <= steps; ++s) {
    world.step(kDt);
    const Real angle = world.joint_coordinate(hinge);
    if (previous > 0 && angle <= 0) {
      crossings.push_back((Real(s) - 1 + previous / (previous - angle)) * kDt);
    }
    if (s > steps - 120) last_amplitude = std::max(last_amplitude, std::abs(angle));
    max_anchor_error =
        std::max(max_anchor_error, (carried(world, rod, local_anchor) - pivot).norm());
    previous = angle;
  }
  ASSERT_GE(crossings.size(), 5u);
  const Real period = (crossings.back() - crossings.front()) / Real(crossings.size() - 1);
  EXPECT_NEAR(period, expected, Real(0.01) * expected) << "T0 " << t0;
  EXPECT_NEAR(last_amplitude, theta0, Real(0.05) * theta0);
  EXPECT_LT(max_anchor_error, Real(0.002));
  // The motion stays in the hinge's plane.
  EXPECT_LT(std::abs(world.position(rod).z()), Real(1e-4));
}

// A 1 m rod pivoted at its end, horizontal along +x: gravity turns it about -z, down to the lower
// limit -0.4 rad, where it must rest (within 0.02 rad) without swinging past it by 0.05 rad.
TEST(Joints, HingeLimitHoldsRodUnderGravity) {
  World world = make_world();
  const Vec3 pivot(0, 2, 0);
  const BodyId rod = add_body(world, test::box_shape(Vec3(Real(0.5), Real(0.05), Real(0.05))),
                              at(pivot + Vec3(Real(0.5), 0, 0)));
  JointDef j;
  j.type = JointType::Hinge;
  j.body_a = rod;
  j.anchor = pivot;
  j.axis = Vec3::UnitZ();
  j.limits = {true, Real(-0.4), Real(0.4)};
  const JointId hinge = world.create_joint(j);
  Real lowest = 0;
  for (int s = 0; s < 180; ++s) {
    world.step(kDt);
    lowest = std::min(lowest, world.joint_coordinate(hinge));
  }
  EXPECT_NEAR(world.joint_coordinate(hinge), Real(-0.4), Real(0.02));
  EXPECT_GT(lowest, Real(-0.45));
  EXPECT_LT(world.angular_velocity(rod).norm(), Real(0.01));
  // The limit carries the rod's weight moment about the pivot: m g d.
  const Real mass = world.mass(rod);
  EXPECT_NEAR(world.joint_torque(hinge).z(), mass * kG * Real(0.5) * std::cos(Real(0.4)),
              Real(0.02) * mass * kG * Real(0.5));
}

// A wheel (a 1 x 0.2 x 1 box, I = m (1 + 1) / 12 about y) on a vertical hinge through its centre,
// motor speed 4 rad/s with torque limit tau: w(t) = tau t / I until it reaches 4, then stays.
TEST(Joints, MotorAcceleratesAtTorqueLimitThenHoldsSpeed) {
  World world = make_world();
  const BodyId wheel =
      add_body(world, test::box_shape(Vec3(Real(0.5), Real(0.1), Real(0.5))), at(Vec3(0, 1, 0)));
  const Real inertia = world.mass(wheel) * 2 / 12;
  JointDef j;
  j.type = JointType::Hinge;
  j.body_a = wheel;
  j.anchor = Vec3(0, 1, 0);
  j.axis = Vec3::UnitY();
  const Real tau = Real(0.5) * inertia;  // 0.5 rad/s^2: 8 s to reach 4 rad/s
  j.motor = {true, 4, tau};
  const JointId hinge = world.create_joint(j);
  for (int s = 1; s <= 600; ++s) {
    world.step(kDt);
    const Real t = Real(s) * kDt;
    const Real w = world.angular_velocity(wheel).y();
    if (s == 240) {
      EXPECT_NEAR(w, tau * t / inertia, Real(0.01) * tau * t / inertia);
    }
  }
  EXPECT_NEAR(world.angular_velocity(wheel).y(), 4, Real(0.01) * 4);
  EXPECT_LT(std::hypot(world.angular_velocity(wheel).x(), world.angular_velocity(wheel).z()),
            Real(1e-3));
  // At speed the motor needs no torque (no friction): the reading shows it.
  EXPECT_LT(std::abs(world.joint_torque(hinge).y()), Real(0.05) * tau);
  // Speed and torque change at runtime: a reversed motor brakes at the limit.
  world.set_joint_motor(hinge, {true, -4, tau});
  world.step(kDt);
  EXPECT_NEAR(world.angular_velocity(wheel).y(), 4 - tau * kDt / inertia, Real(1e-3));
}

// A 1 kg-class box on a horizontal slider to the world with a 1 Hz undamped spring, pulled 0.1 m
// along the axis: it oscillates at 1 Hz (the soft spring's frequency is that of the row's
// effective mass, which for a body against the world is the body's mass). Gravity pulls across
// the axis; the body must neither turn nor leave the axis.
TEST(Joints, SliderSpringOscillatesAtItsFrequency) {
  World world = make_world();
  const BodyId box = add_body(world, test::box_shape(Vec3::Constant(Real(0.2))), at(Vec3(0, 1, 0)));
  JointDef j;
  j.type = JointType::Slider;
  j.body_a = box;
  j.anchor = Vec3(0, 1, 0);
  j.axis = Vec3(1, 0, 1);  // diagonal in the ground plane
  const Real hz = 1;
  j.spring = {true, hz, 0, 0};
  const JointId slider = world.create_joint(j);
  const Vec3 axis = Vec3(1, 0, 1).normalized();
  world.set_position(box, Vec3(0, 1, 0) + Real(0.1) * axis);
  EXPECT_NEAR(world.joint_coordinate(slider), Real(0.1), 1e-5);
  std::vector<Real> crossings;
  Real previous = world.joint_coordinate(slider);
  Real off_axis = 0, turned = 0;
  for (int s = 1; s <= 360; ++s) {
    world.step(kDt);
    const Real x = world.joint_coordinate(slider);
    if (previous > 0 && x <= 0)
      crossings.push_back((Real(s) - 1 + previous / (previous - x)) * kDt);
    const Vec3 offset = world.position(box) - Vec3(0, 1, 0);
    off_axis = std::max(off_axis, (offset - offset.dot(axis) * axis).norm());
    turned = std::max(turned,
                      Real(2 * std::acos(std::min(Real(1), std::abs(world.orientation(box).w())))));
    previous = x;
  }
  ASSERT_GE(crossings.size(), 4u);
  const Real period = (crossings.back() - crossings.front()) / Real(crossings.size() - 1);
  EXPECT_NEAR(period, 1 / hz, Real(0.01) / hz);
  EXPECT_LT(off_axis, Real(0.002));
  EXPECT_LT(turned, Real(1e-3));
}

// A rope of 2 m (distance joint, min 0) from a fixed point to a ball that starts 1 m below it:
// the ball falls freely (y = y0 - g t^2 / 2) for sqrt(2 / g) = 0.45 s, then hangs at 2 m.
TEST(Joints, RopeFallsFreelyThenHangsAtItsLength) {
  World world = make_world();
  const Vec3 top(0, 5, 0);
  const BodyId ball = add_body(world, test::sphere_shape(Real(0.1)), at(top - Vec3(0, 1, 0)));
  JointDef j;
  j.type = JointType::Distance;
  j.body_a = ball;
  j.anchor = top - Vec3(0, 1, 0);
  j.anchor_b = top;
  j.min_length = 0;
  j.max_length = 2;
  const JointId rope = world.create_joint(j);
  for (int s = 1; s <= 24; ++s) world.step(kDt);  // 0.4 s: still slack
  const Real t = 24 * kDt;
  // Substepped semi-implicit Euler: x error g h t / 2 (free_flight.cpp), h = dt / 4.
  EXPECT_NEAR(world.position(ball).y(), 4 - kG * t * t / 2, kG * (kDt / 4) * t / 2 + 1e-4);
  EXPECT_LT(world.joint_force(rope).norm(), Real(1e-6));
  for (int s = 0; s < 156; ++s) world.step(kDt);
  EXPECT_NEAR(world.joint_coordinate(rope), 2, Real(0.005));
  EXPECT_LT(world.linear_velocity(ball).norm(), Real(0.05));
  // It carries the ball's weight.
  EXPECT_NEAR(world.joint_force(rope).y(), world.mass(ball) * kG,
              Real(0.02) * world.mass(ball) * kG);
}

// Two boxes welded side by side in zero gravity, one struck off-centre: they tumble as one body.
// The weld's impulses are equal and opposite, so linear momentum is conserved to rounding, and
// angular momentum about the origin as well as the soft rows allow (0.5 %); the relative pose
// stays within the weld's settling error.
TEST(Joints, WeldTumblesAsOneBody) {
  World world = make_world(Vec3::Zero());
  const BodyId a =
      add_body(world, test::box_shape(Vec3(Real(0.5), Real(0.2), Real(0.3))), at(Vec3(0, 0, 0)));
  const BodyId b = add_body(world, test::box_shape(Vec3(Real(0.3), Real(0.3), Real(0.3))),
                            at(Vec3(Real(0.8), 0, 0)));
  JointDef j;
  j.type = JointType::Fixed;
  j.body_a = a;
  j.body_b = b;
  j.has_anchor = false;
  world.create_joint(j);
  world.apply_impulse(a, Vec3(0, 300, 100), Vec3(Real(-0.5), 0, Real(0.2)));
  const Vec3 p0 = world.linear_momentum();
  const Vec3 l0 = world.angular_momentum();
  const Quat rel0 = world.orientation(a).conjugate() * world.orientation(b);
  const Vec3 offset0 = world.orientation(a).conjugate() * (world.position(b) - world.position(a));
  for (int s = 0; s < 300; ++s) {
    world.step(kDt);
    const Quat rel = world.orientation(a).conjugate() * world.orientation(b);
    const Vec3 offset = world.orientation(a).conjugate() * (world.position(b) - world.position(a));
    ASSERT_LT(rel0.angularDistance(rel), Real(0.01)) << "step " << s;
    ASSERT_LT((offset - offset0).norm(), Real(0.005)) << "step " << s;
  }
  EXPECT_LT((world.linear_momentum() - p0).norm(), Real(1e-3) * p0.norm());
  EXPECT_LT((world.angular_momentum() - l0).norm(), Real(0.005) * l0.norm());
  EXPECT_GT(world.angular_velocity(a).norm(), Real(0.5));  // it does tumble
}

// Ten 0.1 kg capsule links of 0.2 m on ball joints at their ends, hung from a fixed point, and a
// 10 kg ball (100 times a link) on the last, swinging. Returns the chain's worst stretch (top to
// the weight's centre over its rest length, minus 1) over 5 s, and at the end.
struct Stretch {
  Real worst = 0, at_end = 0;
};
Stretch heavy_chain_stretch(int iterations, Real constraint_hertz) {
  WorldDef def;
  def.allow_sleep = false;
  def.threads = 1;
  def.iterations = iterations;
  World world(def);
  const Vec3 top(0, 5, 0);
  const int links = 10;
  const Real length = Real(0.2);
  BodyId previous;  // null: the world
  for (int k = 0; k <= links; ++k) {
    const bool weight = k == links;
    BodyDef d = at(top - Vec3(0, length * (Real(k) + Real(0.5)), 0));
    d.mass = weight ? Real(10) : Real(0.1);
    const BodyId body = add_body(
        world, weight ? test::sphere_shape(Real(0.1)) : test::capsule_shape(Real(0.03), Real(0.07)),
        d);
    JointDef j;
    j.type = JointType::Ball;
    j.body_a = body;
    j.body_b = previous;
    j.anchor = top - Vec3(0, length * Real(k), 0);
    j.constraint_hertz = constraint_hertz;
    world.create_joint(j);
    previous = body;
  }
  const BodyId weight = previous;
  const Real rest = length * (Real(links) + Real(0.5));
  world.apply_linear_impulse(weight, Vec3(10, 0, 0));  // a swing: the links are loaded unevenly
  Stretch out;
  for (int s = 0; s < 300; ++s) {
    world.step(kDt);
    EXPECT_TRUE(test::all_finite(world));
    out.worst = std::max(out.worst, (world.position(weight) - top).norm() / rest - 1);
  }
  out.at_end = (world.position(weight) - top).norm() / rest - 1;
  return out;
}

// With the chain's joints as stiff as the substep rate (constraint_hertz 240 at 60 steps of 4
// substeps, set on each joint, so Gauss-Seidel solves them) and 16 iterations, the chain
// stretches under 1 %: a soft row's static error is F / (m_eff omega^2), small once omega is
// high, and the iterations carry the load up the chain. At the defaults (92 Hz, 2 iterations)
// Gauss-Seidel alone let it stretch 6 %; the loaded point rows are now solved directly
// (solver/direct_solve.hpp), and the bound is 1 % at the defaults as well.
TEST(Joints, HeavyWeightOnLightChainStretchesLittle) {
  const Stretch stiff = heavy_chain_stretch(16, 240);
  EXPECT_LT(stiff.worst, Real(0.01));
  EXPECT_LT(std::abs(stiff.at_end), Real(0.01));
  const Stretch defaults = heavy_chain_stretch(2, 0);
  std::printf("heavy chain at the defaults: worst stretch %.5f, at the end %.5f\n",
              double(defaults.worst), double(defaults.at_end));
  EXPECT_LT(defaults.worst, Real(0.01));
  EXPECT_LT(std::abs(defaults.at_end), Real(0.01));
}

// A 1 kg ball hangs from a ball joint with break_force 15 N: its weight (9.81 N) holds; a 10 N
// push down added in one step raises the force to about 19.8 N and breaks it in that step,
// with an event; the ball then falls freely.
TEST(Joints, BreakForceBreaksInTheStepItIsExceeded) {
  World world = make_world();
  BodyDef d = at(Vec3(0, 2, 0));
  d.mass = 1;
  const BodyId ball = add_body(world, test::sphere_shape(Real(0.1)), d);
  JointDef j;
  j.type = JointType::Ball;
  j.body_a = ball;
  j.anchor = Vec3(0, Real(2.5), 0);
  j.break_force = 15;
  const JointId joint = world.create_joint(j);
  for (int s = 0; s < 30; ++s) world.step(kDt);
  ASSERT_TRUE(world.is_valid(joint));
  EXPECT_NEAR(world.joint_force(joint).y(), kG, Real(0.05) * kG);
  EXPECT_TRUE(world.joint_removed_events().empty());
  world.apply_force(ball, Vec3(0, -10, 0));
  world.step(kDt);
  EXPECT_FALSE(world.is_valid(joint));
  ASSERT_EQ(world.joint_removed_events().size(), 1u);
  const JointRemovedEvent& e = world.joint_removed_events()[0];
  EXPECT_EQ(e.joint, joint);
  EXPECT_EQ(e.body_a, ball);
  EXPECT_TRUE(e.body_b.is_null());
  EXPECT_EQ(e.reason, JointRemoval::Broke);
  EXPECT_GT(e.force, 15);
  EXPECT_EQ(world.joint_count(), 0u);
  const Real v0 = world.linear_velocity(ball).y();
  for (int s = 0; s < 30; ++s) world.step(kDt);
  EXPECT_NEAR(world.linear_velocity(ball).y(), v0 - kG * 30 * kDt, Real(1e-3));
  world.step(kDt);
  EXPECT_TRUE(world.joint_removed_events().empty());
}

// Joint friction: a wheel (a 1 x 0.2 x 1 box) spun at 6 rad/s on a vertical hinge with friction
// torque tau slows at tau / I to rest and stays; a cube on a cone joint at its centre, spun about
// a tilted axis, slows the same way about that axis (its inertia is isotropic, and the friction
// impulse opposes the relative angular velocity).
TEST(Joints, FrictionStopsTheTurnAtItsTorque) {
  World world = make_world();
  const BodyId wheel =
      add_body(world, test::box_shape(Vec3(Real(0.5), Real(0.1), Real(0.5))), at(Vec3(0, 1, 0)));
  const BodyId cube =
      add_body(world, test::box_shape(Vec3::Constant(Real(0.3))), at(Vec3(3, 1, 0)));
  const Real i_wheel = world.mass(wheel) * 2 / 12;
  const Real i_cube = world.mass(cube) * Real(0.36) * 2 / 12;
  JointDef hinge;
  hinge.type = JointType::Hinge;
  hinge.body_a = wheel;
  hinge.anchor = Vec3(0, 1, 0);
  hinge.axis = Vec3::UnitY();
  hinge.friction = 2 * i_wheel;  // 2 rad/s^2: at rest after 3 s
  world.create_joint(hinge);
  JointDef cone;
  cone.type = JointType::Cone;
  cone.body_a = cube;
  cone.anchor = Vec3(3, 1, 0);
  cone.axis = Vec3::UnitY();
  cone.friction = 2 * i_cube;
  world.create_joint(cone);
  const Vec3 spin_axis = Vec3(1, 2, 2).normalized();
  world.set_angular_velocity(wheel, Vec3(0, 6, 0));
  world.set_angular_velocity(cube, 6 * spin_axis);
  for (int s = 1; s <= 240; ++s) {
    world.step(kDt);
    const Real expected = std::max(Real(0), 6 - 2 * Real(s) * kDt);
    ASSERT_NEAR(world.angular_velocity(wheel).y(), expected, Real(0.02)) << "step " << s;
    ASSERT_NEAR(world.angular_velocity(cube).dot(spin_axis), expected, Real(0.02)) << "step " << s;
  }
  EXPECT_LT(world.angular_velocity(cube).norm(), Real(1e-3));
}

}  // namespace joints_test
}  // namespace elan
