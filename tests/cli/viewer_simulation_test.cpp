// SPDX-License-Identifier: MIT
// The viewer's simulation without a window (tools/viewer/simulation.hpp, live_settings.hpp,
// timeline.hpp): the settings the panel changes live, applied as the panel applies them, against
// closed forms and against `elan run` with the same settings; and the timeline playing a program
// recording, seeking back and forth, against the recorded hashes. Needs no display.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "determinism/recorded_program.hpp"
#include "elan/recorder.hpp"
#include "elan/scene.hpp"
#include "tools/viewer/simulation.hpp"
#include "tools/viewer/timeline.hpp"

namespace elan::test {
namespace {

using Json = nlohmann::json;
using viewer::LiveSettings;
using viewer::Simulation;

std::string hex(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, h);
  return buf;
}

// A simulation of the scene `text`, as `elan view` makes one (threads as given).
Simulation simulation(const std::string& text, int threads) {
  viewer::Source source;
  source.name = "test scene";
  source.scene = parse_scene(text, source.name);
  source.def = source.scene.world;
  source.def.threads = threads;
  source.timestep = source.scene.timestep;
  World world(source.def);
  load_into(source.scene, world, source.name);
  return Simulation(std::move(source), std::move(world));
}

// `elan run` of the scene file `path`: its JSON summary.
Json run(const std::string& path, const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"run", path};
  args.insert(args.end(), extra.begin(), extra.end());
  const Result r = run_elan(args, 120);
  EXPECT_EQ(r.status, 0) << r.err;
  return r.status == 0 ? Json::parse(r.out) : Json();
}

// A ball in free fall, no ground: the closed forms of the solver's substepping (symplectic
// Euler, h = dt / substeps): after S substeps, v = v0 + g S h and
// y = y0 + v0 S h + g h^2 S (S + 1) / 2.
TEST(ViewerLiveSettings, NewGravityGivesTheClosedFormMotion) {
  Simulation sim = simulation(R"({"timestep": 0.0125, "bodies": [
    {"shape": {"type": "sphere", "radius": 0.5}, "position": [0, 100, 0]}]})",
                              1);
  for (int n = 0; n < 10; ++n) sim.step();
  const BodyId ball = sim.world().body_at(0);
  LiveSettings s = sim.settings();
  EXPECT_EQ(s.gravity, Vec3(0, Real(-9.81), 0));
  EXPECT_EQ(s.substeps, 4);
  s.gravity = Vec3(2, Real(-3), Real(1.5));
  sim.apply(s);
  EXPECT_EQ(sim.world().settings().gravity, s.gravity);
  const Vec3 v0 = sim.world().linear_velocity(ball), p0 = sim.world().center_of_mass(ball);
  constexpr int kSteps = 40;
  for (int n = 0; n < kSteps; ++n) sim.step();
  const double h = 0.0125 / 4, S = 4.0 * kSteps;
  const Vec3 v = sim.world().linear_velocity(ball), p = sim.world().center_of_mass(ball);
  for (int k = 0; k < 3; ++k) {
    const double g = double(s.gravity[k]);
    // 160 float additions of g h to a velocity of a few m/s: rounding stays below 1e-4 m/s.
    EXPECT_NEAR(double(v[k]), double(v0[k]) + g * S * h, 1e-4) << k;
    // The position adds up as many rounded steps of at most 100 m: 160 ulps of 100 m ~ 1e-3 m.
    EXPECT_NEAR(double(p[k]), double(p0[k]) + double(v0[k]) * S * h + g * h * h * S * (S + 1) / 2,
                2e-3)
        << k;
  }
  // Reset keeps what was changed live.
  sim.reset();
  EXPECT_EQ(sim.world().settings().gravity, s.gravity);
  EXPECT_EQ(sim.step_count(), 0u);
  // A value the world refuses is an elan::Error naming it.
  s.substeps = 0;
  try {
    sim.apply(s);
    ADD_FAILURE() << "substeps 0 accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "substeps");
  }
}

class ViewerLiveSettingsRun : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = temp_path("live_settings.json");
    write(path_, kSmallScene);
  }
  void TearDown() override { std::remove(path_.c_str()); }
  std::string path_;
};

// Substeps, iterations and threads changed before the first step: the state `elan run` reaches
// with the same settings, bit for bit, whatever the viewer's thread count.
TEST_F(ViewerLiveSettingsRun, SubstepsIterationsAndThreadsGiveTheRunsBits) {
  const Json reference =
      run(path_, {"--steps", "90", "--substeps", "6", "--iterations", "3", "--threads", "2"});
  const Json plain = run(path_, {"--steps", "90"});
  ASSERT_NE(reference["state_hash"], plain["state_hash"]) << "the settings change the bits";
  for (int threads : {1, 2}) {
    Simulation sim = simulation(kSmallScene, 2);
    LiveSettings s = sim.settings();
    s.substeps = 6;
    s.iterations = 3;
    s.threads = threads;
    sim.apply(s);
    EXPECT_EQ(sim.world().settings().threads, threads);
    for (int n = 0; n < 90; ++n) sim.step();
    EXPECT_EQ(hex(sim.world().state_hash()), reference["state_hash"]) << threads << " threads";
  }
  // Threads changed every step never change a bit.
  Simulation sim = simulation(kSmallScene, 1);
  for (int n = 0; n < 90; ++n) {
    LiveSettings s = sim.settings();
    s.threads = 1 + n % 2;
    sim.apply(s);
    sim.step();
  }
  EXPECT_EQ(hex(sim.world().state_hash()), plain["state_hash"]);
}

// Sleeping off: the bits of the scene run with "allow_sleep": false, no body ever asleep; and
// switched off once bodies sleep, every body wakes at once.
TEST_F(ViewerLiveSettingsRun, SleepingOffIsTheScenesAllowSleepFalse) {
  constexpr int kSteps = 300;  // 3 s: the pile has come to rest and sleeps (0.5 s at rest)
  std::string off_text = kSmallScene;
  off_text.replace(off_text.find('{'), 1, R"({"allow_sleep": false,)");
  const std::string off_path = temp_path("live_settings_off.json");
  write(off_path, off_text);
  const Json reference = run(off_path, {"--steps", std::to_string(kSteps)});
  std::remove(off_path.c_str());

  const auto asleep = [](const World& w) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < w.body_count(); ++i) {
      const BodyId id = w.body_at(i);
      n += w.motion_type(id) == MotionType::Dynamic && !w.is_awake(id);
    }
    return n;
  };
  Simulation on = simulation(kSmallScene, 2);
  for (int n = 0; n < kSteps; ++n) on.step();
  ASSERT_GT(asleep(on.world()), 0u) << "with sleeping on, resting bodies sleep";
  LiveSettings s = on.settings();
  s.sleeping = false;
  on.apply(s);
  EXPECT_EQ(asleep(on.world()), 0u) << "sleeping off wakes every body";
  EXPECT_FALSE(on.world().sleep_enabled());

  Simulation off = simulation(kSmallScene, 2);
  s = off.settings();
  s.sleeping = false;
  off.apply(s);
  for (int n = 0; n < kSteps; ++n) {
    off.step();
    ASSERT_EQ(asleep(off.world()), 0u) << "step " << n;
  }
  EXPECT_EQ(hex(off.world().state_hash()), reference["state_hash"]);
}

// A program recording on the timeline: every state reached, stepping forward or seeking back
// and forth (keyframes restored, the recorded calls re-applied), has the recorded hash.
TEST(ViewerTimeline, PlaysAProgramRecordingWithSeeking) {
  const RecordedProgram program = record_program(2);
  const std::string bytes(program.recording.begin(), program.recording.end());
  viewer::Source source;
  source.name = "recorded program";
  source.recording = decode_recording(bytes, source.name);
  ASSERT_TRUE(source.recording->is_program());
  source.timestep = Real(source.recording->timestep);
  source.def.broadphase = BroadphaseType(source.recording->broadphase);
  World start = recording_start_world(*source.recording, 1, source.def.broadphase);
  Simulation sim(std::move(source), std::move(start));
  // The simulation owns the recording from here.
  const Recording& r = *sim.source().recording;
  viewer::Timeline timeline(r);
  ASSERT_EQ(timeline.length(), kProgramSteps);
  EXPECT_TRUE(timeline.matches(sim));
  for (uint64_t n = 0; n < kProgramSteps; ++n) {
    timeline.advance(sim);
    ASSERT_EQ(sim.step_count(), n + 1);
    ASSERT_TRUE(timeline.matches(sim)) << "step " << n + 1;
  }
  EXPECT_EQ(sim.world().state_hash(), program.final_hash);
  // Back and forth: between keyframes (every 10 steps), on one, to the start and the end.
  for (uint64_t step : {37u, 5u, 90u, 60u, 0u, 119u, 120u, 44u}) {
    timeline.seek(sim, step);
    ASSERT_EQ(sim.step_count(), step);
    EXPECT_EQ(sim.world().state_hash(), r.hashes[step]) << "step " << step;
  }
  EXPECT_FALSE(timeline.first_mismatch().has_value());
  EXPECT_TRUE(timeline.error().empty()) << timeline.error();
  // The bodies the program created and destroyed are drawn with their own shapes.
  for (std::size_t i = 0; i < sim.world().body_count(); ++i) {
    EXPECT_EQ(sim.body_shape(i).type,
              sim.world().shape_def(sim.world().shape(sim.world().body_at(i))).type);
  }
}

}  // namespace
}  // namespace elan::test
