// SPDX-License-Identifier: MIT
// Scene parser: defaults as the spec gives them, generators placing bodies exactly, names and
// quaternions resolved, and load_into creating bodies in scene order with shared shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/world/world_access.hpp"
#include "elan/elan.hpp"

namespace elan {
namespace scene_parse_test {

std::string sphere_body(const std::string& extra = "") {
  return R"({"shape": {"type": "sphere", "radius": 0.5})" + extra + "}";
}

TEST(SceneParser, DefaultsFollowTheSpec) {
  const Scene s = parse_scene(R"({"bodies": [)" + sphere_body() + "]}", "t.json");
  EXPECT_EQ(s.world.gravity, Vec3(0, Real(-9.81), 0));
  EXPECT_EQ(s.timestep, Real(1.0 / 60.0));
  EXPECT_TRUE(s.world.allow_sleep);
  EXPECT_FALSE(s.has_substeps);
  EXPECT_FALSE(s.has_iterations);
  ASSERT_EQ(s.bodies.size(), 1u);
  const SceneBody& b = s.bodies[0];
  EXPECT_TRUE(b.name.empty());
  EXPECT_EQ(b.shape.type, ShapeType::Sphere);
  EXPECT_EQ(b.shape.radius, Real(0.5));
  EXPECT_EQ(b.body.motion, MotionType::Dynamic);
  EXPECT_EQ(b.body.position, Vec3::Zero());
  EXPECT_EQ(b.body.orientation.coeffs(), Quat::Identity().coeffs());
  EXPECT_EQ(b.body.linear_velocity, Vec3::Zero());
  EXPECT_EQ(b.body.angular_velocity, Vec3::Zero());
  EXPECT_FALSE(b.body.mass.has_value());
  EXPECT_EQ(b.body.density, Real(1000));
  EXPECT_EQ(b.body.friction, Real(0.5));
  EXPECT_EQ(b.body.restitution, Real(0));
  EXPECT_EQ(b.body.linear_damping, Real(0));
  EXPECT_EQ(b.body.angular_damping, Real(0));
}

TEST(SceneParser, ReadsEveryWorldAndBodyKey) {
  const Scene s = parse_scene(R"({
    "gravity": [1, 2, 3], "timestep": 0.01, "substeps": 6, "iterations": 3, "allow_sleep": false,
    "bodies": [
      {"name": "k", "motion": "kinematic", "shape": {"type": "capsule", "radius": 0.2, "half_height": 0.7},
       "position": [1, 2, 3], "orientation": [0, 0, 2, 0], "linear_velocity": [4, 5, 6],
       "angular_velocity": [7, 8, 9], "mass": 3, "friction": 0.9, "restitution": 0.4,
       "linear_damping": 0.1, "angular_damping": 0.2},
      {"motion": "static", "shape": {"type": "plane", "normal": [0, 0, 1], "offset": -2}},
      {"shape": {"type": "cylinder", "radius": 0.3, "half_height": 0.4}, "density": 500}
    ]})",
                              "t.json");
  EXPECT_EQ(s.world.gravity, Vec3(1, 2, 3));
  EXPECT_EQ(s.timestep, Real(0.01));
  EXPECT_EQ(s.world.substeps, 6);
  EXPECT_EQ(s.world.iterations, 3);
  EXPECT_TRUE(s.has_substeps && s.has_iterations);
  EXPECT_FALSE(s.world.allow_sleep);
  ASSERT_EQ(s.bodies.size(), 3u);
  const BodyDef& k = s.bodies[0].body;
  EXPECT_EQ(s.bodies[0].name, "k");
  EXPECT_EQ(k.motion, MotionType::Kinematic);
  EXPECT_EQ(s.bodies[0].shape.type, ShapeType::Capsule);
  EXPECT_EQ(s.bodies[0].shape.half_height, Real(0.7));
  EXPECT_EQ(k.position, Vec3(1, 2, 3));
  // [w, x, y, z] = [0, 0, 2, 0] normalises to a half turn about y.
  EXPECT_EQ(k.orientation.w(), Real(0));
  EXPECT_EQ(k.orientation.y(), Real(1));
  EXPECT_EQ(k.linear_velocity, Vec3(4, 5, 6));
  EXPECT_EQ(k.angular_velocity, Vec3(7, 8, 9));
  EXPECT_EQ(k.mass, Real(3));
  EXPECT_EQ(k.friction, Real(0.9));
  EXPECT_EQ(k.restitution, Real(0.4));
  EXPECT_EQ(k.linear_damping, Real(0.1));
  EXPECT_EQ(k.angular_damping, Real(0.2));
  EXPECT_EQ(s.bodies[1].shape.type, ShapeType::Plane);
  EXPECT_EQ(s.bodies[1].shape.normal, Vec3(0, 0, 1));
  EXPECT_EQ(s.bodies[1].shape.offset, Real(-2));
  EXPECT_EQ(s.bodies[2].shape.type, ShapeType::Cylinder);
  EXPECT_EQ(s.bodies[2].body.density, Real(500));
}

TEST(SceneParser, QuaternionIsNormalised) {
  const Scene s =
      parse_scene(R"({"bodies": [)" + sphere_body(R"(, "orientation": [1, 1, 0, 0])") + "]}", "t");
  const Quat q = s.bodies[0].body.orientation;
  EXPECT_NEAR(q.w(), std::sqrt(0.5), 1e-7);
  EXPECT_NEAR(q.x(), std::sqrt(0.5), 1e-7);
  EXPECT_EQ(q.y(), Real(0));
  EXPECT_NEAR(q.norm(), 1, 1e-7);
}

TEST(SceneParser, PyramidCountAndPlacementAreExact) {
  for (int base = 1; base <= 6; ++base) {
    const Scene s = parse_scene(
        R"({"bodies": [)" + sphere_body() + R"(], "generators": [{"type": "pyramid", "base": )" +
            std::to_string(base) + R"(, "half_extent": 0.25, "origin": [1, 2, -3]}]})",
        "t");
    ASSERT_EQ(s.bodies.size(), 1u + std::size_t(base * (base + 1) * (2 * base + 1) / 6));
    EXPECT_EQ(s.bodies[0].shape.type, ShapeType::Sphere);  // explicit bodies first
    std::size_t i = 1;
    for (int layer = 0; layer < base; ++layer) {
      const int n = base - layer;
      for (int z = 0; z < n; ++z) {
        for (int x = 0; x < n; ++x, ++i) {
          const SceneBody& b = s.bodies[i];
          EXPECT_EQ(b.shape.type, ShapeType::Box);
          EXPECT_EQ(b.shape.half_extents, Vec3::Constant(Real(0.25)));
          EXPECT_EQ(b.body.motion, MotionType::Dynamic);
          EXPECT_EQ(b.body.friction, Real(0.5));
          // Cubes 0.5 apart, centred on x = 1, z = -3; layer L rests on 2 + 0.5 L.
          EXPECT_EQ(b.body.position.x(), Real(1 + 0.5 * x - 0.25 * (n - 1)));
          EXPECT_EQ(b.body.position.y(), Real(2 + 0.5 * layer + 0.25));
          EXPECT_EQ(b.body.position.z(), Real(-3 + 0.5 * z - 0.25 * (n - 1)));
        }
      }
    }
  }
}

TEST(SceneParser, GridPlacesCopiesXFastestThenYThenZ) {
  const Scene s = parse_scene(R"({"generators": [{"type": "grid", "count": [2, 3, 4],
      "spacing": [1.5, 2, -1], "origin": [10, 0, 5],
      "body": {"motion": "kinematic", "friction": 0.8,
               "shape": {"type": "box", "half_extents": [0.1, 0.2, 0.3]}}}]})",
                              "t");
  ASSERT_EQ(s.bodies.size(), 24u);
  for (int k = 0; k < 4; ++k) {
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 2; ++i) {
        const SceneBody& b = s.bodies[std::size_t(i + 2 * (j + 3 * k))];
        EXPECT_EQ(b.body.position, Vec3(Real(10 + 1.5 * i), Real(2 * j), Real(5 - k)));
        EXPECT_EQ(b.body.motion, MotionType::Kinematic);
        EXPECT_EQ(b.body.friction, Real(0.8));
        EXPECT_EQ(b.shape.half_extents, Vec3(Real(0.1), Real(0.2), Real(0.3)));
      }
    }
  }
}

// Found by fuzz_scene: gravity past the supported range passed parse_scene, and the World's
// constructor then threw an elan::Error naming no file, where parse_scene promises SceneError.
TEST(SceneParser, GravityOutOfRangeIsASceneErrorNamingTheFile) {
  try {
    parse_scene(R"({"gravity": [0, 1e38, 0]})", "f.json");
    FAIL() << "gravity of 1e38 m/s^2 was accepted";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "f.json: gravity: length must be at most 100000 m/s^2, got 1e+38");
  }
  EXPECT_NO_THROW(parse_scene(R"({"gravity": [0, -1e4, 0]})", "f.json"));
}

TEST(SceneParser, ErrorsNameFileBodyAndField) {
  const auto message = [](const std::string& text) {
    try {
      parse_scene(text, "f.json");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(R"({"bodies": [)" + sphere_body() + R"(, {"name": "b", "shape":
                {"type": "sphere", "radius": -1}}]})"),
            "f.json: body 1 (\"b\"): shape.radius: must be positive, got -1");
  EXPECT_EQ(message(R"({"bodies": [{"name": "x", "shape": {"type": "sphere", "radius": 1}},
                {"name": "x", "shape": {"type": "sphere", "radius": 1}}]})"),
            "f.json: body 1 (\"x\"): name: duplicate name \"x\" (also body 0)");
  EXPECT_EQ(message(R"({"substeps": 0})"), "f.json: substeps: must be at least 1, got 0");
  EXPECT_EQ(message(""), "f.json: empty file (expected a JSON object)");
}

TEST(SceneLoader, CreatesBodiesInSceneOrderAndSharesIdenticalShapes) {
  const Scene s = parse_scene(R"({"bodies": [
      {"motion": "static", "shape": {"type": "box", "half_extents": [5, 1, 5]}, "position": [0, -1, 0]}],
    "generators": [
      {"type": "grid", "count": [4, 1, 3], "spacing": [2, 0, 2],
       "body": {"shape": {"type": "sphere", "radius": 0.5}}},
      {"type": "pyramid", "base": 3, "origin": [20, 0, 0]}]})",
                              "t");
  World world;
  load_into(s, world, "t");
  ASSERT_EQ(world.body_count(), s.bodies.size());
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    EXPECT_EQ(world.position(world.body_at(i)), s.bodies[i].body.position) << i;
  }
  EXPECT_EQ(world.motion_type(world.body_at(0)), MotionType::Static);
  // One ground box, one sphere for the 12 grid copies, one cube for the 14 pyramid cubes.
  EXPECT_EQ(detail::state_of(world).shapes.size(), 3u);
}

TEST(SceneLoader, LibraryErrorsArePrefixedWithFileAndBody) {
  Scene s = parse_scene(R"({"bodies": [)" + sphere_body(R"(, "name": "ball")") + "]}", "t.json");
  s.bodies[0].shape.radius = Real(-1);  // past the parser, the library must still refuse it
  World world;
  try {
    load_into(s, world, "t.json");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("t.json: body 0 (\"ball\"): shape", 0), 0u) << e.what();
  }
}

}  // namespace scene_parse_test
}  // namespace elan
