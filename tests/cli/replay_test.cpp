// SPDX-License-Identifier: MIT
// `elan run --record` with keyframes, `elan replay` naming the first differing body and field,
// `elan diverge`, and refusal (exit 2, one clear line) of old, future, corrupt and truncated files.
#include <gtest/gtest.h>

#include "cli/cli_runner.hpp"
#include "determinism/recorded_program.hpp"
#include "elan/recorder.hpp"
#include "elan/snapshot.hpp"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <span>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Json = nlohmann::json;

using namespace elan::test;

// kSmallScene (cli_runner.hpp): body 2 is the sphere named "b".
const char* const kScene = kSmallScene;

uint64_t fnv1a(const std::string& s, std::size_t n) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t i = 0; i < n; ++i) {
    h ^= uint8_t(s[i]);
    h *= 0x100000001b3ull;
  }
  return h;
}

void put_u64(std::string& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(char(uint8_t(v >> (8 * i))));
}
void put_u32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(char(uint8_t(v >> (8 * i))));
}
void put_u32_at(std::string& s, std::size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) s[at + i] = char(uint8_t(v >> (8 * i)));
}
uint64_t get_u64(const std::string& s, std::size_t at) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= uint64_t(uint8_t(s[at + i])) << (8 * i);
  return v;
}

void reseal(std::string& bytes) {
  const uint64_t sum = fnv1a(bytes, bytes.size() - 8);
  for (int i = 0; i < 8; ++i) bytes[bytes.size() - 8 + i] = char(uint8_t(sum >> (8 * i)));
}

// A version-3 scene recording as version 2 wrote it: without the engine version and the promise
// (after the real size) and without the starting snapshot and the calls (after the scene text),
// both empty in a scene recording.
std::string to_version_2(const std::string& v3) {
  std::string v2 = v3.substr(0, 8);
  put_u32(v2, 2);
  std::size_t at = 12;
  v2 += v3.substr(at, 4);  // real size
  at += 4;
  for (int s = 0; s < 2; ++s) at += 8 + get_u64(v3, at);  // engine version, promise
  const std::size_t fixed = 8 + 8 + 4 + 4 + 4 + 4 + 8;    // steps .. keyframe_every
  v2 += v3.substr(at, fixed);
  at += fixed;
  for (int s = 0; s < 2; ++s) {  // scene name, scene text
    const uint64_t n = get_u64(v3, at);
    v2 += v3.substr(at, 8 + n);
    at += 8 + n;
  }
  for (int s = 0; s < 2; ++s) at += 8 + get_u64(v3, at);  // snapshot, calls
  v2 += v3.substr(at, v3.size() - 8 - at);
  put_u64(v2, 0);
  reseal(v2);
  return v2;
}

// Offset of the field after the promise in a version-3 recording (the steps).
std::size_t after_promise(const std::string& v3) {
  std::size_t at = 16;
  for (int s = 0; s < 2; ++s) at += 8 + get_u64(v3, at);
  return at;
}

class Replay : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = temp_path("scene.json");
    write(scene_, kScene);
    path_ = temp_path("r.rec");
    const Result r = run_elan({"run", scene_, "--steps", "12", "--threads", "2", "--record", path_,
                               "--keyframe-every", "5"});
    ASSERT_EQ(r.status, 0) << r.err;
    summary_ = Json::parse(r.out);
    bytes_ = read(path_);
  }
  void TearDown() override {
    std::remove(path_.c_str());
    std::remove(scene_.c_str());
  }
  Json replay(const std::vector<std::string>& extra, int expected_status) {
    std::vector<std::string> args = {"replay", path_};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = run_elan(args);
    EXPECT_EQ(r.status, expected_status) << r.err;
    return r.status == 0 || r.status == 1 ? Json::parse(r.out) : Json();
  }
  std::string scene_, path_, bytes_;
  Json summary_;
};

TEST_F(Replay, MatchesWithAnyThreadsAndBroadphase) {
  for (const std::vector<std::string>& extra :
       std::vector<std::vector<std::string>>{{"--threads", "1"},
                                             {"--threads", "2", "--broadphase", "all-pairs"},
                                             {"--threads", "2", "--broadphase", "tree"}}) {
    const Json j = replay(extra, 0);
    EXPECT_EQ(j["match"], true);
    EXPECT_EQ(j["keyframes"], 3);  // steps 0, 5, 10
    EXPECT_EQ(j["state_hash"], summary_["state_hash"]);
  }
}

TEST_F(Replay, PerturbationBetweenKeyframesIsFoundByResimulating) {
  const Json j = replay({"--threads", "1", "--perturb", "2:7"}, 1);
  EXPECT_EQ(j["first_mismatch_step"], 7);
  const Json& d = j["divergence"];
  EXPECT_EQ(d["keyframe"], 5);
  EXPECT_EQ(d["method"], "re-simulated from keyframe");
  EXPECT_EQ(d["body"], 2);
  EXPECT_EQ(d["name"], "b");
  EXPECT_EQ(d["field"], "px");
  EXPECT_GT(d["replayed"].get<double>(), d["recorded"].get<double>());
}

TEST_F(Replay, PerturbationAtAKeyframeIsFoundAgainstIt) {
  for (const char* at : {"3:10", "3:0"}) {
    const Json j = replay({"--perturb", at}, 1);
    const Json& d = j["divergence"];
    EXPECT_EQ(d["method"], "keyframe") << at;
    EXPECT_EQ(d["body"], 3) << at;
    EXPECT_TRUE(d["name"].is_null()) << at;
    EXPECT_EQ(d["field"], "px") << at;
  }
}

TEST_F(Replay, ForgedHashIsReportedWithoutABody) {
  // The recording's last hash changed and resealed: the keyframe before it re-simulates to the
  // true hash, so the recording itself is not reproducible and no body can be blamed.
  std::string forged = bytes_;
  forged[forged.size() - 16] ^= 1;
  reseal(forged);
  write(path_, forged);
  const Json j = replay({}, 1);
  EXPECT_EQ(j["first_mismatch_step"], 12);
  EXPECT_TRUE(j["divergence"]["body"].is_null());
  EXPECT_NE(j["divergence"]["reason"].get<std::string>().find("does not reproduce"),
            std::string::npos);
}

TEST_F(Replay, WithoutKeyframesTheStepIsStillReported) {
  ASSERT_EQ(
      run_elan({"run", scene_, "--steps", "6", "--record", path_, "--keyframe-every", "0"}).status,
      0);
  const Json j = replay({"--perturb", "1:4"}, 1);
  EXPECT_EQ(j["first_mismatch_step"], 4);
  EXPECT_TRUE(j["divergence"]["body"].is_null());
  EXPECT_NE(j["divergence"]["reason"].get<std::string>().find("no keyframes"), std::string::npos);
}

TEST_F(Replay, VersionTwoRecordingsAreStillRead) {
  write(path_, to_version_2(bytes_));
  const Json j = replay({"--threads", "2"}, 0);
  EXPECT_EQ(j["match"], true);
  EXPECT_EQ(j["keyframes"], 3);
  EXPECT_EQ(j["state_hash"], summary_["state_hash"]);
  const Json p = replay({"--perturb", "2:7"}, 1);
  EXPECT_EQ(p["first_mismatch_step"], 7);
  EXPECT_EQ(p["divergence"]["body"], 2);
}

TEST_F(Replay, VersionOneRecordingsAreStillRead) {
  // Version 1 is version 2 without the keyframe interval and the keyframes.
  const std::string v2 = to_version_2(bytes_);
  std::size_t at = 8;
  std::string v1 = v2.substr(0, at);
  put_u32(v1, 1);
  at += 4;
  const std::size_t fixed = 4 + 8 + 8 + 4 + 4 + 4 + 4;  // real size .. broadphase
  v1 += v2.substr(at, fixed);
  at += fixed + 8;               // skip keyframe_every
  for (int s = 0; s < 2; ++s) {  // scene name, scene text
    const uint64_t n = get_u64(v2, at);
    v1 += v2.substr(at, 8 + n);
    at += 8 + n;
  }
  const uint64_t keyframes = get_u64(v2, at);
  at += 8;
  for (uint64_t k = 0; k < keyframes; ++k) at += 16 + get_u64(v2, at + 8);
  v1 += v2.substr(at, v2.size() - 8 - at);
  put_u64(v1, 0);
  reseal(v1);
  write(path_, v1);
  const Json j = replay({}, 0);
  EXPECT_EQ(j["match"], true);
  EXPECT_EQ(j["keyframes"], 0);
  const Json p = replay({"--perturb", "2:3"}, 1);
  EXPECT_NE(p["divergence"]["reason"].get<std::string>().find("format version 1"),
            std::string::npos);
}

TEST_F(Replay, FutureVersionIsRefusedByName) {
  std::string future = bytes_;
  future[8] = 4;
  reseal(future);
  write(path_, future);
  const Result r = run_elan({"replay", path_});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(
      r.err.find(path_ + ": unsupported recording version 4 (this elan reads versions 1 to 3)"),
      std::string::npos)
      << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST_F(Replay, CorruptKeyframeUnderAValidChecksumIsRefused) {
  // Break the first keyframe's snapshot magic, then reseal the recording: the recording's
  // checksum passes, the keyframe's own check must not.
  const std::size_t magic = bytes_.find(
      "\x89"
      "ELANSNP");
  ASSERT_NE(magic, std::string::npos);
  std::string bad = bytes_;
  bad[magic + 5] = 'X';
  reseal(bad);
  write(path_, bad);
  const Result r = run_elan({"replay", path_, "--perturb", "2:1"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("keyframe at step 0"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(path_), std::string::npos) << r.err;
}

TEST_F(Replay, FlippedBytesAndTruncationsAreRefused) {
  // Every 37th byte (about 60 positions over every section) and every 61st length.
  for (std::size_t at = 0; at < bytes_.size(); at += 37) {
    std::string bad = bytes_;
    bad[at] ^= 0x04;
    write(path_, bad);
    const Result r = run_elan({"replay", path_});
    EXPECT_EQ(r.status, 2) << "byte " << at << ": " << r.err;
    EXPECT_NE(r.err.find(path_), std::string::npos) << "byte " << at << ": " << r.err;
  }
  for (std::size_t n = 0; n < bytes_.size(); n += 61) {
    write(path_, bytes_.substr(0, n));
    const Result r = run_elan({"replay", path_});
    EXPECT_EQ(r.status, 2) << "length " << n << ": " << r.err;
    EXPECT_TRUE(r.out.empty());
  }
}

TEST_F(Replay, BadPerturbationIsAUsageError) {
  for (const char* bad : {"2", "x:1", "9:1", "2:-1"}) {
    const Result r = run_elan({"replay", path_, "--perturb", bad});
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_NE(r.err.find("--perturb"), std::string::npos) << r.err;
  }
}

TEST_F(Replay, DivergeReportsNothingForThreadsAndBroadphase) {
  const Result r = run_elan({"diverge", scene_, "--steps", "20", "--a", "--threads 1", "--b",
                             "--threads 2 --broadphase all-pairs"});
  EXPECT_EQ(r.status, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["diverged"], false);
  EXPECT_EQ(j["b"]["broadphase"], "all-pairs");
}

TEST_F(Replay, DivergeFindsTheStepBodyAndField) {
  const Result r =
      run_elan({"diverge", scene_, "--steps", "20", "--a", "--threads 2", "--b", "--perturb 1:6"});
  EXPECT_EQ(r.status, 1) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["diverged"], true);
  EXPECT_EQ(j["step"], 6);
  EXPECT_EQ(j["body"], 1);
  EXPECT_EQ(j["name"], "a");
  EXPECT_EQ(j["field"], "px");
  const Result sub = run_elan({"diverge", scene_, "--steps", "20", "--b", "--substeps 2"});
  EXPECT_EQ(sub.status, 1);
  EXPECT_EQ(Json::parse(sub.out)["step"], 1);
}

TEST_F(Replay, DivergeRefusesBadSides) {
  const Result r = run_elan({"diverge", scene_, "--a", "--threads x"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--a"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
}

// --- Regression tests for the reproducers of issue 42 (tests/cli/reproducers/) ---

std::string reproducer(const std::string& name) {
  return std::string(ELAN_REPRODUCERS) + "/" + name;
}

std::size_t count_lines(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// diverge_same_perturb_false_divergence.txt: with the same perturbation on both sides, side a was
// compared after its nudge and before b's, and a divergence was reported at that step.
TEST_F(Replay, DivergeWithIdenticalOptionsNeverDiverges) {
  for (const char* perturb : {"--perturb 1:0", "--perturb 1:2", "--perturb 2:5", "--perturb 3:8"}) {
    const Result r =
        run_elan({"diverge", scene_, "--steps", "8", "--a", perturb, "--b", perturb}, 60);
    EXPECT_EQ(r.status, 0) << perturb << ": " << r.out << r.err;
    EXPECT_EQ(Json::parse(r.out)["diverged"], false) << perturb;
  }
  const Result tower = run_elan({"diverge", std::string(ELAN_SCENE_DIR) + "/tower20.json",
                                 "--steps", "5", "--a", "--perturb 1:2", "--b", "--perturb 1:2"},
                                60);
  EXPECT_EQ(tower.status, 0) << tower.out << tower.err;
  const Result sides =
      run_elan({"diverge", scene_, "--steps", "8", "--a", "--threads 1 --perturb 2:3", "--b",
                "--threads 2 --broadphase all-pairs --perturb 2:3"},
               60);
  EXPECT_EQ(sides.status, 0) << sides.out << sides.err;
}

TEST_F(Replay, DivergeWithDifferentPerturbationsStillDiverges) {
  // Another body at the same step: found at that step.
  Result r = run_elan(
      {"diverge", scene_, "--steps", "8", "--a", "--perturb 1:2", "--b", "--perturb 2:2"}, 60);
  EXPECT_EQ(r.status, 1) << r.err;
  Json j = Json::parse(r.out);
  EXPECT_EQ(j["step"], 2);
  EXPECT_EQ(j["body"], 1);
  EXPECT_EQ(j["field"], "px");
  // The same body at another step: found at the first of them.
  r = run_elan({"diverge", scene_, "--steps", "8", "--a", "--perturb 1:4", "--b", "--perturb 1:2"},
               60);
  EXPECT_EQ(r.status, 1) << r.err;
  j = Json::parse(r.out);
  EXPECT_EQ(j["step"], 2);
  EXPECT_EQ(j["body"], 1);
}

// Exit 2 and one line that names the recording (not the scene path it carries) as corrupt.
void expect_corrupt_recording(const Result& r, const std::string& file, const std::string& what) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind(file + ": corrupt recording: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << "expected '" << what << "' in " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

// replay_corrupt_embedded_scene.rec (valid checksum, scene text "[]") was reported as
// "seeds/h_stack.json: expected a JSON object ...".
TEST(ReplayCorrupt, EmbeddedSceneIsReportedByTheRecording) {
  const std::string file = reproducer("replay_corrupt_embedded_scene.rec");
  expect_corrupt_recording(run_elan({"replay", file}, 60), file,
                           "recorded scene \"seeds/h_stack.json\": expected a JSON object");
}

// replay_nul_scene_name_empty_message.rec (scene name "\0") printed an empty line.
TEST(ReplayCorrupt, NulInEmbeddedSceneNameGivesOneEscapedLine) {
  const std::string file = reproducer("replay_nul_scene_name_empty_message.rec");
  expect_corrupt_recording(run_elan({"replay", file}, 60), file,
                           R"(recorded scene "\u0000": expected a JSON object)");
}

// replay_recorded_substeps_100.rec blamed the scene; replay_recorded_threads_5000.rec was
// accepted, or failed with "elan: threads: must be in 0..1024" under --perturb.
TEST(ReplayCorrupt, RecordedSettingsOutOfRangeAreACorruptRecording) {
  const std::string substeps = reproducer("replay_recorded_substeps_100.rec");
  expect_corrupt_recording(run_elan({"replay", substeps}, 60), substeps,
                           "recorded substeps must be in 1..64, got 100");
  const std::string threads = reproducer("replay_recorded_threads_5000.rec");
  for (const std::vector<std::string>& extra :
       std::vector<std::vector<std::string>>{{}, {"--perturb", "1:4"}}) {
    std::vector<std::string> args = {"replay", threads};
    args.insert(args.end(), extra.begin(), extra.end());
    expect_corrupt_recording(run_elan(args, 60), threads,
                             "recorded threads must be in 0..1024, got 5000");
  }
}

// A recording whose settings a world refuses (iterations 65 under a valid checksum) or whose
// scene has a bad body names the recording too.
TEST_F(Replay, InvalidRecordedSettingsAndScenesNameTheRecording) {
  // iterations sits after the promise, steps, timestep and substeps.
  std::string bytes = bytes_;
  const std::size_t at = after_promise(bytes) + 8 + 8 + 4;
  put_u32_at(bytes, at, 65);
  reseal(bytes);
  write(path_, bytes);
  expect_corrupt_recording(run_elan({"replay", path_}, 60), path_,
                           "recorded iterations must be in 1..64, got 65");

  // A scene whose body is refused at load: radius -1, same length as the recorded "0.5".
  bytes = bytes_;
  const std::size_t radius = bytes.find("\"radius\": 0.5");
  ASSERT_NE(radius, std::string::npos);
  bytes.replace(radius, 13, "\"radius\": -1 ");
  reseal(bytes);
  write(path_, bytes);
  expect_corrupt_recording(run_elan({"replay", path_}, 60), path_, "shape.radius");
}

// A recording keeps the scene text only: the OBJ files a scene names go into it, so a replay
// needs none of them (they are deleted here before replaying) and gives the same hashes.
TEST(ReplayGeometry, ObjFilesAreRecordedWithTheScene) {
  const std::string ground = temp_path("ground.obj"), wedge = temp_path("wedge.obj");
  write(ground, "v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nf 1 4 3 2\n");
  write(wedge,
        "v -0.2 -0.15 -0.3\nv 0.2 -0.15 -0.3\nv 0 0.2 -0.3\nv -0.2 -0.15 0.3\nv 0.2 -0.15 0.3\n"
        "v 0 0.2 0.3\nf 1 3 2\nf 4 5 6\nf 1 2 5 4\nf 2 3 6 5\nf 3 1 4 6\n");
  const auto name = [](const std::string& path) { return path.substr(path.rfind('/') + 1); };
  const std::string scene = temp_path("scene.json"), rec = temp_path("r.rec");
  write(scene, R"({"bodies": [
      {"motion": "static", "shape": {"type": "mesh", "file": ")" +
                   name(ground) + R"("}},
      {"shape": {"type": "convex_hull", "file": ")" +
                   name(wedge) + R"("}, "position": [0, 0.5, 0]},
      {"shape": {"type": "compound", "children": [
        {"shape": {"type": "sphere", "radius": 0.2}},
        {"shape": {"type": "convex_hull", "file": ")" +
                   name(wedge) + R"("}, "position": [0, 0.4, 0]}]},
       "position": [1, 1, 0]}]})");
  const Result r = run_elan({"run", scene, "--steps", "30", "--record", rec});
  ASSERT_EQ(r.status, 0) << r.err;
  std::remove(ground.c_str());
  std::remove(wedge.c_str());
  std::remove(scene.c_str());
  const Result p = run_elan({"replay", rec, "--threads", "2"});
  EXPECT_EQ(p.status, 0) << p.err;
  const Json j = Json::parse(p.out.empty() ? "{}" : p.out);
  EXPECT_EQ(j["match"], true) << p.out;
  EXPECT_EQ(j["state_hash"], Json::parse(r.out)["state_hash"]);
  std::remove(rec.c_str());
}

}  // namespace

// A jointed scene (chains of ball and hinge joints over a pile) records and replays bit for bit
// with other threads and broadphase, its keyframes carrying the joints; a perturbed replay finds
// the body.
TEST(ReplayJoints, JointedSceneReplaysAndFindsAPerturbation) {
  const std::string path = temp_path("joints.rec");
  const Result r = run_elan({"run", std::string(ELAN_SCENE_DIR) + "/chains.json", "--steps", "40",
                             "--threads", "2", "--record", path, "--keyframe-every", "20"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Json summary = Json::parse(r.out);
  EXPECT_EQ(summary["joints"], 576);
  for (const std::vector<std::string>& extra : std::vector<std::vector<std::string>>{
           {"--threads", "1"}, {"--threads", "2", "--broadphase", "all-pairs"}}) {
    std::vector<std::string> args = {"replay", path};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result replayed = run_elan(args);
    ASSERT_EQ(replayed.status, 0) << replayed.err;
    const Json j = Json::parse(replayed.out);
    EXPECT_EQ(j["match"], true);
    EXPECT_EQ(j["state_hash"], summary["state_hash"]);
  }
  // Body 1100 is a chain link.
  const Result perturbed = run_elan({"replay", path, "--perturb", "1100:25"});
  EXPECT_EQ(perturbed.status, 1) << perturbed.err;
  const Json j = Json::parse(perturbed.out);
  EXPECT_EQ(j["first_mismatch_step"], 25);
  EXPECT_EQ(j["divergence"]["body"], 1100);
  std::remove(path.c_str());
}

// Program recordings (elan/recorder.hpp): made in this process by the program of
// determinism/recorded_program.hpp, replayed, searched and cut by the elan binary.
namespace program {

std::string to_string(const std::vector<uint8_t>& v) {
  return std::string(v.begin(), v.end());
}

const elan::test::RecordedProgram& recorded() {
  static const elan::test::RecordedProgram p = elan::test::record_program(2);
  return p;
}

std::string hex(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

class ProgramReplay : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = temp_path("program.rec");
    bytes_ = to_string(recorded().recording);
    write(path_, bytes_);
  }
  void TearDown() override { std::remove(path_.c_str()); }
  elan::Recording decoded() const { return elan::decode_recording(bytes_, path_); }
  void write_recording(const elan::Recording& r) { write(path_, elan::encode_recording(r)); }
  std::string path_, bytes_;
};

TEST_F(ProgramReplay, ReplaysBitForBitWithAnyThreadsAndBroadphase) {
  for (const std::vector<std::string>& extra :
       std::vector<std::vector<std::string>>{{"--threads", "1"},
                                             {"--threads", "2", "--broadphase", "tree"},
                                             {"--threads", "2", "--broadphase", "all-pairs"}}) {
    std::vector<std::string> args = {"replay", path_};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = run_elan(args);
    ASSERT_EQ(r.status, 0) << r.err << r.out;
    const Json j = Json::parse(r.out);
    EXPECT_EQ(j["kind"], "program");
    EXPECT_EQ(j["match"], true);
    EXPECT_EQ(j["steps"], elan::test::kProgramSteps);
    EXPECT_EQ(j["state_hash"], hex(recorded().final_hash));
  }
}

// kPushUlps ulps more on the first component of the impulse the program applies after step
// kPushStep (fewer can round away in v + J / m: recorded_program.hpp), edited through the codec:
// the replay parts at the next step, and the divergence finder (the keyframe at kPushStep replayed
// with the recorded calls) names the pushed body.
//
// The recorded state after that step is known only from a keyframe there: replaying from the
// keyframe before it re-applies the edited call too, which reproduces the replay and not the
// recorded hash (that case is reported without a body). So this recording keeps a keyframe at
// every step.
TEST_F(ProgramReplay, FourUlpsInOneCallAreFoundAtItsStepAndBody) {
  static const elan::test::RecordedProgram every_step = elan::test::record_program(2, 1);
  elan::Recording r = elan::decode_recording(to_string(every_step.recording), path_);
  for (const elan::RecordedCall& c : elan::list_calls(r)) {
    if (elan::recorded_call_name(c.op) != "apply_impulse") continue;
    uint8_t* x = r.calls.data() + c.offset + 8;  // after the body id
    elan::Real v;
    std::memcpy(&v, x, sizeof v);
    v = elan::test::nudged_up(v);
    std::memcpy(x, &v, sizeof v);
  }
  write_recording(r);
  const Result out = run_elan({"replay", path_, "--threads", "2"});
  ASSERT_EQ(out.status, 1) << out.err;
  const Json j = Json::parse(out.out);
  EXPECT_EQ(j["first_mismatch_step"], elan::test::kPushStep + 1);
  const Json& d = j["divergence"];
  EXPECT_EQ(d["keyframe"], elan::test::kPushStep + 1);
  EXPECT_EQ(d["method"], "keyframe");
  // The pushed body, or a lower-index one it touches, which the push reaches within its step
  // (the in-process test ProgramRecording.FourUlpsInOneCallAreFoundAtTheRightStepAndBody checks the
  // contact).
  EXPECT_LE(d["body"].get<std::size_t>(), every_step.pushed_body) << j.dump();
  // When the pushed body is named: the edited x component changes vx by an ulp; the
  // position moved by vx dt rounds to the same bits here, so vx is the first field that differs.
  if (d["body"] == every_step.pushed_body) {
    EXPECT_EQ(d["field"], "vx");
  }

  // With keyframes every 10 steps the step is found, and the reason why no body is named given.
  r = decoded();
  for (const elan::RecordedCall& c : elan::list_calls(r)) {
    if (elan::recorded_call_name(c.op) != "apply_impulse") continue;
    uint8_t* x = r.calls.data() + c.offset + 8;
    elan::Real v;
    std::memcpy(&v, x, sizeof v);
    v = elan::test::nudged_up(v);
    std::memcpy(x, &v, sizeof v);
  }
  write_recording(r);
  const Result sparse = run_elan({"replay", path_});
  ASSERT_EQ(sparse.status, 1) << sparse.err;
  const Json k = Json::parse(sparse.out);
  EXPECT_EQ(k["first_mismatch_step"], elan::test::kPushStep + 1);
  EXPECT_TRUE(k["divergence"]["body"].is_null());
  EXPECT_NE(k["divergence"]["reason"].get<std::string>().find("does not reproduce"),
            std::string::npos);
}

TEST_F(ProgramReplay, UntilSaveSnapshotContinuesBitForBit) {
  const std::string snap = temp_path("program_45.snap");
  const Result out = run_elan({"replay", path_, "--until", "45", "--save-snapshot", snap});
  ASSERT_EQ(out.status, 0) << out.err;
  const std::string bytes = read(snap);
  std::remove(snap.c_str());
  const elan::Recording r = decoded();
  elan::Replayer rest(
      r,
      elan::load_snapshot(std::span(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size())),
      45);
  EXPECT_EQ(rest.actual_hash(), r.hashes[45]);
  while (rest.step() < r.steps) ASSERT_TRUE(rest.advance()) << rest.step();
  EXPECT_EQ(rest.actual_hash(), recorded().final_hash);
}

TEST_F(ProgramReplay, SaveSceneSaysWhyNot) {
  const std::string scene = temp_path("program.json");
  const Result out = run_elan({"replay", path_, "--until", "10", "--save-scene", scene});
  EXPECT_EQ(out.status, 2);
  EXPECT_NE(out.err.find("cannot be written as a scene"), std::string::npos) << out.err;
  EXPECT_NE(out.err.find("use --save-snapshot"), std::string::npos) << out.err;
  EXPECT_EQ(elan::test::count_lines(out.err), 1u) << out.err;
}

TEST_F(ProgramReplay, RecordingsFromBuildsWithOtherPromisesAreRefused) {
  elan::Recording r = decoded();
  r.real_bytes = sizeof(elan::Real) == 4 ? 8 : 4;
  write_recording(r);
  Result out = run_elan({"replay", path_});
  EXPECT_EQ(out.status, 2);
  EXPECT_NE(out.err.find(path_ + ": recorded by a build with " + std::to_string(r.real_bytes * 8) +
                         "-bit Real"),
            std::string::npos)
      << out.err;
  EXPECT_TRUE(out.out.empty());

  r = decoded();
  r.promise = "x86-64 double, cross-build";
  write_recording(r);
  out = run_elan({"replay", path_});
  EXPECT_EQ(out.status, 2);
  EXPECT_NE(out.err.find(path_ + ": recorded by a build that promises \"x86-64 double"),
            std::string::npos)
      << out.err;

  std::string future = bytes_;
  future[8] = 4;
  reseal(future);
  write(path_, future);
  out = run_elan({"replay", path_});
  EXPECT_EQ(out.status, 2);
  EXPECT_NE(out.err.find(path_ + ": unsupported recording version 4"), std::string::npos)
      << out.err;
}

TEST_F(ProgramReplay, DivergeComparesTwoReplays) {
  Result out =
      run_elan({"diverge", path_, "--a", "--threads 1", "--b", "--threads 2 --broadphase tree"});
  ASSERT_EQ(out.status, 0) << out.err;
  EXPECT_EQ(Json::parse(out.out)["diverged"], false);
  out = run_elan({"diverge", path_, "--a", "--threads 1", "--b", "--threads 2 --perturb 3:50"});
  ASSERT_EQ(out.status, 1) << out.err;
  const Json j = Json::parse(out.out);
  EXPECT_EQ(j["step"], 50);
  EXPECT_EQ(j["body"], 3);
  EXPECT_EQ(j["field"], "px");
}

}  // namespace program
