// The elan command: `elan run` simulates a scene file and prints a JSON summary, `elan replay`
// re-simulates a recording and compares every step's state hash. Every error exits with status 2.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "elan/elan.hpp"
#include "tools/options.hpp"
#include "tools/recording.hpp"
#include "tools/trajectory.hpp"

namespace elan::cli {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

constexpr double kProgressSeconds = 2.0;

std::string hex(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, h);
  return buf;
}

Json vec(const Vec3& v) {
  return Json::array({double(v.x()), double(v.y()), double(v.z())});
}

std::string read_file(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open " + what + ": " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw std::runtime_error(path + ": cannot read " + what);
  return text.str();
}

// Builds the world; errors the library reports for settings name the scene file.
World make_world(const WorldDef& def, const std::string& scene_name) {
  try {
    return World(def);
  } catch (const Error& e) {
    throw SceneError(scene_name + ": " + e.what());
  }
}

// Reports each StepStatus flag once, on stderr.
void warn_status(uint32_t fresh, uint64_t step) {
  if (fresh & kStepFrozeNonFinite) {
    std::fprintf(
        stderr, "elan: warning: step %" PRIu64 ": a body became non-finite and was frozen\n", step);
  }
  if (fresh & kStepColorOverflow) {
    std::fprintf(stderr,
                 "elan: warning: step %" PRIu64
                 ": constraints overflowed the colours (solved serially)\n",
                 step);
  }
  if (fresh & kStepBadTimestep) {
    std::fprintf(stderr, "elan: warning: step %" PRIu64 ": bad timestep, nothing simulated\n",
                 step);
  }
}

class Progress {
 public:
  Progress(const char* verb, uint64_t total)
      : verb_(verb), total_(total), start_(Clock::now()), last_(start_) {}
  void update(uint64_t done) {
    const auto now = Clock::now();
    if (std::chrono::duration<double>(now - last_).count() < kProgressSeconds) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "elan: %s step %" PRIu64 "/%" PRIu64 " (%.0f%%), %.3f ms/step\n", verb_,
                 done, total_, 100.0 * double(done) / double(total_),
                 1000.0 * elapsed / double(done));
  }

 private:
  const char* verb_;
  uint64_t total_;
  Clock::time_point start_, last_;
};

int run(const RunOptions& o) {
  const std::string text = read_file(o.scene, "scene");
  const Scene scene = parse_scene(text, o.scene);
  WorldDef def = scene.world;
  if (o.substeps) def.substeps = *o.substeps;
  if (o.iterations) def.iterations = *o.iterations;
  def.threads = resolve_threads(o.threads);
  def.broadphase = o.broadphase;
  const Real dt = o.timestep ? Real(*o.timestep) : scene.timestep;
  World world = make_world(def, o.scene);
  load_into(scene, world, o.scene);
  if (o.has_every && o.trajectory.empty()) {
    std::fprintf(stderr, "elan: warning: --every has no effect without --trajectory\n");
  }

  // Output files are opened before stepping so a bad path fails at once.
  std::optional<TrajectoryWriter> trajectory;
  if (!o.trajectory.empty()) trajectory.emplace(o.trajectory, world);
  std::ofstream record;
  if (!o.record.empty()) {
    record.open(o.record, std::ios::binary | std::ios::trunc);
    if (!record)
      throw std::runtime_error(o.record + ": cannot open for writing: " + std::strerror(errno));
  }

  std::vector<uint64_t> hashes;
  if (!o.record.empty()) {
    hashes.reserve(o.steps + 1);
    hashes.push_back(world.state_hash());
  }
  if (trajectory) trajectory->write(world, 0, 0.0);

  StepProfile total;
  uint32_t status = kStepOk;
  double wall = 0;
  Progress progress("run", o.steps);
  for (uint64_t step = 1; step <= o.steps; ++step) {
    const auto t0 = Clock::now();
    const uint32_t s = world.step(dt);
    wall += std::chrono::duration<double>(Clock::now() - t0).count();
    warn_status(s & ~status, step);
    status |= s;
    const StepProfile& p = world.last_step().profile;
    total.bounds += p.bounds;
    total.pairs += p.pairs;
    total.collide += p.collide;
    total.islands += p.islands;
    total.color += p.color;
    total.solve += p.solve;
    total.ccd += p.ccd;
    total.finalize += p.finalize;
    total.total += p.total;
    if (!hashes.empty()) hashes.push_back(world.state_hash());
    if (trajectory && (step % o.every == 0 || step == o.steps)) {
      trajectory->write(world, step, double(step) * double(dt));
    }
    progress.update(step);
  }
  if (trajectory) trajectory->close();
  if (!o.record.empty()) {
    Recording r;
    r.real_bytes = sizeof(Real);
    r.steps = o.steps;
    r.timestep = double(dt);
    r.substeps = def.substeps;
    r.iterations = def.iterations;
    r.threads = uint32_t(def.threads);
    r.broadphase = uint32_t(def.broadphase);
    r.scene_name = o.scene;
    r.scene_text = text;
    r.hashes = std::move(hashes);
    const std::string bytes = encode_recording(r);
    record.write(bytes.data(), std::streamsize(bytes.size()));
    record.close();
    if (!record) throw std::runtime_error(o.record + ": writing the recording failed");
  }

  const StepStats& last = world.last_step();
  std::size_t awake = last.awake;
  if (o.steps == 0) {
    awake = 0;
    for (std::size_t i = 0; i < world.body_count(); ++i) {
      const BodyId id = world.body_at(i);
      awake += world.motion_type(id) == MotionType::Dynamic && world.is_awake(id);
    }
  }
  Json out;
  out["scene"] = o.scene;
  out["bodies"] = world.body_count();
  out["steps"] = o.steps;
  out["threads"] = def.threads;
  out["broadphase"] = broadphase_name(def.broadphase);
  out["timestep"] = double(dt);
  out["substeps"] = world.settings().substeps;
  out["iterations"] = world.settings().iterations;
  out["wall_seconds"] = wall;
  out["ms_per_step"] = o.steps == 0 ? 0.0 : 1000.0 * wall / double(o.steps);
  out["state_hash"] = hex(world.state_hash());
  out["kinetic_energy"] = double(world.kinetic_energy());
  out["linear_momentum"] = vec(world.linear_momentum());
  out["angular_momentum"] = vec(world.angular_momentum());
  out["pairs"] = o.steps == 0 ? 0 : last.pairs;
  out["manifolds"] = o.steps == 0 ? 0 : last.manifolds;
  out["contacts"] = o.steps == 0 ? 0 : last.contacts;
  out["awake"] = awake;
  out["colors"] = o.steps == 0 ? 0 : last.colors;
  out["overflow"] = o.steps == 0 ? 0 : last.overflow;
  out["status"] = status;
  out["profile_ms"] = {
      {"bounds", total.bounds},   {"pairs", total.pairs},       {"collide", total.collide},
      {"islands", total.islands}, {"color", total.color},       {"solve", total.solve},
      {"ccd", total.ccd},         {"finalize", total.finalize}, {"total", total.total}};
  std::cout << out.dump() << std::endl;
  return 0;
}

int replay(const ReplayOptions& o) {
  const std::string bytes = read_file(o.file, "recording");
  const Recording r = decode_recording(bytes, o.file);
  if (r.real_bytes != sizeof(Real)) {
    throw RecordingError(o.file + ": recorded by a build with " + std::to_string(r.real_bytes * 8) +
                         "-bit Real, this build uses " + std::to_string(sizeof(Real) * 8) +
                         "-bit: hashes are comparable only on one build");
  }
  const Scene scene = parse_scene(r.scene_text, r.scene_name);
  WorldDef def = scene.world;
  def.substeps = r.substeps;
  def.iterations = r.iterations;
  def.threads = resolve_threads(o.threads);
  def.broadphase = o.broadphase.value_or(BroadphaseType(r.broadphase));
  const Real dt = Real(r.timestep);
  World world = make_world(def, r.scene_name);
  load_into(scene, world, r.scene_name);

  Json out;
  out["recording"] = o.file;
  out["steps"] = r.steps;
  out["threads"] = def.threads;
  out["broadphase"] = broadphase_name(def.broadphase);
  Progress progress("replay", r.steps);
  for (uint64_t step = 0; step <= r.steps; ++step) {
    if (step > 0) {
      world.step(dt);
      progress.update(step);
    }
    const uint64_t h = world.state_hash();
    if (h != r.hashes[step]) {
      out["match"] = false;
      out["first_mismatch_step"] = step;
      out["expected"] = hex(r.hashes[step]);
      out["actual"] = hex(h);
      std::cout << out.dump() << std::endl;
      return 1;
    }
  }
  out["match"] = true;
  out["state_hash"] = hex(r.hashes.back());
  std::cout << out.dump() << std::endl;
  return 0;
}

int dispatch(const std::vector<std::string>& args) {
  if (args.empty()) {
    std::fputs(kMainUsage, stderr);
    return 2;
  }
  const std::string& command = args[0];
  const std::span<const std::string> rest(args.data() + 1, args.size() - 1);
  if (command == "--help" || command == "-h" || command == "help") {
    std::fputs(kMainUsage, stdout);
    return 0;
  }
  if (command == "--version") {
    std::puts("elan 0.1.0");
    return 0;
  }
  if (command == "run") {
    const RunOptions o = parse_run_options(rest);
    if (o.help) {
      std::fputs(kRunUsage, stdout);
      return 0;
    }
    return run(o);
  }
  if (command == "replay") {
    const ReplayOptions o = parse_replay_options(rest);
    if (o.help) {
      std::fputs(kReplayUsage, stdout);
      return 0;
    }
    return replay(o);
  }
  throw UsageError("unknown command '" + command + "'");
}

}  // namespace
}  // namespace elan::cli

int main(int argc, char** argv) {
  using namespace elan::cli;
  try {
    return dispatch(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& e) {
    std::fprintf(stderr, "elan: %s (see 'elan --help')\n", e.what());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "elan: out of memory\n");
  } catch (const elan::SceneError& e) {
    std::fprintf(stderr, "%s\n", e.what());
  } catch (const RecordingError& e) {
    std::fprintf(stderr, "%s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "elan: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "elan: unexpected error\n");
  }
  return 2;
}
