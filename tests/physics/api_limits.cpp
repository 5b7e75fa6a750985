// SPDX-License-Identifier: MIT
// The supported ranges of elan/limits.hpp through the API: a value outside them is refused with
// elan::Error naming the field (and nothing is half created), values at their bounds are
// accepted and stay finite when stepped, and every standard scene is within them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "elan/elan.hpp"

namespace elan {
namespace api_limits_test {

constexpr Real kDt = Real(1.0 / 60.0);

ShapeDef sphere(Real r) {
  ShapeDef s;
  s.type = ShapeType::Sphere;
  s.radius = r;
  return s;
}

ShapeDef box(const Vec3& h) {
  ShapeDef s;
  s.type = ShapeType::Box;
  s.half_extents = h;
  return s;
}

// The field the call's elan::Error names, and its message; "" when it does not throw.
template <class F>
std::string refused_field(F&& call, std::string* message = nullptr) {
  try {
    call();
  } catch (const Error& e) {
    if (message) *message = e.what();
    return e.field();
  }
  return "";
}

TEST(ApiLimits, ShapeSizesOutsideTheRangeAreRefusedNamingTheField) {
  World w;
  EXPECT_EQ(refused_field([&] { w.create_shape(sphere(Real(1e-30))); }), "shape.radius");
  EXPECT_EQ(refused_field([&] { w.create_shape(sphere(Real(1e20))); }), "shape.radius");
  EXPECT_EQ(refused_field([&] { w.create_shape(box(Vec3(Real(1e10), Real(1e10), 1))); }),
            "shape.half_extents");
  ShapeDef capsule;
  capsule.type = ShapeType::Capsule;
  capsule.radius = Real(0.5);
  capsule.half_height = Real(1e5);
  EXPECT_EQ(refused_field([&] { w.create_shape(capsule); }), "shape.half_height");
  ShapeDef hull;
  hull.type = ShapeType::ConvexHull;
  hull.points = {Vec3(0, 0, 0), Vec3(Real(2e4), 0, 0), Vec3(0, Real(2e4), 0),
                 Vec3(0, 0, Real(2e4))};
  EXPECT_EQ(refused_field([&] { w.create_shape(hull); }), "shape.points");
  hull.points = {Vec3(0, 0, 0), Vec3(Real(2e5), 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  EXPECT_EQ(refused_field([&] { w.create_shape(hull); }), "shape.points");
  ShapeDef plane;
  plane.type = ShapeType::Plane;
  plane.normal = Vec3(0, 1, 0);
  plane.offset = Real(1e6);
  EXPECT_EQ(refused_field([&] { w.create_shape(plane); }), "shape.offset");
  // The bounds themselves are in (as rounded to Real).
  EXPECT_NO_THROW(w.create_shape(sphere(Real(limits::kMinSize))));
  EXPECT_NO_THROW(w.create_shape(sphere(Real(limits::kMaxSize))));
  EXPECT_NO_THROW(w.create_shape(box(Vec3::Constant(Real(limits::kMaxSize)))));
}

TEST(ApiLimits, BodyValuesOutsideTheRangeAreRefusedAndNothingIsCreated) {
  World w;
  const ShapeId ball = w.create_shape(sphere(Real(0.5)));
  auto refused = [&](auto edit) {
    BodyDef d;
    d.shape = ball;
    edit(d);
    const std::size_t before = w.body_count();
    std::string message;
    const std::string field = refused_field([&] { w.create_body(d); }, &message);
    EXPECT_EQ(w.body_count(), before) << message;
    return field;
  };
  EXPECT_EQ(refused([](BodyDef& d) { d.position = Vec3(Real(3e38), 0, 0); }), "position");
  EXPECT_EQ(refused([](BodyDef& d) { d.position = Vec3(0, 0, Real(-2e5)); }), "position");
  EXPECT_EQ(refused([](BodyDef& d) { d.linear_velocity = Vec3(Real(1e20), 0, 0); }),
            "linear_velocity");
  EXPECT_EQ(refused([](BodyDef& d) { d.angular_velocity = Vec3(0, Real(1e6), 0); }),
            "angular_velocity");
  EXPECT_EQ(refused([](BodyDef& d) { d.mass = Real(1e-40); }), "mass");
  EXPECT_EQ(refused([](BodyDef& d) { d.mass = Real(1e10); }), "mass");
  EXPECT_EQ(refused([](BodyDef& d) { d.density = Real(1e12); }), "density");
  EXPECT_EQ(refused([](BodyDef& d) { d.density = Real(1e-9); }), "density");
  EXPECT_EQ(refused([](BodyDef& d) { d.friction = Real(1e38); }), "friction");
  EXPECT_EQ(refused([](BodyDef& d) { d.restitution = Real(1e30); }), "restitution");
  EXPECT_EQ(w.body_count(), 0u);
}

// A shape whose volume times the density leaves the mass range says the computed mass is out of
// range (the huge sphere once said "not positive" of a mass that had overflowed to inf).
TEST(ApiLimits, ComputedMassOutOfRangeSaysSoWithTheFactors) {
  World w;
  BodyDef d;
  d.shape = w.create_shape(box(Vec3::Constant(Real(1e4))));
  d.density = Real(1e9);
  std::string message;
  EXPECT_EQ(refused_field([&] { w.create_body(d); }, &message), "mass");
  EXPECT_NE(message.find("computed mass is out of range"), std::string::npos) << message;
  EXPECT_NE(message.find("density 1e+09"), std::string::npos) << message;
  d.shape = w.create_shape(sphere(Real(1e-4)));
  d.density = Real(1e-3);
  EXPECT_EQ(refused_field([&] { w.create_body(d); }, &message), "mass");
  EXPECT_NE(message.find("computed mass is out of range"), std::string::npos) << message;
  EXPECT_EQ(w.body_count(), 0u);
  // A static body has no mass: its density is not multiplied out.
  d.motion = MotionType::Static;
  d.density = Real(1000);
  d.shape = w.create_shape(box(Vec3::Constant(Real(1e4))));
  EXPECT_NO_THROW(w.create_body(d));
}

TEST(ApiLimits, GravityAndTimestepOutsideTheRangeAreRefused) {
  WorldDef def;
  def.gravity = Vec3(0, Real(1e38), 0);
  std::string message;
  EXPECT_EQ(refused_field([&] { World w(def); }, &message), "gravity");
  EXPECT_NE(message.find("m/s^2"), std::string::npos) << message;
  def.gravity = Vec3(0, Real(-limits::kMaxGravity), 0);
  World w(def);
  EXPECT_EQ(w.step(Real(2)), uint32_t(kStepBadTimestep));
  EXPECT_EQ(w.step(Real(1e-7)), uint32_t(kStepBadTimestep));
  EXPECT_EQ(w.step(kDt), uint32_t(kStepOk));
}

TEST(ApiLimits, SettersOutsideTheRangeAreRefusedNamingTheField) {
  World w;
  const ShapeId ball = w.create_shape(sphere(Real(0.5)));
  BodyDef d;
  d.shape = ball;
  const BodyId id = w.create_body(d);
  const Vec3 far(Real(1e6), 0, 0);
  EXPECT_EQ(refused_field([&] { w.set_position(id, far); }), "position");
  EXPECT_EQ(refused_field([&] { w.set_transform(id, {far, Quat::Identity()}); }), "position");
  EXPECT_EQ(refused_field([&] { w.set_linear_velocity(id, Vec3(Real(1e20), 0, 0)); }),
            "linear_velocity");
  EXPECT_EQ(refused_field([&] { w.set_angular_velocity(id, Vec3(Real(1e20), 0, 0)); }),
            "angular_velocity");
  EXPECT_EQ(refused_field([&] { w.set_mass(id, Real(1e-40)); }), "mass");
  EXPECT_EQ(refused_field([&] { w.set_mass(id, Real(1e20)); }), "mass");
  EXPECT_EQ(refused_field([&] { w.set_friction(id, Real(101)); }), "friction");
  EXPECT_EQ(refused_field([&] { w.set_restitution(id, Real(1.5)); }), "restitution");
  EXPECT_NO_THROW(w.set_friction(id, Real(limits::kMaxFriction)));
  EXPECT_NO_THROW(w.set_restitution(id, Real(limits::kMaxRestitution)));
  // An impulse that would take the body past the speed bound is refused, the body untouched.
  EXPECT_EQ(refused_field([&] { w.apply_linear_impulse(id, Vec3(Real(1e30), 0, 0)); }), "impulse");
  EXPECT_EQ(w.linear_velocity(id), Vec3::Zero());
  EXPECT_EQ(refused_field([&] { w.apply_angular_impulse(id, Vec3(Real(1e30), 0, 0)); }),
            "angular_impulse");
  EXPECT_EQ(w.angular_velocity(id), Vec3::Zero());
  // At a point far off the centre: the linear half is in range, the angular half is not.
  EXPECT_EQ(
      refused_field([&] { w.apply_impulse(id, Vec3(0, Real(1e4), 0), Vec3(Real(1e5), 0, 0)); }),
      "impulse");
  EXPECT_EQ(w.linear_velocity(id), Vec3::Zero());
  EXPECT_EQ(w.angular_velocity(id), Vec3::Zero());
  const std::vector<Real> big{Real(1e6)}, zero{0};
  EXPECT_EQ(refused_field([&] { w.set_center_of_mass_positions(big, zero, zero); }), "positions");
  EXPECT_EQ(refused_field([&] { w.set_linear_velocities(zero, big, zero); }), "linear_velocities");
  EXPECT_EQ(refused_field([&] { w.set_angular_velocities(zero, zero, big); }),
            "angular_velocities");
  EXPECT_EQ(w.position(id), Vec3::Zero());
}

// The abuse the issue lists, at the bounds: 1e4 and 1e5 m/s bodies, 1e4 and 1e5 rad/s ones, the
// heaviest and lightest masses, the largest and smallest sizes, far from the origin, under the
// strongest gravity. Every body and every world total stays finite and nothing is frozen.
TEST(ApiLimits, BodiesAtTheBoundsStayFiniteWhenStepped) {
  for (const double g : {1e4, limits::kMaxGravity}) {
    WorldDef def;
    def.gravity = Vec3(0, Real(-g), 0);
    def.threads = 1;
    World w(def);
    BodyDef ground;
    ground.motion = MotionType::Static;
    ground.shape = w.create_shape(box(Vec3(Real(1e4), 1, Real(1e4))));
    ground.position = Vec3(0, -1, 0);
    w.create_body(ground);
    auto add = [&](const ShapeDef& s, const Vec3& p, auto edit) {
      BodyDef d;
      d.shape = w.create_shape(s);
      d.position = p;
      edit(d);
      return w.create_body(d);
    };
    const Real vmax = Real(limits::kMaxLinearSpeed), wmax = Real(limits::kMaxAngularSpeed);
    add(sphere(Real(0.2)), Vec3(0, 1, 0),
        [](BodyDef& d) { d.linear_velocity = Vec3(Real(1e4), 0, 0); });
    add(sphere(Real(0.2)), Vec3(5, 1, 0),
        [&](BodyDef& d) { d.linear_velocity = Vec3(0, -vmax, 0); });
    add(box(Vec3::Constant(Real(0.5))), Vec3(10, 1, 0),
        [](BodyDef& d) { d.angular_velocity = Vec3(Real(1e4), 0, 0); });
    add(box(Vec3(1, Real(0.1), Real(0.3))), Vec3(15, 1, 0),
        [&](BodyDef& d) { d.angular_velocity = Vec3(0, 0, wmax); });
    add(box(Vec3::Constant(Real(limits::kMinSize))), Vec3(20, Real(1e-4), 0),
        [](BodyDef& d) { d.mass = Real(limits::kMinMass); });
    add(box(Vec3::Constant(Real(100))), Vec3(20, 100, 0),
        [](BodyDef& d) { d.mass = Real(limits::kMaxMass); });
    add(sphere(Real(1)), Vec3(Real(limits::kMaxPosition), 0, Real(-limits::kMaxPosition)),
        [&](BodyDef& d) {
          d.linear_velocity = Vec3(vmax, 0, 0);
          d.angular_velocity = Vec3(0, wmax, 0);
          d.mass = Real(limits::kMaxMass);
        });
    uint32_t status = 0;
    for (int n = 0; n < 60; ++n) status |= w.step(kDt);
    EXPECT_EQ(status & kStepFrozeNonFinite, 0u) << "g " << g;
    for (std::size_t i = 0; i < w.body_count(); ++i) {
      const BodyId id = w.body_at(i);
      EXPECT_TRUE(w.position(id).allFinite()) << "body " << i;
      EXPECT_TRUE(w.linear_velocity(id).allFinite()) << "body " << i;
      EXPECT_TRUE(w.angular_velocity(id).allFinite()) << "body " << i;
    }
    EXPECT_TRUE(std::isfinite(w.kinetic_energy())) << "g " << g;
    EXPECT_TRUE(w.linear_momentum().allFinite()) << "g " << g;
    EXPECT_TRUE(w.angular_momentum().allFinite()) << "g " << g;
  }
}

// Every scene shipped in scenes/ loads: the ranges leave the standard scenes (and so their
// golden hashes) as they were.
TEST(ApiLimits, EveryStandardSceneIsWithinTheRanges) {
  std::size_t scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(ELAN_SCENE_DIR)) {
    if (entry.path().extension() != ".json") continue;
    const std::string path = entry.path().string();
    EXPECT_NO_THROW({
      const Scene scene = load_scene(path);
      World w(scene.world);
      load_into(scene, w, path);
    }) << path;
    ++scenes;
  }
  EXPECT_GE(scenes, 10u);
}

}  // namespace api_limits_test
}  // namespace elan
