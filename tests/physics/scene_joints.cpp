// SPDX-License-Identifier: MIT
// Scene files' joints: each kind's fields land in JointDef as the spec maps them, bodies resolve
// by index, name or null, every bad input names the file, joint and field, the chain, ragdoll and
// joint_grid generators make the bodies and joints they promise, and load_into creates them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/scene/joint_schema.hpp"
#include "elan/elan.hpp"

namespace elan {
namespace scene_joints_test {

// Body 0 a static ground, 1 "a" and 2 "b" dynamic spheres, 3 "k" kinematic.
std::string scene(const std::string& joints, const std::string& generators = "[]") {
  return R"({"bodies": [
    {"motion": "static", "shape": {"type": "box", "half_extents": [10, 1, 10]}, "position": [0, -1, 0]},
    {"name": "a", "shape": {"type": "sphere", "radius": 0.5}, "position": [0, 2, 0]},
    {"name": "b", "shape": {"type": "sphere", "radius": 0.5}, "position": [0, 4, 0]},
    {"name": "k", "motion": "kinematic", "shape": {"type": "sphere", "radius": 0.5}, "position": [3, 4, 0]}],
    "generators": )" +
         generators + R"(, "joints": [)" + joints + "]}";
}

SceneJoint only_joint(const Scene& s) {
  EXPECT_EQ(s.joints.size(), 1u);
  return s.joints.at(0);
}

std::string message(const std::string& text) {
  try {
    parse_scene(text, "f.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneJoints, BallResolvesBodiesByNameIndexAndNull) {
  const Scene s = parse_scene(scene(R"({"type": "ball", "bodies": ["a", 2], "anchor": [0, 3, 0]},
      {"type": "ball", "bodies": [1, null], "anchor": [0, 2.5, 0], "name": "pin"})"),
                              "t");
  ASSERT_EQ(s.joints.size(), 2u);
  EXPECT_EQ(s.joints[0].body_a, 1);
  EXPECT_EQ(s.joints[0].body_b, 2);
  EXPECT_TRUE(s.joints[0].name.empty());
  const JointDef& d = s.joints[0].def;
  EXPECT_EQ(d.type, JointType::Ball);
  EXPECT_EQ(d.anchor, Vec3(0, 3, 0));
  EXPECT_FALSE(d.collide_connected);
  EXPECT_EQ(d.break_force, std::numeric_limits<Real>::infinity());
  EXPECT_EQ(s.joints[1].body_b, -1);
  EXPECT_EQ(s.joints[1].name, "pin");
}

TEST(SceneJoints, HingeMapsLimitsMotorSpringAndTheCommonKeys) {
  const SceneJoint j = only_joint(parse_scene(
      scene(R"({"type": "hinge", "name": "door", "bodies": ["a", "b"], "anchor": [1, 1, 0],
        "axis": [0, 2, 0], "limits": [-1.5, 1.25], "motor": {"speed": 2, "max_torque": 50},
        "spring": {"frequency": 3, "damping_ratio": 0.5, "target": 0.25},
        "collide_connected": true, "break_force": 1000})"),
      "t"));
  const JointDef& d = j.def;
  EXPECT_EQ(d.type, JointType::Hinge);
  EXPECT_EQ(j.name, "door");
  EXPECT_EQ(d.anchor, Vec3(1, 1, 0));
  EXPECT_EQ(d.axis, Vec3(0, 1, 0));  // normalised
  EXPECT_TRUE(d.limits.enabled);
  EXPECT_EQ(d.limits.lower, Real(-1.5));
  EXPECT_EQ(d.limits.upper, Real(1.25));
  EXPECT_TRUE(d.motor.enabled);
  EXPECT_EQ(d.motor.speed, Real(2));
  EXPECT_EQ(d.motor.max_force, Real(50));  // max_torque, N m
  EXPECT_TRUE(d.spring.enabled);
  EXPECT_EQ(d.spring.frequency, Real(3));
  EXPECT_EQ(d.spring.damping_ratio, Real(0.5));
  EXPECT_EQ(d.spring.target, Real(0.25));
  EXPECT_TRUE(d.collide_connected);
  EXPECT_EQ(d.break_force, Real(1000));
}

TEST(SceneJoints, HingeWithoutOptionsLeavesThemOff) {
  const JointDef d = only_joint(parse_scene(scene(R"({"type": "hinge", "bodies": ["a", null],
        "anchor": [0, 0, 0], "axis": [1, 0, 0]})"),
                                            "t"))
                         .def;
  EXPECT_FALSE(d.limits.enabled);
  EXPECT_FALSE(d.motor.enabled);
  EXPECT_FALSE(d.spring.enabled);
}

TEST(SceneJoints, SliderMapsMaxForceAndDefaultsItsAnchorToTheFirstBody) {
  const JointDef d = only_joint(parse_scene(scene(R"({"type": "slider", "bodies": ["b", "a"],
        "axis": [0, 0, -3], "limits": [-2, 5], "motor": {"speed": -1, "max_force": 20},
        "spring": {"frequency": 1.5}})"),
                                            "t"))
                         .def;
  EXPECT_EQ(d.type, JointType::Slider);
  EXPECT_EQ(d.anchor, Vec3(0, 4, 0));  // body "b"
  EXPECT_EQ(d.axis, Vec3(0, 0, -1));
  EXPECT_EQ(d.limits.lower, Real(-2));
  EXPECT_EQ(d.limits.upper, Real(5));  // metres: not bounded by pi
  EXPECT_EQ(d.motor.speed, Real(-1));
  EXPECT_EQ(d.motor.max_force, Real(20));
  EXPECT_EQ(d.spring.frequency, Real(1.5));
  EXPECT_EQ(d.spring.damping_ratio, Real(0));
  EXPECT_EQ(d.spring.target, Real(0));
}

TEST(SceneJoints, FixedAnchorIsOptional) {
  const Scene s = parse_scene(scene(R"({"type": "fixed", "bodies": ["a", "b"]},
      {"type": "fixed", "bodies": ["a", "b"], "anchor": [0, 3, 0]})"),
                              "t");
  EXPECT_FALSE(s.joints[0].def.has_anchor);
  EXPECT_TRUE(s.joints[1].def.has_anchor);
  EXPECT_EQ(s.joints[1].def.anchor, Vec3(0, 3, 0));
}

TEST(SceneJoints, DistanceMapsAnchorsLengthsAndRestLength) {
  const Scene s = parse_scene(
      scene(R"({"type": "distance", "bodies": ["a", "b"], "anchors": [[0, 2.5, 0], [0, 3.5, 0]]},
      {"type": "distance", "bodies": ["a", "b"], "anchors": [[0, 2.5, 0], [0, 3.5, 0]],
       "min_length": 0},
      {"type": "distance", "bodies": ["a", "b"], "anchors": [[0, 2.5, 0], [0, 3.5, 0]],
       "min_length": 0.5, "max_length": 2, "rest_length": 1.5,
       "spring": {"frequency": 4, "damping_ratio": 1}},
      {"type": "distance", "bodies": ["a", "b"], "anchors": [[0, 2.5, 0], [0, 3.5, 0]],
       "spring": {"frequency": 4, "rest_length": 0.75}})"),
      "t");
  ASSERT_EQ(s.joints.size(), 4u);
  const JointDef& rod = s.joints[0].def;
  EXPECT_EQ(rod.type, JointType::Distance);
  EXPECT_EQ(rod.anchor, Vec3(0, Real(2.5), 0));
  EXPECT_EQ(rod.anchor_b, Vec3(0, Real(3.5), 0));
  // Absent lengths are the distance at load: a rigid rod.
  EXPECT_LT(rod.min_length, 0);
  EXPECT_LT(rod.max_length, 0);
  EXPECT_FALSE(rod.spring.enabled);
  EXPECT_LT(rod.spring.target, 0);
  // min_length 0 alone: a rope as long as the distance at load.
  EXPECT_EQ(s.joints[1].def.min_length, Real(0));
  EXPECT_LT(s.joints[1].def.max_length, 0);
  const JointDef& sprung = s.joints[2].def;
  EXPECT_EQ(sprung.min_length, Real(0.5));
  EXPECT_EQ(sprung.max_length, Real(2));
  EXPECT_TRUE(sprung.spring.enabled);
  EXPECT_EQ(sprung.spring.frequency, Real(4));
  EXPECT_EQ(sprung.spring.damping_ratio, Real(1));
  EXPECT_EQ(sprung.spring.target, Real(1.5));
  EXPECT_EQ(s.joints[3].def.spring.target, Real(0.75));  // rest_length inside the spring
}

TEST(SceneJoints, ConeMapsSwingAndTwist) {
  const Scene s = parse_scene(
      scene(R"({"type": "cone", "bodies": ["a", "b"], "anchor": [0, 3, 0], "axis": [0, -1, 0],
        "swing_limit": 0.8, "twist_limits": [-0.5, 0.25]},
      {"type": "cone", "bodies": ["a", "b"], "anchor": [0, 3, 0], "axis": [0, -1, 0]})"),
      "t");
  const JointDef& d = s.joints[0].def;
  EXPECT_EQ(d.type, JointType::Cone);
  EXPECT_EQ(d.axis, Vec3(0, -1, 0));
  EXPECT_EQ(d.swing_limit, Real(0.8));
  EXPECT_TRUE(d.limits.enabled);
  EXPECT_EQ(d.limits.lower, Real(-0.5));
  EXPECT_EQ(d.limits.upper, Real(0.25));
  EXPECT_EQ(s.joints[1].def.swing_limit, Real(3.14159265358979323846));  // free swing
  EXPECT_FALSE(s.joints[1].def.limits.enabled);
}

// The library's body A cannot be the world: the bodies swap, and the coordinate of the world
// relative to the body is minus that of the body relative to the world.
TEST(SceneJoints, WorldFirstSwapsTheBodiesAndTheCoordinatesSign) {
  const JointDef d =
      only_joint(parse_scene(scene(R"({"type": "hinge", "bodies": [null, "a"], "anchor": [0, 3, 0],
        "axis": [0, 0, 1], "limits": [-0.5, 1], "motor": {"speed": 2, "max_torque": 5},
        "spring": {"frequency": 1, "target": 0.25}})"),
                             "t"))
          .def;
  const Scene s = parse_scene(scene(R"({"type": "distance", "bodies": [null, "a"],
        "anchors": [[0, 5, 0], [0, 2, 0]]})"),
                              "t");
  EXPECT_EQ(only_joint(s).body_a, 1);
  EXPECT_EQ(only_joint(s).body_b, -1);
  EXPECT_EQ(only_joint(s).def.anchor, Vec3(0, 2, 0));
  EXPECT_EQ(only_joint(s).def.anchor_b, Vec3(0, 5, 0));
  EXPECT_EQ(d.limits.lower, Real(-1));
  EXPECT_EQ(d.limits.upper, Real(0.5));
  EXPECT_EQ(d.motor.speed, Real(-2));
  EXPECT_EQ(d.spring.target, Real(-0.25));
}

TEST(SceneJoints, ExplicitJointsMayNameGeneratedBodiesAndComeFirst) {
  const Scene s = parse_scene(scene(R"({"type": "ball", "bodies": [5, "a"], "anchor": [0, 0, 0]})",
                                    R"([{"type": "grid", "count": [2, 1, 1], "spacing": [1, 0, 0],
                "body": {"shape": {"type": "sphere", "radius": 0.25}}},
               {"type": "chain", "links": 3, "link": {"shape": {"type": "sphere", "radius": 0.25}}}])"),
                              "t");
  ASSERT_EQ(s.bodies.size(), 4u + 2u + 3u);
  ASSERT_EQ(s.joints.size(), 1u + 3u);
  EXPECT_EQ(s.joints[0].body_a, 5);  // the second grid sphere
  EXPECT_EQ(s.joints[1].body_a, 6);  // the chain's first link, after the explicit joint
}

TEST(SceneJoints, ErrorsNameFileJointAndField) {
  struct Case {
    std::string joints;
    std::string expected;
  };
  const std::string hinge = R"("type": "hinge", "bodies": ["a", "b"], "anchor": [0, 3, 0], )";
  const std::vector<Case> cases = {
      {R"({"type": "ball", "name": "j", "bodies": ["a", "c"], "anchor": [0, 0, 0]})",
       "f.json: joint 0 (\"j\"): bodies[1]: no body named \"c\""},
      {R"({"type": "ball", "bodies": [1, 4], "anchor": [0, 0, 0]})",
       "f.json: joint 0: bodies[1]: no body 4 (the scene has 4 bodies"},
      {R"({"type": "ball", "bodies": [-1, 2], "anchor": [0, 0, 0]})",
       "f.json: joint 0: bodies[0]: must be at least 0"},
      {R"({"type": "ball", "bodies": [1.5, 2], "anchor": [0, 0, 0]})",
       "f.json: joint 0: bodies[0]: expected an integer"},
      {R"({"type": "ball", "bodies": [true, 2], "anchor": [0, 0, 0]})",
       "f.json: joint 0: bodies[0]: expected a body index, a body name or null"},
      {R"({"type": "ball", "bodies": ["a", "a"], "anchor": [0, 0, 0]})",
       "f.json: joint 0: bodies: the same body twice (body 1)"},
      {R"({"type": "ball", "bodies": [null, null], "anchor": [0, 0, 0]})",
       "f.json: joint 0: bodies: both are the world"},
      {R"({"type": "ball", "bodies": [0, "k"], "anchor": [0, 0, 0]})",
       "f.json: joint 0: bodies: at least one body must be dynamic (body 0 is static, body 3 "
       "(\"k\") is kinematic)"},
      {R"({"type": "ball", "bodies": [null, "k"], "anchor": [0, 0, 0]})",
       "f.json: joint 0: bodies: at least one body must be dynamic (the world is static, body 3 "
       "(\"k\") is kinematic)"},
      {R"({"type": "ball", "bodies": ["a"], "anchor": [0, 0, 0]})",
       "f.json: joint 0: bodies: expected two bodies"},
      {R"({"type": "ball", "anchor": [0, 0, 0]})", "f.json: joint 0: bodies: missing"},
      {R"({"bodies": ["a", "b"]})", "f.json: joint 0: type: missing"},
      {R"({"type": "weld", "bodies": ["a", "b"]})",
       "f.json: joint 0: type: unknown joint type \"weld\""},
      {R"({"type": "ball", "bodies": ["a", "b"], "anchor": [0, 0, 0], "axis": [0, 1, 0]})",
       "f.json: joint 0: axis: unknown key for a ball joint"},
      {R"({"type": "ball", "bodies": ["a", "b"]})", "f.json: joint 0: anchor: missing"},
      {R"({"type": "hinge", "bodies": ["a", "b"], "anchor": [0, 0, 0]})",
       "f.json: joint 0: axis: missing"},
      {R"({"type": "ball", "bodies": ["a", "b"], "anchor": [0, 1e39, 0]})",
       "f.json: joint 0: anchor[1]: not a finite number"},
      {R"({"type": "ball", "bodies": ["a", "b"], "anchor": [0, 0]})",
       "f.json: joint 0: anchor: expected 3 numbers, got 2"},
      {"{" + hinge + R"("axis": [0, 0, 0]})", "f.json: joint 0: axis: zero axis"},
      {"{" + hinge + R"("axis": [0, 1, 0], "limits": [1, -1]})",
       "f.json: joint 0: limits: lo > hi"},
      {"{" + hinge + R"("axis": [0, 1, 0], "limits": [0, 3.2]})",
       "f.json: joint 0: limits[1]: must be in [-pi, pi] rad"},
      {"{" + hinge + R"("axis": [0, 1, 0], "limits": "open"})",
       "f.json: joint 0: limits: expected an array of 2 numbers"},
      {"{" + hinge + R"("axis": [0, 1, 0], "motor": {"speed": 1, "max_torque": -1}})",
       "f.json: joint 0: motor.max_torque: must not be negative"},
      {"{" + hinge + R"("axis": [0, 1, 0], "motor": {"speed": 1, "max_force": 1}})",
       "f.json: joint 0: motor.max_force: unknown key for a hinge motor"},
      {"{" + hinge + R"("axis": [0, 1, 0], "motor": {"speed": 1}})",
       "f.json: joint 0: motor.max_torque: missing"},
      {"{" + hinge + R"("axis": [0, 1, 0], "spring": {"frequency": 0}})",
       "f.json: joint 0: spring.frequency: must be positive"},
      {"{" + hinge + R"("axis": [0, 1, 0], "spring": {"frequency": 1, "damping_ratio": -0.1}})",
       "f.json: joint 0: spring.damping_ratio: must not be negative"},
      {"{" + hinge + R"("axis": [0, 1, 0], "collide_connected": 1})",
       "f.json: joint 0: collide_connected: expected true or false"},
      {"{" + hinge + R"("axis": [0, 1, 0], "break_force": 0})",
       "f.json: joint 0: break_force: must be positive"},
      {R"({"type": "slider", "bodies": ["a", "b"], "axis": [1, 0, 0],
          "motor": {"speed": 1, "max_force": -2}})",
       "f.json: joint 0: motor.max_force: must not be negative"},
      {R"({"type": "cone", "bodies": ["a", "b"], "anchor": [0, 0, 0], "axis": [1, 0, 0],
          "swing_limit": 3.5})",
       "f.json: joint 0: swing_limit: must be in [0, pi] rad"},
      {R"({"type": "cone", "bodies": ["a", "b"], "anchor": [0, 0, 0], "axis": [1, 0, 0],
          "swing_limit": -0.1})",
       "f.json: joint 0: swing_limit: must be in [0, pi] rad"},
      {R"({"type": "cone", "bodies": ["a", "b"], "anchor": [0, 0, 0], "axis": [1, 0, 0],
          "twist_limits": [0.5, 0.2]})",
       "f.json: joint 0: twist_limits: lo > hi"},
      {R"({"type": "distance", "bodies": ["a", "b"], "anchors": [[0, 0, 0], [0, 1, 0]],
          "min_length": 2, "max_length": 1})",
       "f.json: joint 0: min_length: min_length 2 is above max_length 1"},
      {R"({"type": "distance", "bodies": ["a", "b"], "anchors": [[0, 0, 0], [0, 1, 0]],
          "min_length": 2})",
       "f.json: joint 0: min_length: min_length 2 is above the distance at load, 1"},
      {R"({"type": "distance", "bodies": ["a", "b"], "anchors": [[0, 0, 0], [0, 1, 0]],
          "max_length": 0.5})",
       "f.json: joint 0: max_length: max_length 0.5 is below the distance at load, 1"},
      {R"({"type": "distance", "bodies": ["a", "b"], "anchors": [[0, 0, 0], [0, 1, 0]],
          "max_length": -1})",
       "f.json: joint 0: max_length: must not be negative"},
      {R"({"type": "distance", "bodies": ["a", "b"], "anchors": [[0, 0, 0]]})",
       "f.json: joint 0: anchors: expected two points"},
      {R"({"type": "distance", "bodies": ["a", "b"], "anchors": [[0, 0, 0], [0, 1, 0]],
          "spring": {"frequency": 1, "target": 1}})",
       "f.json: joint 0: spring.target: unknown key for a distance spring"},
      {R"({"type": "distance", "bodies": ["a", "b"], "anchors": [[0, 0, 0], [0, 1, 0]],
          "rest_length": 1, "spring": {"frequency": 1, "rest_length": 1}})",
       "f.json: joint 0: rest_length: given twice"},
      {R"({"type": "ball", "bodies": ["a", "b"], "anchor": [0, 0, 0], "name": "j"},
          {"type": "ball", "bodies": ["a", "b"], "anchor": [0, 0, 0], "name": "j"})",
       "f.json: joint 1 (\"j\"): name: duplicate name \"j\" (also joint 0)"},
      {R"({"type": "ball", "bodies": ["a", "b"], "anchor": [0, 0, 0], "name": 3})",
       "f.json: joint 0: name: expected a string"},
      {R"(3)", "f.json: joint 0: expected an object"},
  };
  for (const Case& c : cases) {
    const std::string m = message(scene(c.joints));
    EXPECT_EQ(m.rfind(c.expected, 0), 0u) << "expected: " << c.expected << "\n     got: " << m;
  }
  EXPECT_EQ(message(R"({"joints": {}})"),
            "f.json: joints: expected an array of joints, got an object");
}

TEST(SceneJoints, GeneratorErrorsNameTheGeneratorAndField) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"type": "chain", "links": 0, "link": {"shape": {"type": "sphere", "radius": 1}}})",
       "f.json: generator 0 (chain): links: must be at least 1"},
      {R"({"type": "chain", "links": 2})", "f.json: generator 0 (chain): link: missing"},
      {R"({"type": "chain", "links": 2, "link": {"motion": "static",
          "shape": {"type": "sphere", "radius": 1}}})",
       "f.json: generator 0 (chain): link.motion: a link must be dynamic"},
      {R"({"type": "chain", "links": 2, "joint": "cone",
          "link": {"shape": {"type": "sphere", "radius": 1}}})",
       "f.json: generator 0 (chain): joint: unknown chain joint \"cone\""},
      {R"({"type": "chain", "links": 2, "axis": [1, 0, 0],
          "link": {"shape": {"type": "sphere", "radius": 1}}})",
       "f.json: generator 0 (chain): axis: only a hinge chain has an axis"},
      {R"({"type": "chain", "links": 2, "direction": [0, 0, 0],
          "link": {"shape": {"type": "sphere", "radius": 1}}})",
       "f.json: generator 0 (chain): direction: zero vector"},
      {R"({"type": "chain", "links": 2, "count": [2, 1, 1],
          "link": {"shape": {"type": "sphere", "radius": 1}}})",
       "f.json: generator 0 (chain): spacing: missing"},
      {R"({"type": "ragdoll", "scale": 0})",
       "f.json: generator 0 (ragdoll): scale: must be positive"},
      {R"({"type": "ragdoll", "arms": 2})", "f.json: generator 0 (ragdoll): arms: unknown key"},
      {R"({"type": "ragdoll", "count": [1000, 1000, 1], "spacing": [1, 1, 1]})",
       "f.json: generator 0 (ragdoll): count: too many bodies"},
      {R"({"type": "joint_grid", "count": 0})",
       "f.json: generator 0 (joint_grid): count: must be at least 1"},
      {R"({"type": "joint_grid", "count": 4000})",
       "f.json: generator 0 (joint_grid): count: must be at most 3162"},
      {R"({"type": "joint_grid", "count": 4, "pinned": "left"})",
       "f.json: generator 0 (joint_grid): pinned: unknown pinning \"left\""},
  };
  for (const auto& [gen, expected] : cases) {
    const std::string m = message(R"({"generators": [)" + gen + "]}");
    EXPECT_EQ(m.rfind(expected, 0), 0u) << "expected: " << expected << "\n     got: " << m;
  }
}

TEST(SceneJoints, ChainHangsLinksEndToEndFromThePinnedPoint) {
  const Scene s = parse_scene(R"({"generators": [{"type": "chain", "links": 4, "origin": [1, 10, 0],
      "link": {"shape": {"type": "capsule", "radius": 0.1, "half_height": 0.15}, "density": 500},
      "joint": "hinge", "axis": [0, 0, 2], "count": [2, 1, 1], "spacing": [3, 0, 0]}]})",
                              "t");
  ASSERT_EQ(s.bodies.size(), 8u);
  ASSERT_EQ(s.joints.size(), 8u);
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < 4; ++i) {
      const SceneBody& b = s.bodies[std::size_t(4 * c + i)];
      EXPECT_EQ(b.shape.type, ShapeType::Capsule);
      EXPECT_EQ(b.body.density, Real(500));
      // Links 0.5 m long (the default spacing) hang straight down from (1 + 3c, 10, 0).
      EXPECT_NEAR(b.body.position.x(), 1 + 3 * c, 1e-6);
      EXPECT_NEAR(b.body.position.y(), 10 - 0.5 * (i + 0.5), 1e-6);
      EXPECT_NEAR(std::abs((b.body.orientation * Vec3::UnitY()).y()), 1, 1e-6);
      const SceneJoint& j = s.joints[std::size_t(4 * c + i)];
      EXPECT_EQ(j.def.type, JointType::Hinge);
      EXPECT_EQ(j.def.axis, Vec3(0, 0, 1));
      EXPECT_EQ(j.body_a, 4 * c + i);
      EXPECT_EQ(j.body_b, i == 0 ? -1 : 4 * c + i - 1);
      EXPECT_NEAR(j.def.anchor.y(), 10 - 0.5 * i, 1e-6);
    }
  }
}

TEST(SceneJoints, ChainFollowsItsDirection) {
  const Scene s = parse_scene(R"({"generators": [{"type": "chain", "links": 3,
      "direction": [1, 0, 0], "link_spacing": 0.4,
      "link": {"shape": {"type": "box", "half_extents": [0.05, 0.2, 0.05]}}}]})",
                              "t");
  ASSERT_EQ(s.joints.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const SceneBody& b = s.bodies[std::size_t(i)];
    EXPECT_NEAR(b.body.position.x(), 0.4 * (i + 0.5), 1e-6);
    EXPECT_NEAR(b.body.position.y(), 0, 1e-6);
    // The link's own Y axis lies along the chain.
    EXPECT_NEAR((b.body.orientation * Vec3::UnitY()).x(), 1, 1e-6);
    EXPECT_EQ(s.joints[std::size_t(i)].def.type, JointType::Ball);
    EXPECT_NEAR(s.joints[std::size_t(i)].def.anchor.x(), 0.4 * i, 1e-6);
  }
}

TEST(SceneJoints, JointGridIsBox2dsBenchmark) {
  const Scene s = parse_scene(R"({"generators": [{"type": "joint_grid", "count": 100}]})", "t");
  ASSERT_EQ(s.bodies.size(), 10000u);
  // 2 n (n - 1) joints but the six between the seven pinned spheres of the top row.
  ASSERT_EQ(s.joints.size(), 2u * 100u * 99u - 6u);
  std::size_t statics = 0;
  for (std::size_t k = 0; k < 100; ++k) {
    for (std::size_t i = 0; i < 100; ++i) {
      const SceneBody& b = s.bodies[k * 100 + i];
      EXPECT_EQ(b.shape.radius, Real(0.4));
      ASSERT_EQ(b.body.position, Vec3(Real(k), -Real(i), 0));
      statics += b.body.motion == MotionType::Static;
      // The spheres pass through one another: Box2D's filter.
      EXPECT_EQ(b.body.category_bits & b.body.mask_bits, 0u);
    }
  }
  EXPECT_EQ(statics, 7u);
  for (int k = 47; k <= 53; ++k) {
    EXPECT_EQ(s.bodies[std::size_t(k * 100)].body.motion, MotionType::Static) << k;
  }
  for (const SceneJoint& j : s.joints) {
    ASSERT_GE(j.body_b, 0);
    EXPECT_EQ(j.def.type, JointType::Ball);
    const Vec3 mid = (s.bodies[std::size_t(j.body_a)].body.position +
                      s.bodies[std::size_t(j.body_b)].body.position) /
                     2;
    EXPECT_EQ(j.def.anchor, mid);
    EXPECT_EQ((s.bodies[std::size_t(j.body_a)].body.position -
               s.bodies[std::size_t(j.body_b)].body.position)
                  .norm(),
              Real(1));
  }
  const Scene row = parse_scene(
      R"({"generators": [{"type": "joint_grid", "count": 5, "pinned": "row", "spacing": 2,
          "radius": 0.5, "origin": [1, 20, 3]}]})",
      "t");
  EXPECT_EQ(row.joints.size(), 2u * 5u * 4u - 4u);
  EXPECT_EQ(row.bodies[6].body.position, Vec3(3, 18, 3));
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(row.bodies[k * 5].body.motion, MotionType::Static);
    EXPECT_EQ(row.bodies[k * 5 + 1].body.motion, MotionType::Dynamic);
  }
}

// Signed distance from a world point to a body's surface (negative inside).
double surface_distance(const SceneBody& b, const Vec3& world) {
  const Eigen::Vector3d p =
      (b.body.orientation.conjugate() * (world - b.body.position)).cast<double>();
  const ShapeDef& s = b.shape;
  switch (s.type) {
    case ShapeType::Sphere:
      return p.norm() - double(s.radius);
    case ShapeType::Capsule: {
      const double y = std::clamp(p.y(), -double(s.half_height), double(s.half_height));
      return (p - Eigen::Vector3d(0, y, 0)).norm() - double(s.radius);
    }
    case ShapeType::Box: {
      const Eigen::Vector3d q = p.cwiseAbs() - s.half_extents.cast<double>();
      return q.cwiseMax(0).norm() + std::min(q.maxCoeff(), 0.0);
    }
    default:
      return 1e9;
  }
}

TEST(SceneJoints, RagdollJointsLieWhereItsPartsTouch) {
  for (const char* extra :
       {"", R"(, "hands": false)", R"(, "scale": 0.5, "orientation": [0.5, 0.5, 0.5, 0.5])"}) {
    const Scene s = parse_scene(R"j({"generators": [{"type": "ragdoll", "origin": [2, 3, 4],
        "count": [2, 1, 3], "spacing": [3, 0, 2])j" +
                                    std::string(extra) + "}]}",
                                "t");
    const bool hands = std::string(extra).find("hands") == std::string::npos;
    const std::size_t parts = hands ? 16 : 14;
    ASSERT_EQ(s.bodies.size(), 6 * parts) << extra;
    ASSERT_EQ(s.joints.size(), 6 * (parts - 1)) << extra;
    const double tolerance = 1e-5;
    for (std::size_t i = 0; i < s.joints.size(); ++i) {
      const SceneJoint& j = s.joints[i];
      // Each ragdoll's joints join its own parts, child (A) to parent (B): a tree.
      ASSERT_GE(j.body_b, 0);
      EXPECT_EQ(std::size_t(j.body_a) / parts, i / (parts - 1)) << i;
      EXPECT_EQ(std::size_t(j.body_b) / parts, i / (parts - 1)) << i;
      EXPECT_NEAR(surface_distance(s.bodies[std::size_t(j.body_a)], j.def.anchor), 0, tolerance)
          << extra << " joint " << i;
      EXPECT_NEAR(surface_distance(s.bodies[std::size_t(j.body_b)], j.def.anchor), 0, tolerance)
          << extra << " joint " << i;
      const JointDef& d = j.def;
      EXPECT_TRUE(d.type == JointType::Cone || d.type == JointType::Hinge);
      EXPECT_TRUE(d.limits.enabled);
      EXPECT_LT(d.limits.lower, d.limits.upper);
      EXPECT_GE(d.limits.lower, -Real(3.14159265358979323846));
      EXPECT_LE(d.limits.upper, Real(3.14159265358979323846));
      EXPECT_NEAR(d.axis.norm(), 1, 1e-6);
      if (d.type == JointType::Cone) {
        EXPECT_GT(d.swing_limit, 0);
        EXPECT_LT(d.swing_limit, Real(3.14159265358979323846) / 1.5);
      } else {
        // A hinge bends one way only: straight (0) is one end of its range, or inside a short
        // one (the ankle).
        EXPECT_LE(d.limits.lower, 0);
        EXPECT_GE(d.limits.upper, 0);
      }
    }
    // No part's centre lies inside another part: the figure does not start tangled.
    for (std::size_t a = 0; a < parts; ++a) {
      for (std::size_t b = 0; b < parts; ++b) {
        if (a != b) {
          EXPECT_GT(surface_distance(s.bodies[b], s.bodies[a].body.position), 0) << a << " " << b;
        }
      }
    }
  }
}

TEST(SceneJoints, RagdollKneesAndElbowsBendTheHumanWay) {
  const Scene s = parse_scene(R"({"generators": [{"type": "ragdoll"}]})", "t");
  // A knee's positive angle swings the shin (A) back, away from the facing direction +z: the
  // shin's downward direction turned about the axis by a small positive angle gains -z.
  int hinges = 0;
  for (const SceneJoint& j : s.joints) {
    if (j.def.type != JointType::Hinge) continue;
    ++hinges;
    const Vec3 child = s.bodies[std::size_t(j.body_a)].body.position - j.def.anchor;
    const Vec3 turned = Eigen::AngleAxis<Real>(Real(0.5), j.def.axis) * child;
    const bool knee_or_ankle = std::abs(j.def.axis.x()) > Real(0.5);
    if (knee_or_ankle && child.y() < Real(-0.1)) {
      EXPECT_LT(turned.z(), child.z() - Real(0.05)) << "knee bends backward";
      EXPECT_EQ(j.def.limits.lower, 0);
    } else if (!knee_or_ankle) {
      EXPECT_GT(turned.z(), child.z() + Real(0.05))
          << "elbow bends forward " << child.transpose() << " axis " << j.def.axis.transpose();
      EXPECT_EQ(j.def.limits.lower, 0);
    }
  }
  EXPECT_EQ(hinges, 6);  // elbows, knees, ankles
}

TEST(SceneJoints, LoadIntoCreatesTheJointsInSceneOrder) {
  const Scene s = parse_scene(
      scene(R"({"type": "hinge", "name": "h", "bodies": ["a", null], "anchor": [0, 3, 0],
        "axis": [1, 0, 0]},
      {"type": "ball", "bodies": ["b", "a"], "anchor": [0, 3, 0]})",
            R"([{"type": "ragdoll", "origin": [5, 0, 0]}])"),
      "t");
  World world;
  load_into(s, world, "t");
  ASSERT_EQ(world.joint_count(), s.joints.size());
  for (std::size_t j = 0; j < s.joints.size(); ++j) {
    const JointDef& d = world.joint_def(world.joint_at(j));
    EXPECT_EQ(d.type, s.joints[j].def.type) << j;
    EXPECT_EQ(d.body_a, world.body_at(std::size_t(s.joints[j].body_a))) << j;
    if (s.joints[j].body_b < 0) {
      EXPECT_TRUE(d.body_b.is_null()) << j;
    } else {
      EXPECT_EQ(d.body_b, world.body_at(std::size_t(s.joints[j].body_b))) << j;
    }
  }
}

// A few ragdolls dropped in a heap stay in one piece: each joint's two anchors, carried by the
// bodies from their load poses, still meet after two seconds, and nothing is flung away.
TEST(SceneJoints, RagdollHeapHoldsTogether) {
  const Scene s = parse_scene(R"j({"bodies": [{"motion": "static",
        "shape": {"type": "box", "half_extents": [20, 1, 20]}, "position": [0, -1, 0]}],
      "generators": [
        {"type": "ragdoll", "origin": [-1, 0.5, 0.9], "orientation": [0.70710678, -0.70710678, 0, 0],
         "count": [2, 2, 1], "spacing": [2, 0.6, 0]},
        {"type": "ragdoll", "origin": [0, 1.6, -0.5], "orientation": [0.70710678, 0, 0.70710678, 0]}]})j",
                              "t");
  World world(s.world);
  load_into(s, world, "t");
  ASSERT_EQ(world.joint_count(), 5u * 15u);
  // Each anchor in its body's frame, at load.
  struct Local {
    Vec3 a, b;
  };
  std::vector<Local> local;
  for (const SceneJoint& j : s.joints) {
    const SceneBody& a = s.bodies[std::size_t(j.body_a)];
    const SceneBody& b = s.bodies[std::size_t(j.body_b)];
    local.push_back({a.body.orientation.conjugate() * (j.def.anchor - a.body.position),
                     b.body.orientation.conjugate() * (j.def.anchor - b.body.position)});
  }
  for (int i = 0; i < 120; ++i) world.step(s.timestep);
  for (std::size_t k = 0; k < s.joints.size(); ++k) {
    const BodyId a = world.body_at(std::size_t(s.joints[k].body_a));
    const BodyId b = world.body_at(std::size_t(s.joints[k].body_b));
    const Vec3 wa = world.position(a) + world.orientation(a) * local[k].a;
    const Vec3 wb = world.position(b) + world.orientation(b) * local[k].b;
    EXPECT_LT((wa - wb).norm(), Real(0.02)) << "joint " << k;
  }
  for (std::size_t i = 1; i < world.body_count(); ++i) {
    const Vec3 p = world.position(world.body_at(i));
    EXPECT_TRUE(p.allFinite()) << i;
    EXPECT_LT(p.norm(), Real(6)) << i;
    EXPECT_GT(p.y(), Real(-0.01)) << i;
  }
}

// Past the parser, the library must still refuse a bad joint, and the message speaks the file's
// language: the joint as the file numbers and names it, the field as the file spells it.
TEST(SceneJoints, LibraryErrorsArePrefixedWithFileAndJoint) {
  Scene s = parse_scene(scene(R"({"type": "ball", "bodies": ["a", "b"], "anchor": [0, 3, 0]},
      {"type": "hinge", "name": "h", "bodies": ["a", null], "anchor": [0, 3, 0], "axis": [1, 0, 0]})"),
                        "t.json");
  s.joints[1].def.axis = Vec3::Zero();
  World world;
  try {
    load_into(s, world, "t.json");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("t.json: joint 1 (\"h\"): axis", 0), 0u) << m;
  }
}

TEST(SceneJoints, LibraryFieldsAreNamedAsInTheFile) {
  using detail::scene_file::scene_field;
  EXPECT_EQ(scene_field(JointType::Hinge, "motor.max_force"), "motor.max_torque");
  EXPECT_EQ(scene_field(JointType::Slider, "motor.max_force"), "motor.max_force");
  EXPECT_EQ(scene_field(JointType::Cone, "limits"), "twist_limits");
  EXPECT_EQ(scene_field(JointType::Cone, "limits.lower"), "twist_limits.lower");
  EXPECT_EQ(scene_field(JointType::Distance, "anchor"), "anchors[0]");
  EXPECT_EQ(scene_field(JointType::Distance, "anchor_b"), "anchors[1]");
  EXPECT_EQ(scene_field(JointType::Distance, "spring.target"), "rest_length");
  EXPECT_EQ(scene_field(JointType::Ball, "body_a"), "bodies");
  EXPECT_EQ(scene_field(JointType::Ball, "body_b"), "bodies");
  EXPECT_EQ(scene_field(JointType::Hinge, "axis"), "axis");
}

}  // namespace scene_joints_test
}  // namespace elan
