// SPDX-License-Identifier: MIT
// Runs the built `elan` binary: bad scenes and bad arguments exit 2 with a one-line message naming
// the field, the summary has the contract's keys, trajectories and recordings round-trip.
#include <gtest/gtest.h>

#include "cli/cli_runner.hpp"
#include "tools/recording.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Json = nlohmann::json;

using namespace elan::test;

std::string small_scene() {
  const std::string path = temp_path("scene.json");
  write(path, kSmallScene);
  return path;
}

struct BadScene {
  const char* file;
  const char* field;  // must appear in the message
};

void PrintTo(const BadScene& c, std::ostream* os) {
  *os << c.file;
}

class BadSceneFile : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneFile, ExitsTwoWithOneLineNamingTheField) {
  const BadScene& c = GetParam();
  const Result r = run_elan({"run", std::string(ELAN_BAD_SCENES) + "/" + c.file, "--steps", "1"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(c.file), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(c.field), std::string::npos) << "expected '" << c.field << "' in " << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

INSTANTIATE_TEST_SUITE_P(
    Cli, BadSceneFile,
    ::testing::Values(
        BadScene{"malformed.json", ":3:15: malformed JSON"},
        BadScene{"nan_token.json", "malformed JSON at gravity[1]"},
        BadScene{"infinity_token.json", "malformed JSON at gravity[1]"},
        BadScene{"overflow.json", "shape.radius: number overflow"},
        BadScene{"empty.json", "empty file"}, BadScene{"top_level_array.json", "JSON object"},
        BadScene{"trailing_garbage.json", "end of input"}, BadScene{"deep_nesting.json", "nesting"},
        BadScene{"missing_shape.json", "body 0: shape: missing"},
        BadScene{"missing_radius.json", "body 0: shape.radius: missing"},
        BadScene{"wrong_type_radius.json", "body 0 (\"ball\"): shape.radius: expected a number"},
        BadScene{"wrong_type_sleep.json", "allow_sleep"},
        BadScene{"wrong_type_bodies.json", "bodies: expected an array"},
        BadScene{"short_vector.json", "body 0: position: expected 3 numbers, got 2"},
        BadScene{"long_vector.json", "gravity: expected 3 numbers, got 4"},
        BadScene{"negative_radius.json", "body 1 (\"ball\"): shape.radius: must be positive"},
        BadScene{"zero_half_extent.json", "shape.half_extents[1]: must be positive"},
        BadScene{"zero_half_height.json", "shape.half_height: must be positive"},
        BadScene{"zero_mass.json", "body 0: mass: must be positive"},
        BadScene{"negative_density.json", "body 0: density: must be positive"},
        BadScene{"negative_friction.json", "body 0: friction"},
        BadScene{"mass_and_density.json", "mass: give either mass or density"},
        BadScene{"degenerate_hull.json", "body 0: shape.points: degenerate hull"},
        BadScene{"few_hull_points.json", "body 0: shape.points"},
        BadScene{"unknown_world_key.json", "gravty: unknown key"},
        BadScene{"unknown_body_key.json", "body 0: colour: unknown key"},
        BadScene{"unknown_shape_key.json", "shape.half_extents: unknown key for a sphere"},
        BadScene{"unknown_generator_key.json", "generator 0 (pyramid): size: unknown key"},
        BadScene{"unknown_shape_type.json", "shape.type: unknown shape type \"torus\""},
        BadScene{"unknown_motion.json", "motion: unknown motion"},
        BadScene{"unknown_generator_type.json", "generator 0 (spiral): type"},
        BadScene{"dynamic_plane.json", "motion: a plane must be static"},
        BadScene{"zero_plane_normal.json", "shape.normal"},
        BadScene{"duplicate_name.json", "body 1 (\"a\"): name: duplicate name"},
        BadScene{"duplicate_key.json", "body 0: shape.radius: duplicate key"},
        BadScene{"huge_grid.json", "generator 0 (grid): count: too many bodies"},
        BadScene{"huge_pyramid.json", "generator 0 (pyramid): base: too many bodies"},
        BadScene{"huge_total.json", "too many bodies"},
        BadScene{"grid_template_error.json", "generator 0 (grid): body.shape.radius"},
        BadScene{"grid_missing_body.json", "body: missing"},
        BadScene{"grid_zero_count.json", "count[1]: must be at least 1"},
        BadScene{"grid_named_body.json", "body.name"},
        BadScene{"pyramid_fraction_base.json", "base: expected an integer"},
        BadScene{"zero_timestep.json", "timestep: must be positive"},
        BadScene{"negative_timestep.json", "timestep: must be positive"},
        BadScene{"zero_substeps.json", "substeps: must be at least 1"},
        BadScene{"zero_iterations.json", "iterations: must be at least 1"},
        BadScene{"zero_quaternion.json", "body 0: orientation: zero quaternion"},
        BadScene{"joints_not_array.json", "joints: expected an array of joints"},
        BadScene{"joint_unknown_body.json", "joint 0 (\"j\"): bodies[1]: no body named \"c\""},
        BadScene{"joint_body_out_of_range.json", "joint 0: bodies[1]: no body 3"},
        BadScene{"joint_missing_bodies.json", "joint 0: bodies: missing"},
        BadScene{"joint_same_body.json", "joint 0: bodies: the same body twice"},
        BadScene{"joint_two_static.json", "joint 1: bodies: at least one body must be dynamic"},
        BadScene{"joint_unknown_key.json", "joint 0: axis: unknown key for a ball joint"},
        BadScene{"joint_unknown_type.json", "joint 0: type: unknown joint type \"weld\""},
        BadScene{"joint_missing_anchor.json", "joint 0 (\"neck\"): anchor: missing"},
        BadScene{"joint_wrong_type_limits.json", "joint 0: limits: expected an array"},
        BadScene{"joint_non_finite.json", "joint 0: anchor[1]: not a finite number"},
        BadScene{"joint_zero_axis.json", "joint 0: axis: zero axis"},
        BadScene{"joint_reversed_limits.json", "joint 0 (\"door\"): limits: lo > hi"},
        BadScene{"joint_limit_beyond_pi.json", "joint 0: limits[0]: must be in [-pi, pi]"},
        BadScene{"joint_negative_torque.json", "joint 0: motor.max_torque: must not be negative"},
        BadScene{"joint_negative_force.json", "joint 0: motor.max_force: must not be negative"},
        BadScene{"joint_zero_frequency.json", "joint 0: spring.frequency: must be positive"},
        BadScene{"joint_negative_damping.json", "joint 0: spring.damping_ratio: must not be"},
        BadScene{"joint_swing_beyond_pi.json", "joint 0: swing_limit: must be in [0, pi]"},
        BadScene{"joint_reversed_twist.json", "joint 0: twist_limits: lo > hi"},
        BadScene{"joint_min_above_max.json", "joint 0: min_length: min_length 3 is above"},
        BadScene{"joint_negative_friction.json", "joint 0 (\"shoulder\"): friction:"},
        BadScene{"joint_negative_length.json", "joint 0: min_length: must not be negative"},
        BadScene{"joint_zero_break_force.json", "joint 0: break_force: must be positive"},
        BadScene{"joint_duplicate_name.json", "joint 1 (\"j\"): name: duplicate name"},
        BadScene{"chain_kinematic_link.json", "generator 0 (chain): link.motion"},
        BadScene{"ragdoll_negative_scale.json", "generator 0 (ragdoll): scale: must be positive"},
        BadScene{"joint_grid_zero_count.json", "generator 0 (joint_grid): count"},
        BadScene{"mesh_index_out_of_range.json",
                 "body 0 (\"m\"): shape.triangles: triangle 1: index 7 is out of range"},
        BadScene{"mesh_repeated_index.json",
                 "body 0 (\"m\"): shape.triangles: triangle 2: repeated vertex index"},
        BadScene{"mesh_zero_area.json", "body 0 (\"m\"): shape.triangles: triangle 1: "},
        BadScene{"dynamic_mesh.json", "body 0 (\"m\"): motion: a mesh must be static"},
        BadScene{"heightfield_ragged_row.json",
                 "body 0 (\"h\"): shape.heights: row 2 has 2 heights, row 0 has 3"},
        BadScene{"heightfield_too_small.json",
                 "body 0 (\"h\"): shape.heights: at least 2 rows of 2 heights"},
        BadScene{"heightfield_all_holes.json",
                 "body 0 (\"h\"): shape.heights: the holes (NaN heights) leave no triangle"},
        BadScene{"heightfield_zero_spacing.json",
                 "body 0 (\"h\"): shape.spacing[1]: must be positive"},
        BadScene{"dynamic_heightfield.json",
                 "body 0 (\"h\"): motion: a heightfield must be static"},
        BadScene{
            "compound_plane_child.json",
            "body 1 (\"c\"): shape.children[1].shape.type: a compound child cannot be a plane"},
        BadScene{"compound_mesh_child.json",
                 "body 1 (\"c\"): shape.children[1].shape.type: a compound child cannot be a mesh"},
        BadScene{"compound_heightfield_child.json",
                 "body 1 (\"c\"): shape.children[1].shape.type: a compound child cannot be a "
                 "heightfield"},
        BadScene{"compound_compound_child.json",
                 "body 1 (\"c\"): shape.children[1].shape.type: a compound child cannot be a "
                 "compound"},
        BadScene{"compound_empty.json",
                 "body 1 (\"c\"): shape.children: a compound needs at least one child"},
        BadScene{"obj_missing.json", "body 0 (\"m\"): shape.file: " ELAN_BAD_SCENES
                                     "/no_such_mesh.obj: cannot open Wavefront OBJ"},
        BadScene{"obj_malformed.json",
                 "body 0 (\"m\"): shape.file: " ELAN_BAD_SCENES "/malformed.obj: malformed OBJ"},
        BadScene{"terrain_zero_cells.json", "generator 0 (terrain): cells[1]: must be at least 1"}),
    [](const ::testing::TestParamInfo<BadScene>& info) {
      std::string name = info.param.file;
      name = name.substr(0, name.find('.'));
      return name;
    });

TEST(Cli, MissingSceneFileExitsTwo) {
  const Result r = run_elan({"run", "/nonexistent/scene.json"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("/nonexistent/scene.json: cannot open"), std::string::npos) << r.err;
}

TEST(Cli, BadArgumentsExitTwoNamingTheOption) {
  const std::string scene = small_scene();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{}, "usage"},
      {{"fly"}, "unknown command 'fly'"},
      {{"run"}, "missing SCENE.json"},
      {{"run", scene, "--steps", "-1"}, "--steps"},
      {{"run", scene, "--steps", "abc"}, "--steps"},
      {{"run", scene, "--steps", "99999999999999999999"}, "--steps"},
      {{"run", scene, "--steps"}, "--steps: missing value"},
      {{"run", scene, "--threads", "0"}, "--threads"},
      {{"run", scene, "--broadphase", "octree"}, "--broadphase"},
      {{"run", scene, "--timestep", "0"}, "--timestep"},
      {{"run", scene, "--timestep", "nan"}, "--timestep"},
      {{"run", scene, "--timestep", "1e999"}, "--timestep"},
      {{"run", scene, "--substeps", "0"}, "--substeps"},
      {{"run", scene, "--iterations", "1.5"}, "--iterations"},
      {{"run", scene, "--every", "0"}, "--every"},
      {{"run", scene, "--bogus"}, "unknown option '--bogus'"},
      {{"run", scene, scene}, "unexpected argument"},
      {{"run", scene, "--steps", "1", "--trajectory", "/nonexistent/dir/t.csv"}, "t.csv"},
      {{"run", scene, "--steps", "1", "--record", "/nonexistent/dir/r.rec"}, "r.rec"},
      {{"replay"}, "missing FILE"},
      {{"replay", "/nonexistent/r.rec"}, "/nonexistent/r.rec"},
      {{"replay", scene, "--threads", "x"}, "--threads"},
  };
  for (const auto& [args, expected] : cases) {
    const Result r = run_elan(args);
    std::string shown;
    for (const std::string& a : args) shown += a + " ";
    EXPECT_EQ(r.status, 2) << shown << "\n" << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << shown << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << shown << "\n" << r.out;
  }
}

TEST(Cli, HelpGoesToStdoutWithStatusZero) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"--help"}, {"run", "--help"}, {"replay", "--help"}}) {
    const Result r = run_elan(args);
    EXPECT_EQ(r.status, 0);
    EXPECT_NE(r.out.find("usage: elan"), std::string::npos) << r.out;
  }
  EXPECT_NE(run_elan({"run", "--help"}).out.find("--trajectory"), std::string::npos);
}

// The summary names the SIMD path that ran; --simd and ELAN_SIMD force one, with the same bits,
// and a path the build or the CPU lacks, or no path at all, is a usage error.
TEST(Cli, SummaryNamesTheSimdPath) {
  const std::vector<std::string> run = {"run", small_scene(), "--steps", "20", "--threads", "1"};
  const Result best = run_elan(run);
  ASSERT_EQ(best.status, 0) << best.err;
  const Json b = Json::parse(best.out);
  const std::string path = b["simd"];
  EXPECT_TRUE(path == "sse2" || path == "avx2" || path == "avx512" || path == "native") << path;
  std::vector<std::string> sse2 = run;
  sse2.insert(sse2.end(), {"--simd", "sse2"});
  const Result forced = run_elan(sse2);
  const Result by_env = run_elan(run, 0, "env ELAN_SIMD=sse2");
  if (path == "native") {
    // A native build has its one path.
    EXPECT_EQ(forced.status, 2) << forced.out;
    EXPECT_NE(forced.err.find("native"), std::string::npos) << forced.err;
    EXPECT_EQ(by_env.status, 2) << by_env.out;
  } else {
    ASSERT_EQ(forced.status, 0) << forced.err;
    EXPECT_EQ(Json::parse(forced.out)["simd"], "sse2");
    EXPECT_EQ(Json::parse(forced.out)["state_hash"], b["state_hash"]);
    ASSERT_EQ(by_env.status, 0) << by_env.err;
    EXPECT_EQ(Json::parse(by_env.out)["simd"], "sse2");
    EXPECT_EQ(Json::parse(by_env.out)["state_hash"], b["state_hash"]);
  }
  std::vector<std::string> bogus = run;
  bogus.insert(bogus.end(), {"--simd", "mmx"});
  const Result bad = run_elan(bogus);
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("--simd: expected sse2, avx2, avx512 or native, got 'mmx'"),
            std::string::npos)
      << bad.err;
  const Result bad_env = run_elan(run, 0, "env ELAN_SIMD=mmx");
  EXPECT_EQ(bad_env.status, 2);
  EXPECT_NE(bad_env.err.find("ELAN_SIMD: 'mmx' is not a SIMD path"), std::string::npos)
      << bad_env.err;
}

TEST(Cli, SummaryHasTheContractKeys) {
  const Result r = run_elan({"run", small_scene(), "--steps", "10", "--threads", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(count_lines(r.out), 1u) << r.out;
  const Json j = Json::parse(r.out);
  for (const char* key :
       {"bodies", "steps", "threads", "broadphase", "wall_seconds", "ms_per_step", "state_hash",
        "kinetic_energy", "linear_momentum", "angular_momentum", "pairs", "contacts", "awake",
        "timestep", "substeps", "iterations", "profile_ms", "joints", "simd"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["bodies"], 4);
  EXPECT_EQ(j["joints"], 0);
  EXPECT_EQ(j["steps"], 10);
  EXPECT_EQ(j["threads"], 1);
  EXPECT_EQ(j["broadphase"], "sap");
  EXPECT_DOUBLE_EQ(j["timestep"].get<double>(), double(0.01f));
  const std::string hash = j["state_hash"];
  EXPECT_EQ(hash.size(), 16u);
  EXPECT_EQ(hash.find_first_not_of("0123456789abcdef"), std::string::npos) << hash;
  EXPECT_EQ(j["linear_momentum"].size(), 3u);
  EXPECT_EQ(j["angular_momentum"].size(), 3u);
  EXPECT_GE(j["wall_seconds"].get<double>(), 0.0);
  EXPECT_GT(j["kinetic_energy"].get<double>(), 0.0);  // sphere b slides, the box spins
  for (const char* stage : {"bounds", "pairs", "collide", "islands", "split", "packets", "color",
                            "bundles", "prepare", "solve", "ccd", "finalize", "total"}) {
    EXPECT_TRUE(j["profile_ms"].contains(stage)) << stage;
  }
}

// The summary counts the joints still in the world: the scene's explicit joints and those its
// generators make.
TEST(Cli, SummaryCountsTheJoints) {
  const std::string path = temp_path("jointed.json");
  write(path, R"({"bodies": [
      {"name": "door", "shape": {"type": "box", "half_extents": [0.5, 1, 0.05]},
       "position": [0.5, 1, 0]}],
    "generators": [{"type": "chain", "links": 4, "origin": [3, 5, 0],
                    "link": {"shape": {"type": "capsule", "radius": 0.05, "half_height": 0.1}}}],
    "joints": [{"type": "hinge", "bodies": ["door", null], "anchor": [0, 1, 0],
                "axis": [0, 1, 0], "limits": [-1, 1]}]})");
  const Result r = run_elan({"run", path, "--steps", "5", "--threads", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["bodies"], 5);
  EXPECT_EQ(j["joints"], 5);
}

TEST(Cli, OverridesReachTheSummary) {
  const Result r =
      run_elan({"run", small_scene(), "--steps", "2", "--threads", "2", "--timestep", "0.005",
                "--substeps", "3", "--iterations", "2", "--broadphase=all-pairs"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["threads"], 2);
  EXPECT_EQ(j["broadphase"], "all-pairs");
  EXPECT_EQ(j["substeps"], 3);
  EXPECT_EQ(j["iterations"], 2);
  EXPECT_DOUBLE_EQ(j["timestep"].get<double>(), double(float(0.005)));
}

TEST(Cli, ZeroStepsLoadsOnly) {
  const Result r = run_elan({"run", small_scene(), "--steps", "0"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["steps"], 0);
  EXPECT_EQ(j["bodies"], 4);
  EXPECT_EQ(j["awake"], 3);
  // Initial kinetic energy: b moves at 1 m/s, m = 1000 * 4/3 pi 0.5^3.
  const double mass_b = 1000.0 * 4.0 / 3.0 * M_PI * 0.125;
  EXPECT_GT(j["kinetic_energy"].get<double>(), 0.5 * mass_b * 0.999);
}

TEST(Cli, StateHashIndependentOfThreadsAndBroadphase) {
  const std::string scene = small_scene();
  const Json one = Json::parse(run_elan({"run", scene, "--steps", "30", "--threads", "1"}).out);
  const Json two = Json::parse(
      run_elan({"run", scene, "--steps", "30", "--threads", "2", "--broadphase", "all-pairs"}).out);
  EXPECT_EQ(one["state_hash"], two["state_hash"]);
  const Json tree = Json::parse(
      run_elan({"run", scene, "--steps", "30", "--threads", "2", "--broadphase", "tree"}).out);
  EXPECT_EQ(one["state_hash"], tree["state_hash"]);
  EXPECT_EQ(tree["broadphase"], "tree");
}

TEST(Cli, TrajectoryHasHeaderAndOneRowPerMovingBodyPerSample) {
  const std::string csv = temp_path("t.csv");
  const Result r = run_elan({"run", small_scene(), "--steps", "5", "--every", "2", "--trajectory",
                             csv, "--threads", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream in(read(csv));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz");
  // Samples at steps 0, 2, 4 and the last (5); three non-static bodies (indices 1..3).
  std::vector<std::string> keys;
  while (std::getline(in, line)) {
    std::size_t commas = 0;
    for (char c : line) commas += c == ',';
    EXPECT_EQ(commas, 15u) << line;
    keys.push_back(line.substr(0, line.find(',', line.find(',') + 1) + 2));
  }
  const std::vector<std::string> expected = {"0,0,1", "0,0,2", "0,0,3"};
  ASSERT_EQ(keys.size(), 12u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(keys[i], expected[i]);
  EXPECT_EQ(keys[3].substr(0, 2), "2,");
  EXPECT_EQ(keys[6].substr(0, 2), "4,");
  EXPECT_EQ(keys[9].substr(0, 2), "5,");
  std::remove(csv.c_str());
}

TEST(Cli, TrajectoryRowsReadBackToTheSameValues) {
  const std::string csv = temp_path("t.csv");
  ASSERT_EQ(run_elan({"run", small_scene(), "--steps", "1", "--trajectory", csv}).status, 0);
  std::istringstream in(read(csv));
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  // Step 0 of body 1: the scene's position [0, 0.6, 0] as a float prints as 0.600000024.
  EXPECT_EQ(line.substr(0, line.find(",1,", 0) + 3), "0,0,1,");
  EXPECT_NE(line.find(sizeof(float) == 4 ? ",0.600000024," : ",0.59999999999999998,"),
            std::string::npos)
      << line;
  std::remove(csv.c_str());
}

// FNV-1a 64 as the recording format specifies it, to forge a valid file with a wrong hash.
uint64_t fnv1a(const std::string& s, std::size_t n) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t i = 0; i < n; ++i) {
    h ^= uint8_t(s[i]);
    h *= 0x100000001b3ull;
  }
  return h;
}

class Recording : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = temp_path("r.rec");
    const Result r =
        run_elan({"run", small_scene(), "--steps", "3", "--threads", "1", "--record", path_});
    ASSERT_EQ(r.status, 0) << r.err;
    summary_ = Json::parse(r.out);
    bytes_ = read(path_);
    ASSERT_GT(bytes_.size(), 100u);
  }
  void TearDown() override { std::remove(path_.c_str()); }
  std::string path_;
  std::string bytes_;
  Json summary_;
};

TEST_F(Recording, ReplayMatchesWithAnyThreadsAndBroadphase) {
  for (const std::vector<std::string>& extra : std::vector<std::vector<std::string>>{
           {}, {"--threads", "1"}, {"--threads", "2", "--broadphase", "all-pairs"}}) {
    std::vector<std::string> args = {"replay", path_};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = run_elan(args);
    EXPECT_EQ(r.status, 0) << r.err;
    const Json j = Json::parse(r.out);
    EXPECT_EQ(j["match"], true);
    EXPECT_EQ(j["steps"], 3);
    EXPECT_EQ(j["state_hash"], summary_["state_hash"]);
  }
}

TEST_F(Recording, ReplayReportsTheFirstDifferingStep) {
  // The last hash (step 3) sits just before the 8-byte checksum; change it and re-seal.
  std::string forged = bytes_;
  forged[forged.size() - 16] ^= 1;
  const uint64_t sum = fnv1a(forged, forged.size() - 8);
  for (int i = 0; i < 8; ++i) forged[forged.size() - 8 + i] = char(uint8_t(sum >> (8 * i)));
  write(path_, forged);
  const Result r = run_elan({"replay", path_});
  EXPECT_EQ(r.status, 1) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["match"], false);
  EXPECT_EQ(j["first_mismatch_step"], 3);
}

TEST_F(Recording, CorruptByteIsRefused) {
  std::string corrupt = bytes_;
  corrupt[corrupt.size() / 2] ^= 0x20;
  write(path_, corrupt);
  const Result r = run_elan({"replay", path_});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("corrupt"), std::string::npos) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u);
}

// Every length short of the whole file, through the decoder the binary uses: each names the file.
TEST_F(Recording, EveryTruncationIsRefusedByTheDecoder) {
  const std::string name = "cut.rec";
  for (std::size_t n = 0; n < bytes_.size(); ++n) {
    try {
      elan::cli::decode_recording(bytes_.substr(0, n), name);
      ADD_FAILURE() << "length " << n << " was accepted";
    } catch (const elan::cli::RecordingError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(name + ": ", 0), 0u)
          << "length " << n << ": " << e.what();
    }
  }
  EXPECT_NO_THROW(elan::cli::decode_recording(bytes_, name));
}

// And through the binary, at the lengths that end inside each kind of field: the magic, the
// header's numbers, the scene text, the hashes and the checksum.
TEST_F(Recording, TruncationsExitTwoNamingTheFile) {
  const std::size_t size = bytes_.size();
  for (std::size_t n : {std::size_t(0), std::size_t(5), std::size_t(8), std::size_t(13),
                        std::size_t(40), size / 2, size - 12, size - 8, size - 1}) {
    write(path_, bytes_.substr(0, n));
    const Result r = run_elan({"replay", path_});
    EXPECT_EQ(r.status, 2) << "length " << n << ": " << r.err;
    EXPECT_NE(r.err.find(path_), std::string::npos) << "length " << n << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
}

TEST_F(Recording, SceneFileIsNotARecording) {
  const Result r = run_elan({"replay", small_scene()});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("not an elan recording"), std::string::npos) << r.err;
}

// --- Regression tests for the reproducers of issue 42 (tests/cli/reproducers/) ---

std::string reproducer(const std::string& name) {
  return std::string(ELAN_REPRODUCERS) + "/" + name;
}

// Exit 2 with exactly one line on stderr that names `file` and says `what`.
void expect_one_line_refusal(const Result& r, const std::string& file, const std::string& what) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << "expected '" << what << "' in " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

// hang_infinite_input_dev_zero.txt: these read without end (1.1 GB after 15 s) before the fix.
TEST(Cli, EndlessInputIsRefusedAtOnce) {
  for (const char* device : {"/dev/zero", "/dev/urandom"}) {
    expect_one_line_refusal(run_elan({"run", device}, 10), device,
                            "is a character device, not a scene file");
    expect_one_line_refusal(run_elan({"diverge", device}, 10), device,
                            "not a scene or recording file");
    expect_one_line_refusal(run_elan({"replay", device}, 10), device,
                            "is a character device, not a recording file");
  }
}

// A FIFO without a writer would block open(2) and read(2): refused without waiting.
TEST(Cli, FifoIsRefusedWithoutBlocking) {
  const std::string fifo = temp_path("fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  expect_one_line_refusal(run_elan({"run", fifo}, 10), fifo, "is a FIFO, not a scene file");
  expect_one_line_refusal(run_elan({"replay", fifo}, 10), fifo, "is a FIFO, not a recording file");
  std::remove(fifo.c_str());
}

// A scene file over the cap (a sparse file: no disk used) is refused before it is read.
TEST(Cli, SceneFileOverTheSizeCapIsRefused) {
  const std::string big = temp_path("big.json");
  write(big, "{}");
  ASSERT_EQ(truncate(big.c_str(), off_t(257) << 20), 0);
  expect_one_line_refusal(run_elan({"run", big}, 10), big, "file too large for a scene");
  std::remove(big.c_str());
}

// A recording's magic is checked on its first 8 bytes, before the rest is read.
TEST(Cli, RecordingMagicIsCheckedFirst) {
  const std::string scene = small_scene();
  expect_one_line_refusal(run_elan({"replay", scene}, 10), scene, "not an elan recording");
}

// dir_as_scene_message.txt: `elan run /tmp` said "empty file".
TEST(Cli, DirectoryAsSceneIsNamedADirectory) {
  const std::string dir = ::testing::TempDir();
  const Result r = run_elan({"run", dir}, 10);
  expect_one_line_refusal(r, dir, "is a directory, not a scene file");
  EXPECT_EQ(r.err.find("empty file"), std::string::npos) << r.err;
  expect_one_line_refusal(run_elan({"replay", dir}, 10), dir,
                          "is a directory, not a recording file");
}

// name_with_newline_breaks_one_line.json, name_with_terminal_escape.json: names were printed
// raw. Any user string (a name, a key, a generator type, a command-line word) is escaped.
TEST(Cli, ControlCharactersInMessagesAreEscaped) {
  const std::string newline = reproducer("name_with_newline_breaks_one_line.json");
  Result r = run_elan({"run", newline});
  expect_one_line_refusal(r, newline, R"(body 0 ("a\nb"): shape.radius: must be positive)");

  const std::string escape = reproducer("name_with_terminal_escape.json");
  r = run_elan({"run", escape});
  expect_one_line_refusal(r, escape, R"(body 0 ("\u001b[2J\u001b[31mOK"))");
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;

  // A NUL, a C1 control (U+009B, CSI) and a DEL in a name; a newline in an unknown key and in a
  // generator type.
  const std::string scene = temp_path("names.json");
  write(scene,
        R"({"bodies":[{"name":"x\u0000y\u009bz\u007f","shape":{"type":"sphere","radius":-1}}]})");
  r = run_elan({"run", scene});
  expect_one_line_refusal(r, scene, R"(body 0 ("x\u0000y\u009bz\u007f"))");
  write(scene, R"({"bodies":[{"shape":{"type":"sphere","radius":1},"na\nme":1}]})");
  expect_one_line_refusal(run_elan({"run", scene}), scene, R"(na\nme: unknown key)");
  write(scene, R"({"generators":[{"type":"gr\r\nid"}]})");
  expect_one_line_refusal(run_elan({"run", scene}), scene, R"(generator 0 (gr\r\nid))");
  std::remove(scene.c_str());

  // A command-line word and a file name.
  r = run_elan({"run", small_scene(), "--broadphase", "a\nb\x1b[2J"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find(R"(got 'a\nb\u001b[2J')"), std::string::npos) << r.err;
  r = run_elan({"run", "/nonexistent/a\nb.json"});
  expect_one_line_refusal(r, R"(/nonexistent/a\nb.json)", "cannot open");
}

// cli_substeps_range_mismatch.txt: --substeps 65 passed the command line and then blamed the
// scene file; 10001 said "between 1 and 10000". One range, the library's, naming the flag.
TEST(Cli, SolverCountsTakeTheLibraryRangeNamingTheFlag) {
  const std::string scene = reproducer("ok_sphere.json");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--substeps", "65"}, "elan: --substeps: must be in 1..64, got 65"},
      {{"--substeps", "10001"}, "elan: --substeps: must be in 1..64, got 10001"},
      {{"--substeps", "0"}, "elan: --substeps: must be in 1..64, got 0"},
      {{"--iterations", "65"}, "elan: --iterations: must be in 1..64, got 65"},
      {{"--threads", "1025"}, "elan: --threads: must be in 1..1024, got 1025"},
  };
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> args = {"run", scene, "--steps", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = run_elan(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err.rfind(message, 0), 0u) << "expected '" << message << "' in " << r.err;
    EXPECT_EQ(r.err.find("ok_sphere.json"), std::string::npos) << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  }
  for (const char* side : {"--substeps 65", "--iterations 65"}) {
    const Result r = run_elan({"diverge", scene, "--steps", "1", "--b", side});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("must be in 1..64, got 65"), std::string::npos) << r.err;
  }
  EXPECT_EQ(
      run_elan({"run", scene, "--steps", "1", "--substeps", "64", "--iterations", "64"}).status, 0);
  // A scene file's own substeps take the same range, at load.
  const std::string file = temp_path("substeps.json");
  write(file, R"({"substeps":65,"bodies":[]})");
  expect_one_line_refusal(run_elan({"run", file}), file, "substeps: must be at most 64, got 65");
  std::remove(file.c_str());
}

// `--threads 4` on a 2-core machine ran 2 workers and reported 4: the summary reports the
// workers that run (never more than the default, all cores), with a warning when fewer than asked.
TEST(Cli, ThreadsReportedAreTheWorkersThatRun) {
  const std::string scene = small_scene();
  const Result all = run_elan({"run", scene, "--steps", "1"});
  ASSERT_EQ(all.status, 0) << all.err;
  const int cores = Json::parse(all.out)["threads"].get<int>();
  ASSERT_GE(cores, 1);
  const Result many = run_elan({"run", scene, "--steps", "1", "--threads", "1024"});
  ASSERT_EQ(many.status, 0) << many.err;
  EXPECT_EQ(Json::parse(many.out)["threads"], cores);
  if (cores < 1024) {
    EXPECT_NE(many.err.find("--threads 1024: at most " + std::to_string(cores)), std::string::npos)
        << many.err;
  }
  const Result one = run_elan({"run", scene, "--steps", "1", "--threads", "1"});
  EXPECT_EQ(Json::parse(one.out)["threads"], 1);
  EXPECT_TRUE(one.err.empty()) << one.err;
  EXPECT_EQ(Json::parse(one.out)["state_hash"], Json::parse(many.out)["state_hash"]);
}

// A scene path that is not valid UTF-8 (a file name may be any bytes) made nlohmann's dump throw
// after the whole run: the summary is printed, the bad byte replaced by U+FFFD. (The scene
// reader refuses such bytes inside the file.)
TEST(Cli, InvalidUtf8InThePathStillPrintsTheSummary) {
  const std::string scene = temp_path("bad\xff.json");
  write(scene, R"({"bodies":[{"shape":{"type":"sphere","radius":1}}]})");
  const Result r = run_elan({"run", scene, "--steps", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(Json::parse(r.out)["scene"].get<std::string>().find("bad\xef\xbf\xbd.json"),
            std::string::npos);
  const Result d = run_elan({"diverge", scene, "--steps", "1", "--b", "--perturb 0:0"});
  EXPECT_EQ(d.status, 1) << d.err;
  EXPECT_EQ(Json::parse(d.out)["diverged"], true);
  std::remove(scene.c_str());
}

}  // namespace
