// SPDX-License-Identifier: MIT
// The supported ranges (elan/limits.hpp) through the elan binary. Each file of reproducers/ is a
// scene that fuzzing found to run with exit 0 while printing null (NaN or inf) totals or
// freezing bodies; now each is refused at load, exit 2, with one line naming the file, the body
// and the field. A scene of the abuse the issue lists, at the bounds, runs to a summary whose
// every number is finite.
#include <gtest/gtest.h>

#include "cli/cli_runner.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

namespace elan::cli_limits_test {

using Json = nlohmann::json;
using namespace elan::test;

// Runs a reproducer: exit 2, nothing on stdout, one stderr line naming the file and `expected`.
void expect_refused(const std::string& file, const std::string& expected) {
  const std::string path = std::string(ELAN_REPRODUCERS) + "/" + file;
  const Result r = run_elan({"run", path, "--steps", "3", "--threads", "1"});
  EXPECT_EQ(r.status, 2) << r.err << r.out;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind(path + ": ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(expected), std::string::npos)
      << "expected '" << expected << "' in " << r.err;
}

// Box half extents 1e10: its inertia overflowed float, inverse 0, and I w = inf * 0 = NaN.
TEST(CliLimits, BoxWhoseInertiaOverflowsIsRefused) {
  expect_refused("nonfinite_big_box_inertia.json",
                 "body 0: shape.half_extents: must be in [0.0001, 10000] m, got 1e+10");
}

// linear_velocity 1e20 m/s: m v^2 overflowed float.
TEST(CliLimits, BodyFasterThanTheSpeedBoundIsRefused) {
  expect_refused("nonfinite_ke_fast_body.json",
                 "body 0: linear_velocity: length must be at most 100000 m/s, got 1e+20");
}

// x = 3e38: the angular momentum m x × v overflowed.
TEST(CliLimits, BodyFartherThanThePositionBoundIsRefused) {
  expect_refused("nonfinite_angmom_far_body.json",
                 "body 0: position: each coordinate must be in "
                 "[-100000, 100000] m, got x = 3e+38");
}

// gravity 1e38 m/s^2: the first step's velocity overflowed.
TEST(CliLimits, GravityStrongerThanItsBoundIsRefused) {
  expect_refused("nonfinite_huge_gravity.json",
                 "gravity: length must be at most 100000 m/s^2, got 1e+38");
}

// mass 1e-40: inverse mass inf; the body and the box on it were frozen at step 1.
TEST(CliLimits, TinyMassThatFrozeItsStackIsRefused) {
  expect_refused("tiny_mass_freezes_stack.json", "body 1: mass: must be in [1e-09, 1e+09] kg");
}

// radius 1e-30 with mass 1: inertia 0, frozen at step 1.
TEST(CliLimits, TinyRadiusWithExplicitMassIsRefused) {
  expect_refused("tiny_radius_explicit_mass_frozen.json",
                 "body 1: shape.radius: must be in [0.0001, 10000] m, got 1e-30");
}

// radius 1e20: its volume overflowed to inf and the message said "computed mass is not
// positive"; now the radius itself is named.
TEST(CliLimits, HugeSphereIsRefusedNamingItsRadiusNotAMassThatIsNotPositive) {
  expect_refused("huge_sphere_mass_message.json",
                 "body 0: shape.radius: must be in [0.0001, 10000] m, got 1e+20");
  const Result r =
      run_elan({"run", std::string(ELAN_REPRODUCERS) + "/huge_sphere_mass_message.json"});
  EXPECT_EQ(r.err.find("not positive"), std::string::npos) << r.err;
}

// Sizes and density each within range whose product is not: the computed mass is named.
TEST(CliLimits, ComputedMassOutOfRangeIsNamedAsSuch) {
  expect_refused("computed_mass_out_of_range.json",
                 "body 0 (\"slab\"): mass: computed mass is out of range: density 1e+09 kg/m^3 x "
                 "volume 8e+12 m^3 = 8e+21 kg");
}

// Found while choosing the ranges: friction 1e38 froze both bodies at step 1, restitution 1e30
// the falling one at its first bounce (exit 0, a warning).
TEST(CliLimits, FrictionThatFrozeBodiesIsRefused) {
  expect_refused("friction_1e38_froze_bodies.json",
                 "body 0: friction: must be in [0, 100], got 1e+38");
}

TEST(CliLimits, RestitutionAboveOneIsRefused) {
  expect_refused("restitution_1e30_froze_bodies.json",
                 "body 0: restitution: must be in [0, 1], got 1e+30");
}

TEST(CliLimits, SceneTimestepOutOfRangeIsRefused) {
  expect_refused("timestep_out_of_range.json", "timestep: must be in [1e-06, 1] s, got 1e+30");
}

// --timestep takes the same range as the scene's: outside it every step would do nothing.
TEST(CliLimits, TimestepOptionOutOfRangeIsRefusedNamingTheFlag) {
  const std::string scene = temp_path("ok.json");
  write(scene, kSmallScene);
  for (const char* dt : {"5", "1e-7"}) {
    const Result r = run_elan({"run", scene, "--steps", "1", "--timestep", dt});
    EXPECT_EQ(r.status, 2) << dt << ": " << r.err;
    EXPECT_NE(r.err.find("--timestep: must be in [1e-06, 1] s"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  EXPECT_EQ(run_elan({"run", scene, "--steps", "1", "--timestep", "1"}).status, 0);
}

// The issue's abuse bodies (1e4 m/s, 1e4 rad/s, gravity 1e4 m/s^2) and bodies at every bound:
// exit 0, status 0, and every total a finite number (JSON null would be NaN or inf).
TEST(CliLimits, SceneAtTheBoundsRunsToAFiniteSummary) {
  const std::string scene = temp_path("bounds.json");
  write(scene, R"({"gravity": [0, -1e4, 0], "bodies": [
    {"motion": "static", "shape": {"type": "box", "half_extents": [10000, 1, 10000]},
     "position": [0, -1, 0]},
    {"shape": {"type": "sphere", "radius": 0.2}, "position": [0, 1, 0],
     "linear_velocity": [1e4, 0, 0]},
    {"shape": {"type": "capsule", "radius": 0.2, "half_height": 0.5}, "position": [5, 2, 0],
     "angular_velocity": [1e4, 0, 0]},
    {"shape": {"type": "box", "half_extents": [0.0001, 0.0001, 0.0001]}, "position": [10, 0.0001, 0],
     "mass": 1e-9},
    {"shape": {"type": "box", "half_extents": [100, 100, 100]}, "position": [10, 101, 0],
     "mass": 1e9},
    {"shape": {"type": "sphere", "radius": 10000}, "position": [100000, 100000, -100000],
     "linear_velocity": [1e5, 0, 0], "angular_velocity": [0, 1e5, 0], "mass": 1e9},
    {"shape": {"type": "convex_hull", "points": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]]},
     "position": [-5, 1, 0], "linear_velocity": [0, -1e5, 0]}]})");
  const Result r = run_elan({"run", scene, "--steps", "60", "--threads", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Json out = Json::parse(r.out);
  EXPECT_EQ(out["status"].get<int>() & 1, 0) << r.out;  // kStepFrozeNonFinite
  ASSERT_TRUE(out["kinetic_energy"].is_number()) << r.out;
  EXPECT_TRUE(std::isfinite(out["kinetic_energy"].get<double>())) << r.out;
  for (const char* key : {"linear_momentum", "angular_momentum"}) {
    for (const Json& x : out[key]) {
      ASSERT_TRUE(x.is_number()) << key << ": " << r.out;
      EXPECT_TRUE(std::isfinite(x.get<double>())) << key << ": " << r.out;
    }
  }
}

}  // namespace elan::cli_limits_test
