// SPDX-License-Identifier: MIT
// The body changes of issue 39 against closed forms: gravity scale and world gravity, damping,
// motion type, shape; user data; every bad argument raises elan::Error naming its field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "physics/physics_util.hpp"

namespace elan {
namespace api_body_changes_test {

using test::add_body;
using test::at;
using test::kDt;

bool same_bits(const Vec3& a, const Vec3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(Real) * 3) == 0;
}

template <class F>
std::string error_field(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.field();
  }
  return "(no error)";
}

// Gravity scale 0 floats exactly; -1 rises with the bits a world of reversed gravity gives
// (s g = -1 x -9.81 = +9.81 exactly), which is free fall's closed form upwards:
// y_N = y0 + g h^2 N (N + 1) / 2 after N substeps of h (free_flight.cpp).
TEST(GravityScale, ZeroFloatsAndMinusOneRisesExactly) {
  WorldDef def;
  def.threads = 1;
  World w(def);
  WorldDef up_def = def;
  up_def.gravity = Vec3(0, Real(9.81), 0);
  World up(up_def);
  BodyDef d = at(Vec3(0, 5, 0));
  d.gravity_scale = 0;
  const BodyId floater = add_body(w, test::sphere_shape(Real(0.5)), d);
  d.position = Vec3(5, 5, 0);
  d.gravity_scale = -1;
  const BodyId riser = add_body(w, test::sphere_shape(Real(0.5)), d);
  d.gravity_scale = 1;
  const BodyId reference = add_body(up, test::sphere_shape(Real(0.5)), d);
  EXPECT_EQ(w.gravity_scale(floater), Real(0));
  EXPECT_EQ(w.gravity_scale(riser), Real(-1));
  const double g = 9.81, h = double(kDt) / def.substeps;
  for (int n = 1; n <= 60; ++n) {
    w.step(kDt);
    up.step(kDt);
    ASSERT_EQ(w.center_of_mass(floater), Vec3(0, 5, 0));
    ASSERT_EQ(w.linear_velocity(floater), Vec3::Zero());
    ASSERT_TRUE(same_bits(w.center_of_mass(riser), up.center_of_mass(reference)));
    const double substeps = double(n) * def.substeps;
    ASSERT_NEAR(double(w.center_of_mass(riser).y()), 5 + g * h * h * substeps * (substeps + 1) / 2,
                1e-4);
  }
  // Back to 1 between steps: it now falls, v = -g t over the next second.
  w.set_gravity_scale(riser, 1);
  const Real v0 = w.linear_velocity(riser).y();
  for (int n = 0; n < 60; ++n) w.step(kDt);
  EXPECT_NEAR(double(w.linear_velocity(riser).y()), double(v0) - g * 1.0, 1e-3);
}

// World gravity changed mid-flight: v changes by the new gravity over the following steps.
TEST(WorldGravity, ChangeTakesEffectAtTheNextStepAndWakesBodies) {
  World w;
  const BodyId ball = add_body(w, test::sphere_shape(Real(0.5)), at(Vec3(0, 5, 0)));
  w.step(kDt);
  const Vec3 g2(3, 0, -2);
  w.set_gravity(g2);
  EXPECT_EQ(w.settings().gravity, g2);
  const Vec3 v0 = w.linear_velocity(ball);
  for (int n = 0; n < 30; ++n) w.step(kDt);
  EXPECT_LT((w.linear_velocity(ball) - (v0 + g2 * (30 * kDt))).norm(), Real(1e-4));
  // A sleeping body wakes under new gravity.
  w.sleep(ball);
  w.set_gravity(Vec3(0, -9.81f, 0));
  EXPECT_TRUE(w.is_awake(ball));
  EXPECT_EQ(error_field([&] { w.set_gravity(Vec3(0, NAN, 0)); }), "gravity");
  EXPECT_EQ(error_field([&] { w.set_gravity(Vec3(0, 1e9f, 0)); }), "gravity");
}

// Damping set between steps: v_N = v0 / (1 + h d)^N (free_flight.cpp's discrete closed form).
TEST(Damping, SetDampingFollowsTheDiscreteClosedForm) {
  World w = test::zero_gravity_world();
  BodyDef d = at(Vec3::Zero());
  d.linear_velocity = Vec3(2, 0, 0);
  const BodyId b = add_body(w, test::sphere_shape(Real(0.5)), d);
  w.set_damping(b, Real(0.5), Real(0.25));
  EXPECT_EQ(w.linear_damping(b), Real(0.5));
  EXPECT_EQ(w.angular_damping(b), Real(0.25));
  for (int n = 0; n < 60; ++n) w.step(kDt);
  const double h = double(kDt) / 4;
  EXPECT_NEAR(double(w.linear_velocity(b).x()), 2 / std::pow(1 + h * 0.5, 240), 1e-5);
  EXPECT_EQ(error_field([&] { w.set_damping(b, -1, 0); }), "linear_damping");
  EXPECT_EQ(error_field([&] { w.set_damping(b, 0, NAN); }), "angular_damping");
  EXPECT_EQ(error_field([&] { w.set_gravity_scale(b, INFINITY); }), "gravity_scale");
  EXPECT_EQ(error_field([&] { w.set_gravity_scale(b, 1e6f); }), "gravity_scale");
  EXPECT_EQ(error_field([&] { w.set_damping(BodyId{}, 0, 0); }), "body");
}

// Static -> dynamic: falls with mass density x volume; dynamic -> kinematic keeps its velocity,
// stops feeling gravity and leaves its contacts; -> static stops dead.
TEST(MotionType, ChangesBetweenStepsRebuildMassContactsAndSleep) {
  World w;
  test::add_ground(w);
  BodyDef d = at(Vec3(0, 3, 0), MotionType::Static);
  d.density = 500;
  const BodyId box = add_body(w, test::box_shape(Vec3(Real(0.5), Real(0.25), Real(1))), d);
  EXPECT_EQ(w.mass(box), Real(0));
  w.set_motion_type(box, MotionType::Dynamic);
  EXPECT_EQ(w.motion_type(box), MotionType::Dynamic);
  EXPECT_NEAR(w.mass(box), Real(500 * 1 * 0.5 * 2), Real(1e-3));  // rho x 8 hx hy hz
  EXPECT_TRUE(w.is_awake(box));
  for (int n = 0; n < 120; ++n) w.step(kDt);
  // Resting on the ground (top at y = 0): centre at hy = 0.25.
  EXPECT_NEAR(w.center_of_mass(box).y(), Real(0.25), Real(0.01));
  EXPECT_GT(w.contact_count(), 0u);

  w.set_linear_velocity(box, Vec3(1, 0, 0));
  w.set_motion_type(box, MotionType::Kinematic);
  EXPECT_EQ(w.mass(box), Real(0));
  EXPECT_EQ(w.contact_count(), 0u);  // kinematic-static pairs are not collided
  EXPECT_EQ(w.contact_end_events().size(), 1u);
  const Vec3 p0 = w.center_of_mass(box);
  for (int n = 0; n < 60; ++n) w.step(kDt);
  EXPECT_LT((w.center_of_mass(box) - (p0 + Vec3(1, 0, 0))).norm(), Real(1e-4));

  w.set_motion_type(box, MotionType::Static);
  EXPECT_EQ(w.linear_velocity(box), Vec3::Zero());
  const Vec3 p1 = w.center_of_mass(box);
  w.step(kDt);
  EXPECT_EQ(w.center_of_mass(box), p1);

  // A given mass survives the trip through static.
  w.set_motion_type(box, MotionType::Dynamic);
  w.set_mass(box, 7);
  w.set_motion_type(box, MotionType::Kinematic);
  w.set_motion_type(box, MotionType::Dynamic);
  EXPECT_NEAR(w.mass(box), Real(7), Real(1e-5));

  BodyDef pd = at(Vec3::Zero(), MotionType::Static);
  const BodyId plane = add_body(w, test::plane_shape(Vec3::UnitY(), -5), pd);
  EXPECT_EQ(error_field([&] { w.set_motion_type(plane, MotionType::Dynamic); }), "motion");
  EXPECT_EQ(error_field([&] { w.set_motion_type(box, MotionType(7)); }), "motion");
  EXPECT_EQ(w.motion_type(plane), MotionType::Static);
}

// A joint keeps a dynamic body: the change that would leave it none is refused.
TEST(MotionType, AJointKeepsOneDynamicBody) {
  World w;
  const BodyId a = add_body(w, test::sphere_shape(Real(0.5)), at(Vec3::Zero()));
  JointDef j;
  j.type = JointType::Ball;
  j.body_a = a;
  j.anchor = Vec3(0, 1, 0);
  w.create_joint(j);
  EXPECT_EQ(error_field([&] { w.set_motion_type(a, MotionType::Kinematic); }), "motion");
  EXPECT_EQ(w.motion_type(a), MotionType::Dynamic);
}

// set_shape: the shape frame stays put, mass and inertia follow at the body's density; a given
// mass sets that density. I of a solid sphere: 2/5 m r^2.
TEST(SetShape, MassAndInertiaFollowAtTheBodysDensity) {
  World w = test::zero_gravity_world();
  BodyDef d = at(Vec3(1, 2, 3));
  d.density = 100;
  const BodyId b = add_body(w, test::box_shape(Vec3::Constant(Real(0.5))), d);  // 1 m^3
  EXPECT_NEAR(w.mass(b), Real(100), Real(1e-4));
  const ShapeId ball = w.create_shape(test::sphere_shape(1));
  w.set_shape(b, ball);
  EXPECT_EQ(w.shape(b), ball);
  const double m = 100 * 4.0 / 3.0 * M_PI;
  EXPECT_NEAR(double(w.mass(b)), m, 1e-3);
  EXPECT_LT((w.inertia(b) - Mat3::Identity() * Real(0.4 * m)).norm(), Real(1e-2));
  EXPECT_EQ(w.position(b), Vec3(1, 2, 3));
  // A hull whose centre of mass is off its origin: the shape frame stays, the centre moves.
  ShapeDef hull;
  hull.type = ShapeType::ConvexHull;
  hull.points = {Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(1, 1, 0), Vec3(1, 0, 1), Vec3(2, 1, 1)};
  w.set_shape(b, w.create_shape(hull));
  EXPECT_LT((w.position(b) - Vec3(1, 2, 3)).norm(), Real(1e-5));
  EXPECT_GT(w.center_of_mass(b).x(), Real(2));
  // Given mass: density = m / V of the old shape.
  w.set_shape(b, ball);
  w.set_mass(b, 10);
  w.set_shape(b, w.create_shape(test::sphere_shape(2)));  // 8 x the volume
  EXPECT_NEAR(w.mass(b), Real(80), Real(1e-3));

  ShapeDef mesh;
  mesh.type = ShapeType::Mesh;
  mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)};
  mesh.triangles = {{0, 1, 2}};
  EXPECT_EQ(error_field([&] { w.set_shape(b, w.create_shape(mesh)); }), "shape");
  EXPECT_EQ(error_field([&] { w.set_shape(b, ShapeId{}); }), "shape");
  const ShapeId gone = w.create_shape(test::sphere_shape(1));
  w.destroy_shape(gone);
  EXPECT_EQ(error_field([&] { w.set_shape(b, gone); }), "shape");
}

TEST(UserData, BodiesShapesAndJointsKeepTheirValues) {
  World w;
  ShapeDef s = test::sphere_shape(Real(0.5));
  s.user_data = 11;
  BodyDef d = at(Vec3::Zero());
  d.user_data = 22;
  d.shape = w.create_shape(s);
  const BodyId b = w.create_body(d);
  JointDef j;
  j.body_a = b;
  j.user_data = 33;
  const JointId joint = w.create_joint(j);
  EXPECT_EQ(w.user_data(d.shape), 11u);
  EXPECT_EQ(w.shape_def(d.shape).user_data, 11u);
  EXPECT_EQ(w.user_data(b), 22u);
  EXPECT_EQ(w.user_data(joint), 33u);
  w.set_user_data(d.shape, 44);
  w.set_user_data(b, 55);
  w.set_user_data(joint, 66);
  EXPECT_EQ(w.user_data(d.shape), 44u);
  EXPECT_EQ(w.shape_def(d.shape).user_data, 44u);
  EXPECT_EQ(w.user_data(b), 55u);
  EXPECT_EQ(w.user_data(joint), 66u);
  EXPECT_EQ(w.joint_def(joint).user_data, 66u);
  EXPECT_EQ(error_field([&] { w.user_data(BodyId{}); }), "body");
  EXPECT_EQ(error_field([&] { w.set_user_data(ShapeId{}, 1); }), "shape");
  EXPECT_EQ(error_field([&] { w.set_user_data(JointId{}, 1); }), "joint");
  EXPECT_EQ(error_field([&] { w.set_hit_event_threshold(-1); }), "speed");
  EXPECT_EQ(error_field([&] { w.contact(0); }), "index");
  BodyDef bad = d;
  bad.gravity_scale = NAN;
  EXPECT_EQ(error_field([&] { w.create_body(bad); }), "gravity_scale");
}

// Contacts that begin: a ball dropped from height H hits at sqrt(2 g H). The manifold begins
// within the speculative distance plus one step's travel (0.02 m + v dt < 2 v dt at these
// speeds), so at most two steps before impact: the approach speed read then is lower by at most
// 2 g dt. A ball set down 5 cm above the ground begins a contact at under sqrt(2 g 0.05) =
// 0.99 m/s, below the 1 m/s threshold.
TEST(HitEvents, DroppedBallHitsAtTheFreeFallSpeedAndASlowContactMakesNone) {
  const Real g = Real(9.81);
  for (const Real height : {Real(1), Real(3)}) {
    World w;
    test::add_ground(w);
    const BodyId ball =
        add_body(w, test::sphere_shape(Real(0.25)), at(Vec3(0, height + Real(0.25), 0)));
    int hits = 0;
    for (int n = 0; n < 120; ++n) {
      w.step(kDt);
      for (const ContactHitEvent& e : w.contact_hit_events()) {
        ++hits;
        EXPECT_EQ(e.body_a, ball);
        EXPECT_NEAR(e.approach_speed, std::sqrt(2 * g * height), 2 * g * kDt);
        EXPECT_LT(e.approach_speed, std::sqrt(2 * g * height) + Real(1e-3));
        EXPECT_LT((e.normal - Vec3(0, -1, 0)).norm(), Real(1e-5));
        EXPECT_NEAR(e.point.x(), Real(0), Real(1e-4));
        ASSERT_EQ(w.contact_begin_events().size(), 1u);
        EXPECT_EQ(w.contact_begin_events()[0].normal, e.normal);
      }
    }
    EXPECT_EQ(hits, 1);
  }
  World w;
  test::add_ground(w);
  add_body(w, test::sphere_shape(Real(0.25)), at(Vec3(0, Real(0.3), 0)));
  int begins = 0;
  for (int n = 0; n < 60; ++n) {
    w.step(kDt);
    begins += int(w.contact_begin_events().size());
    EXPECT_TRUE(w.contact_hit_events().empty());
  }
  EXPECT_EQ(begins, 1);
  // With the threshold at 0 the same slow contact is a hit.
  World w0;
  w0.set_hit_event_threshold(0);
  test::add_ground(w0);
  add_body(w0, test::sphere_shape(Real(0.25)), at(Vec3(0, Real(0.3), 0)));
  int hits = 0;
  for (int n = 0; n < 60; ++n) {
    w0.step(kDt);
    hits += int(w0.contact_hit_events().size());
  }
  EXPECT_EQ(hits, 1);
}

// A box resting on the ground: its manifold's normal impulses over a step hold its weight,
// sum = m g dt, once settled; the view's normal is the begin event's; contacts_of lists it.
TEST(ContactViews, RestingBoxCarriesItsWeight) {
  World w;
  const BodyId ground = test::add_ground(w);
  const BodyId box = add_body(w, test::box_shape(Vec3(Real(0.5), Real(0.25), Real(0.5))),
                              at(Vec3(0, Real(0.26), 0)));
  int begins = 0;
  for (int n = 0; n < 30; ++n) {
    w.step(kDt);
    for (const ContactBeginEvent& e : w.contact_begin_events()) {
      ++begins;
      ASSERT_EQ(w.contact_count(), 1u);
      EXPECT_EQ(w.contact(0).normal, e.normal);
      EXPECT_EQ(w.contact(0).body_a, e.body_a);
      EXPECT_EQ(w.contact(0).body_b, e.body_b);
    }
  }
  EXPECT_EQ(begins, 1);
  ASSERT_EQ(w.contact_count(), 1u);
  const ContactView v = w.contact(0);
  EXPECT_EQ(v.body_a, box);
  EXPECT_EQ(v.body_b, ground);
  EXPECT_LT((v.normal - Vec3(0, -1, 0)).norm(), Real(1e-3));
  EXPECT_EQ(v.point_count, 4);
  Real sum = 0;
  for (int k = 0; k < v.point_count; ++k) {
    sum += v.points[k].normal_impulse;
    EXPECT_NEAR(v.points[k].point.y(), Real(0), Real(0.01));
    EXPECT_LT(std::abs(v.points[k].separation), Real(0.01));
  }
  // Settled (velocity ~ 0): the step's contact impulse cancels gravity's, m g dt.
  const Real weight_impulse = w.mass(box) * Real(9.81) * kDt;
  EXPECT_NEAR(sum, weight_impulse, Real(1e-3) * weight_impulse);
  std::vector<ContactView> of;
  w.contacts_of(box, of);
  ASSERT_EQ(of.size(), 1u);
  EXPECT_EQ(of[0].body_b, ground);
  w.contacts_of(ground, of);
  EXPECT_EQ(of.size(), 1u);
}

}  // namespace api_body_changes_test
}  // namespace elan
