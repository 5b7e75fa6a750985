// SPDX-License-Identifier: MIT
// The program recorder (elan/recorder.hpp): a program that changes its world between steps,
// recorded, replays bit for bit at any thread count and broadphase; a change of a few ulps to one
// recorded argument is found at the step after it, in the body it pushed; a replay stopped at a
// step and saved continues bit for bit; every mutating World method is recorded.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "determinism/recorded_program.hpp"
#include "elan/recorder.hpp"
#include "elan/snapshot.hpp"

namespace elan {
namespace {

Recording decode(const std::vector<uint8_t>& bytes) {
  return decode_recording(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), "test.rec");
}

std::vector<uint8_t> encode(const Recording& r) {
  const std::string s = encode_recording(r);
  return std::vector<uint8_t>(s.begin(), s.end());
}

const test::RecordedProgram& program() {
  static const test::RecordedProgram p = test::record_program(2);
  return p;
}

TEST(ProgramRecording, RecordsEveryStepAndItsHash) {
  const Recording r = decode(program().recording);
  EXPECT_EQ(r.version, kRecordingVersion);
  EXPECT_EQ(r.promise, kDeterminismPromise);
  EXPECT_EQ(r.real_bytes, sizeof(Real));
  EXPECT_TRUE(r.is_program());
  EXPECT_EQ(r.steps, test::kProgramSteps);
  ASSERT_EQ(r.hashes.size(), test::kProgramSteps + 1);
  EXPECT_EQ(r.hashes.back(), program().final_hash);
  EXPECT_EQ(r.keyframes.size(), test::kProgramSteps / 10 + 1);
  std::set<std::string_view> seen;
  uint64_t steps = 0;
  for (const RecordedCall& c : list_calls(r)) {
    seen.insert(recorded_call_name(c.op));
    steps += recorded_call_name(c.op) == "step";
  }
  EXPECT_EQ(steps, test::kProgramSteps);
  for (const char* name : {"create_shape",
                           "create_body",
                           "destroy_body",
                           "create_joint",
                           "destroy_joint",
                           "apply_force",
                           "apply_force_at",
                           "apply_torque",
                           "apply_impulse",
                           "apply_linear_impulse",
                           "apply_angular_impulse",
                           "move_kinematic",
                           "set_joint_motor",
                           "set_friction",
                           "set_restitution",
                           "set_gravity",
                           "set_linear_velocities",
                           "set_substeps",
                           "restore_rollback",
                           "sleep",
                           "wake",
                           "set_mass",
                           "set_motion_type",
                           "set_collision_filter",
                           "set_gravity_scale",
                           "set_transform",
                           "set_damping",
                           "set_sleep_enabled"}) {
    EXPECT_TRUE(seen.count(name)) << name;
  }
}

TEST(ProgramRecording, ReplaysBitForBitAtOneAndTwoThreads) {
  for (int threads : {1, 2}) {
    for (BroadphaseType bp :
         {BroadphaseType::SweepAndPrune, BroadphaseType::AllPairs, BroadphaseType::Tree}) {
      ReplayOptions o;
      o.threads = threads;
      o.broadphase = bp;
      const ReplayResult r = replay_recording(program().recording, o);
      EXPECT_TRUE(r.match) << threads << " threads, broadphase " << int(bp) << ": step "
                           << r.mismatch_step << " " << r.error;
      EXPECT_EQ(r.steps, test::kProgramSteps);
    }
  }
  // Recorded at one thread, the same bits as at two.
  EXPECT_EQ(test::record_program(1).final_hash, program().final_hash);
}

// The impulse of step kPushStep moved up by kPushUlps ulps in its first component, through the
// codec (fewer can round away in v + J / m: recorded_program.hpp):
// the hashes agree up to kPushStep (the call comes after that step's hash) and part at the next
// step, where the pushed body is the first that differs.
TEST(ProgramRecording, FourUlpsInOneCallAreFoundAtTheRightStepAndBody) {
  Recording edited = decode(program().recording);
  bool found = false;
  for (const RecordedCall& c : list_calls(edited)) {
    if (recorded_call_name(c.op) != "apply_impulse") continue;
    ASSERT_EQ(c.step, test::kPushStep);
    // Arguments: body (slot, generation: 8 bytes), impulse (3 Real), point (3 Real).
    uint8_t* x = edited.calls.data() + c.offset + 8;
    Real v;
    std::memcpy(&v, x, sizeof v);
    v = test::nudged_up(v);
    std::memcpy(x, &v, sizeof v);
    found = true;
  }
  ASSERT_TRUE(found);
  const ReplayResult r = replay_recording(encode(edited));
  EXPECT_FALSE(r.match);
  EXPECT_EQ(r.mismatch_step, test::kPushStep + 1);

  // The first differing body: both recordings replayed side by side to that step.
  const Recording original = decode(program().recording);
  Replayer a(original, recording_start_world(original, 1, BroadphaseType::SweepAndPrune));
  Replayer b(edited, recording_start_world(edited, 1, BroadphaseType::SweepAndPrune));
  while (a.step() < test::kPushStep + 1) {
    a.advance();
    b.advance();
    if (a.step() <= test::kPushStep) {
      EXPECT_FALSE(compare_worlds(a.world(), b.world()).found) << a.step();
    }
  }
  const Divergence d = compare_worlds(a.world(), b.world());
  ASSERT_TRUE(d.found);
  // Within its step the push reaches the bodies the pushed one is solved with (a direct system
  // solves a connected stack at once), and the finder names the lowest dense index that differs:
  // the pushed body or one before it, and the pushed body differs too.
  const World& wa = a.world();
  const World& wb = b.world();
  const std::size_t k = program().pushed_body;
  EXPECT_TRUE(wa.linear_velocity(wa.body_at(k)) != wb.linear_velocity(wb.body_at(k)) ||
              wa.angular_velocity(wa.body_at(k)) != wb.angular_velocity(wb.body_at(k)));
  EXPECT_LE(d.body, program().pushed_body);
}

TEST(ProgramRecording, StoppedAndSavedReplayContinuesBitForBit) {
  const Recording r = decode(program().recording);
  for (uint64_t until : {uint64_t(0), uint64_t(37), uint64_t(64), test::kProgramSteps}) {
    ReplayOptions o;
    o.until = until;
    const ReplayResult stopped = replay_recording(program().recording, o);
    ASSERT_TRUE(stopped.match);
    ASSERT_EQ(stopped.steps, until);
    Replayer rest(r, load_snapshot(stopped.snapshot), until);
    EXPECT_EQ(rest.actual_hash(), r.hashes[until]);
    while (rest.step() < r.steps) ASSERT_TRUE(rest.advance()) << until << ": " << rest.step();
    EXPECT_EQ(rest.actual_hash(), program().final_hash);
  }
}

TEST(ProgramRecording, ReplayStepPlaysAWorldItDoesNotOwn) {
  const Recording r = decode(program().recording);
  World w = recording_start_world(r, 1, BroadphaseType::Tree);
  for (uint64_t s = 0; s < r.steps; ++s) {
    replay_step(w, r, s);
    ASSERT_EQ(w.state_hash(), r.hashes[s + 1]) << s;
  }
}

TEST(ProgramRecording, ThrowingCallsAreNotRecordedAndNestedCallsOnce) {
  World w;
  ShapeDef sphere;
  BodyDef body;
  body.shape = w.create_shape(sphere);
  const BodyId b = w.create_body(body);
  start_recording(w);
  EXPECT_THROW(w.set_friction(b, -1), Error);
  w.set_transform(b, Transform{Vec3(1, 2, 3), Quat::Identity()});
  World* worlds[] = {&w};
  step_all(worlds, test::kProgramDt, nullptr);
  const Recording r = decode(stop_recording(w));
  EXPECT_FALSE(is_recording(w));
  const std::vector<RecordedCall> calls = list_calls(r);
  ASSERT_EQ(calls.size(), 2u);
  EXPECT_EQ(recorded_call_name(calls[0].op), "set_transform");
  EXPECT_EQ(recorded_call_name(calls[1].op), "step");
  EXPECT_EQ(r.steps, 1u);
  EXPECT_TRUE(replay_recording(encode(r)).match);
}

TEST(ProgramRecording, OtherPromisesAreRefused) {
  Recording r = decode(program().recording);
  r.promise = "x86-64 double, cross-build";
  try {
    check_recording_build(r, "other.rec");
    ADD_FAILURE() << "accepted";
  } catch (const RecordingError& e) {
    EXPECT_NE(std::string(e.what()).find("other.rec"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("x86-64 double, cross-build"), std::string::npos);
  }
  EXPECT_THROW(replay_recording(encode(r)), RecordingError);
  r = decode(program().recording);
  r.real_bytes = sizeof(Real) == 4 ? 8 : 4;
  EXPECT_THROW(check_recording_build(r, "other.rec"), RecordingError);
}

// Every non-const World method changes state, so each is recorded, or is on this list with the
// reason it is not: a new mutator added to world.hpp without a recorder entry fails here.
TEST(ProgramRecording, EveryMutatorOfTheWorldIsRecorded) {
  const std::set<std::string> not_recorded = {
      "reserve",          // capacity only: no result depends on it
      "set_broadphase",   // results are the same for every broadphase
      "set_threads",      // and every thread count
      "set_pair_filter",  // the caller's code, which a recording cannot hold (docs/replay.md)
  };
  std::ifstream file(ELAN_SOURCE_DIR "/core/include/elan/world.hpp");
  std::stringstream text;
  text << file.rdbuf();
  std::string s = std::regex_replace(text.str(), std::regex("//[^\n]*"), "");
  const std::size_t begin = s.find("class World {");
  const std::size_t end = s.find("\n};", begin);
  ASSERT_NE(begin, std::string::npos);
  s = s.substr(begin, end - begin);
  std::set<std::string> recorded;
  for (std::string_view n : recorded_call_names()) {
    recorded.insert(std::string(n.substr(0, n.find('('))));
  }
  std::size_t mutators = 0;
  std::stringstream decls(s);
  std::string decl;
  const std::regex name_re(R"(([A-Za-z_~][A-Za-z_0-9]*)\s*\()");
  while (std::getline(decls, decl, ';')) {
    std::smatch m;
    if (!std::regex_search(decl, m, name_re)) continue;
    const std::string name = m[1];
    if (name == "World" || name == "~World" || name.rfind("operator", 0) == 0) continue;
    const std::string after = decl.substr(decl.rfind(')') + 1);
    if (after.find("const") != std::string::npos) continue;
    ++mutators;
    EXPECT_TRUE(recorded.count(name) || not_recorded.count(name))
        << "World::" << name << " changes the world but is not recorded (core/world/recorder.cpp)";
  }
  EXPECT_GT(mutators, 40u);  // the parse found the methods
}

}  // namespace
}  // namespace elan
