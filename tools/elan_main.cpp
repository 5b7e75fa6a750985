// SPDX-License-Identifier: MIT
// The elan command: `elan run` simulates a scene file and prints a JSON summary, `elan replay`
// re-simulates a recording and compares every step's state hash, `elan diverge` steps a scene
// under two settings side by side, `elan batch` runs a sweep of simulations on a Dask cluster
// (in Python). Every error exits with status 2.
#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>
#if defined(__GLIBC__)
#include <malloc.h>  // mallopt
#endif

#include "core/scene/regular_file.hpp"
#include "core/scene/self_contained.hpp"
#include "core/world/world_access.hpp"
#include "elan/elan.hpp"
#include "elan/one_line.hpp"
#include "elan/snapshot.hpp"
#include "tools/batch_command.hpp"
#include "tools/options.hpp"
#include "tools/recording.hpp"
#include "tools/trajectory.hpp"
#if defined(ELAN_HAVE_VIEWER)
#include "tools/viewer/viewer.hpp"
#endif

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

// Prints one JSON line on stdout. A path or body name that is not valid UTF-8 (a file name may be
// any bytes) is printed with U+FFFD in place of the bad bytes: nlohmann's default would throw
// after the whole run and print no summary.
void print(const Json& out) {
  std::cout << out.dump(-1, ' ', false, Json::error_handler_t::replace) << std::endl;
}

// The bytes of the recording `path`, a regular file whose magic is checked before the rest is
// read (so /dev/zero, or a large file of anything else, is refused at once).
std::string read_recording(const std::string& path) {
  try {
    detail::RegularFile file(path, "recording");
    std::string bytes = file.read(kRecordingMagicBytes);
    check_recording_magic(bytes, path);
    bytes += file.read(std::numeric_limits<uint64_t>::max());
    return bytes;
  } catch (const detail::FileError& e) {
    throw RecordingError(e.what());
  }
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

// Exit status of `elan run` from its summary: 0, or 1 when its numbers cannot be trusted: a
// total that is not finite (which JSON can only print as null), or a body that became non-finite
// and was frozen. Within elan/limits.hpp's ranges neither should happen (the totals are summed
// in double, and their bounds fit a float); should one still, a script checking the exit status
// must not take the run for sound, so the summary is printed for diagnosis and the status says
// it, on one stderr line.
int unsound_run_status(const Json& out, uint32_t status) {
  std::string bad;
  for (const char* key : {"kinetic_energy", "linear_momentum", "angular_momentum"}) {
    const Json& v = out[key];
    bool finite = true;
    if (v.is_array()) {
      for (const Json& x : v) finite = finite && x.is_number() && std::isfinite(x.get<double>());
    } else {
      finite = v.is_number() && std::isfinite(v.get<double>());
    }
    if (!finite) bad += std::string(bad.empty() ? "" : ", ") + key;
  }
  if (!bad.empty()) {
    std::fprintf(stderr, "elan: error: the summary's %s not finite (printed as null)\n",
                 (bad + (bad.find(',') == std::string::npos ? " is" : " are")).c_str());
    return 1;
  }
  if (status & kStepFrozeNonFinite) {
    std::fprintf(stderr,
                 "elan: error: a body became non-finite and was frozen: the results are not "
                 "sound\n");
    return 1;
  }
  return 0;
}

// The worker count to give a world for --threads `requested` (0 = all cores): the count that
// runs, with a warning when that is fewer than requested. A World makes a oneTBB arena of
// WorldDef::threads slots, but oneTBB runs at most max_allowed_parallelism threads at once (the
// machine's cores unless limited), so on 2 cores an arena of 4 runs 2. Results never depend on
// the count, so oversubscribing would buy nothing; the request is taken as an upper bound (as
// Box2D's workerCount is) and the summary reports the workers that actually run.
int workers(int requested) {
  const int n = resolve_threads(requested);
  if (requested > n) {
    std::fprintf(stderr,
                 "elan: warning: --threads %d: at most %d threads run at once here; using %d\n",
                 requested, n, n);
  }
  return n;
}

// The testing aid of --perturb: one ulp up on the stored x of the body's centre of mass.
void nudge(World& world, uint64_t body) {
  Real& px = detail::state_of(world).bodies.px[body];
  px = std::nextafter(px, std::numeric_limits<Real>::infinity());
}

void check_perturb_body(const std::optional<Perturbation>& p, const World& world) {
  if (p && p->body >= world.body_count()) {
    throw UsageError("--perturb: body " + std::to_string(p->body) +
                     " out of range (the scene has " + std::to_string(world.body_count()) +
                     " bodies)");
  }
}

Json json_name(const Scene& scene, std::size_t body) {
  if (body < scene.bodies.size() && !scene.bodies[body].name.empty()) {
    return scene.bodies[body].name;
  }
  return nullptr;
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
  std::string text = detail::read_scene_file(o.scene);
  WorldDef def;
  Real dt = 0;
  // The parsed scene is freed once the world holds it, and the file's text too unless it goes
  // into a recording: while stepping, the run holds only the world.
  World world = [&] {
    const Scene scene = parse_scene(text, o.scene);
    def = scene.world;
    if (o.substeps) def.substeps = *o.substeps;
    if (o.iterations) def.iterations = *o.iterations;
    def.threads = workers(o.threads);
    def.broadphase = o.broadphase;
    def.simd = o.simd;
    dt = o.timestep ? Real(*o.timestep) : scene.timestep;
    World w = make_world(def, o.scene);
    load_into(scene, w, o.scene);
    return w;
  }();
  if (o.record.empty()) std::string().swap(text);
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

  if (o.has_keyframe_every && o.record.empty()) {
    std::fprintf(stderr, "elan: warning: --keyframe-every has no effect without --record\n");
  }
  std::vector<uint64_t> hashes;
  std::vector<Keyframe> keyframes;
  const auto keyframe = [&](uint64_t step) {
    if (o.record.empty() || o.keyframe_every == 0 || step % o.keyframe_every != 0) return;
    keyframes.push_back(Keyframe{step, save_snapshot(world)});
  };
  if (!o.record.empty()) {
    hashes.reserve(o.steps + 1);
    hashes.push_back(world.state_hash());
  }
  keyframe(0);
  if (trajectory) trajectory->write(world, 0, 0.0);

  RunTotals totals;
  Progress progress("run", o.steps);
  for (uint64_t step = 1; step <= o.steps; ++step) {
    const auto t0 = Clock::now();
    const uint32_t s = world.step(dt);
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    warn_status(s & ~totals.status, step);
    totals.add(world, s, seconds);
    if (!hashes.empty()) hashes.push_back(world.state_hash());
    keyframe(step);
    if (trajectory && (step % o.every == 0 || step == o.steps)) {
      trajectory->write(world, step, double(step) * double(dt));
    }
    progress.update(step);
  }
  if (trajectory) trajectory->close();
  if (!o.record.empty()) {
    Recording r;
    r.real_bytes = sizeof(Real);
    r.engine_version = kEngineVersion;
    r.promise = kDeterminismPromise;
    r.steps = o.steps;
    r.timestep = double(dt);
    r.substeps = def.substeps;
    r.iterations = def.iterations;
    r.threads = uint32_t(def.threads);
    r.broadphase = uint32_t(def.broadphase);
    r.scene_name = o.scene;
    // The OBJ files the scene names go into the recording with it, so it replays anywhere.
    r.scene_text = detail::scene_file::self_contained(text, o.scene);
    r.keyframe_every = o.keyframe_every;
    r.keyframes = std::move(keyframes);
    r.hashes = std::move(hashes);
    const std::string bytes = encode_recording(r);
    record.write(bytes.data(), std::streamsize(bytes.size()));
    record.close();
    if (!record) throw std::runtime_error(o.record + ": writing the recording failed");
  }

  const std::string summary = run_summary_json(world, o.scene, dt, totals);
  std::cout << summary << std::endl;
  return unsound_run_status(Json::parse(summary), totals.status);
}

// A world holding a keyframe, settings as recorded. A keyframe that does not load is a corrupt
// recording.
World load_keyframe(const Keyframe& k, const std::string& file) {
  try {
    return load_snapshot(k.snapshot);
  } catch (const Error& e) {
    throw RecordingError(file + ": corrupt recording: keyframe at step " + std::to_string(k.step) +
                         ": " + e.what());
  }
}

// The world a recording starts from, with the replay's thread count and broadphase: the recorded
// scene (kept in `scene` for body names) or a program recording's starting snapshot. The
// recording's checksum held, so a scene or snapshot that does not load means a corrupt (or
// forged) recording: the message names the recording, and the recorded scene path only as part of
// what is wrong in it.
World start_world(const Recording& r, const std::string& file, int threads,
                  BroadphaseType broadphase, Scene& scene) {
  const auto corrupt = [&](const std::string& what) {
    return RecordingError(file + ": corrupt recording: " + what);
  };
  if (r.is_program()) {
    try {
      return recording_start_world(r, threads, broadphase);
    } catch (const RecordingError& e) {
      throw RecordingError(file + ": " + e.what());
    }
  }
  const std::string embedded =
      "recorded scene" + (r.scene_name.empty() ? std::string() : " \"" + r.scene_name + "\"");
  WorldDef def;
  try {
    scene = parse_scene(r.scene_text, embedded);
    def = scene.world;
  } catch (const SceneError& e) {
    throw corrupt(e.what());
  }
  def.substeps = r.substeps;
  def.iterations = r.iterations;
  def.threads = threads;
  def.broadphase = broadphase;
  try {
    World w(def);
    load_into(scene, w, embedded);
    return w;
  } catch (const SceneError& e) {
    throw corrupt(e.what());
  } catch (const Error& e) {
    throw corrupt(embedded + ": " + e.what());
  }
}

// Finds the first body and field that differ at step `d`, the first step whose hash differs.
// The recorded state at d is known in full only where a keyframe sits at d; otherwise it is
// rebuilt by restoring the last keyframe before d and replaying it to d (a program recording's
// calls included) with the recorded thread count and broadphase, which reproduces the recording
// exactly when the difference comes from the replay's own settings (or --perturb) and not from
// another build; the recorded hashes from the keyframe to d check that, and when they do not
// match, no body is named.
Json locate(const Recording& r, const std::string& file, const World& replayed, uint64_t d,
            const Scene& scene) {
  Json out;
  const Keyframe* k = keyframe_at_or_before(r, d);
  if (k == nullptr) {
    out["body"] = nullptr;
    out["reason"] = r.version < 2 ? "the recording has no keyframes (format version 1)"
                                  : "the recording has no keyframes (--keyframe-every 0)";
    return out;
  }
  World keyframe = load_keyframe(*k, file);
  keyframe.set_threads(resolve_threads(int(r.threads)));
  keyframe.set_broadphase(BroadphaseType(r.broadphase));
  Replayer reference(r, std::move(keyframe), k->step);
  const auto not_reproduced = [&](uint64_t step, const std::string& why) {
    out["body"] = nullptr;
    out["keyframe"] = k->step;
    out["reason"] = "re-simulating from the keyframe at step " + std::to_string(k->step) +
                    " with the recorded settings does not reproduce the recorded " + why +
                    " at step " + std::to_string(step) +
                    ": the recording comes from another build, or a step is not deterministic";
    return out;
  };
  if (reference.actual_hash() != r.hashes[k->step]) return not_reproduced(k->step, "hash");
  while (reference.step() < d) {
    try {
      if (!reference.advance()) return not_reproduced(reference.step(), "hash");
    } catch (const RecordingError& e) {
      return not_reproduced(reference.step() + 1, std::string("calls (") + e.what() + ")");
    }
  }
  const Divergence div = compare_worlds(reference.world(), replayed);
  out["keyframe"] = k->step;
  out["method"] = k->step == d ? "keyframe" : "re-simulated from keyframe";
  if (!div.found) {
    out["body"] = nullptr;
    out["reason"] = "the recorded state and the replay agree in every stored bit";
    return out;
  }
  out["body"] = div.body;
  out["name"] = json_name(scene, div.body);
  out["field"] = div.field;
  out["recorded"] = div.value_a;
  out["replayed"] = div.value_b;
  return out;
}

// Opens `path` for writing a binary file, or fails at once naming it.
std::ofstream open_output(const std::string& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(path + ": cannot open for writing: " + std::strerror(errno));
  return out;
}

void write_all(std::ofstream& out, const std::string& path, const void* data, std::size_t n) {
  out.write(static_cast<const char*>(data), std::streamsize(n));
  out.close();
  if (!out) throw std::runtime_error(path + ": writing failed");
}

// Reads and decodes a recording, refusing one from a build with other promises.
Recording load_recording(const std::string& file) {
  Recording r = decode_recording(read_recording(file), file);
  check_recording_build(r, file);
  return r;
}

int replay(const ReplayOptions& o) {
  const Recording r = load_recording(o.file);
  if (o.until && *o.until > r.steps) {
    throw UsageError("--until: " + std::to_string(*o.until) + " is past the recording's " +
                     std::to_string(r.steps) + " steps");
  }
  // A scene file holds bodies, shapes and joints but no contacts, warm starts or sleep timers,
  // so only a state that is exactly a scene can be written as one: a scene recording's start.
  if (!o.save_scene.empty() && (r.is_program() || *o.until != 0)) {
    throw std::runtime_error(
        "--save-scene: the state after " + std::to_string(*o.until) + " steps of " + o.file +
        " cannot be written as a scene (a scene holds no contacts, warm starts or sleep timers" +
        (r.is_program() ? ", and a program recording starts from a snapshot" : "") +
        "); use --save-snapshot");
  }
  std::ofstream snapshot_out, scene_out;
  if (!o.save_snapshot.empty()) snapshot_out = open_output(o.save_snapshot);
  if (!o.save_scene.empty()) scene_out = open_output(o.save_scene);

  Scene scene;
  const int threads = workers(o.threads);
  const BroadphaseType broadphase = o.broadphase.value_or(BroadphaseType(r.broadphase));
  Replayer replayer(r, start_world(r, o.file, threads, broadphase, scene));
  World& world = replayer.world();
  check_perturb_body(o.perturb, world);

  Json out;
  out["recording"] = o.file;
  out["kind"] = r.is_program() ? "program" : "scene";
  out["steps"] = r.steps;
  out["threads"] = threads;
  out["broadphase"] = broadphase_name(broadphase);
  out["keyframes"] = r.keyframes.size();
  const uint64_t last = o.until.value_or(r.steps);
  if (o.until) out["until"] = last;
  Progress progress("replay", last);
  for (uint64_t step = 0; step <= last; ++step) {
    if (step > 0) {
      try {
        replayer.advance();
      } catch (const RecordingError& e) {
        // A recorded call that fails on replay (a stale id, another returned id): the replay has
        // already parted from the recording; the hashes before it matched.
        out["match"] = false;
        out["first_mismatch_step"] = step;
        out["call_error"] = e.what();
        print(out);
        return 1;
      }
      progress.update(step);
    }
    if (o.perturb && o.perturb->step == step) nudge(world, o.perturb->body);
    const uint64_t h = world.state_hash();
    if (h != r.hashes[step]) {
      out["match"] = false;
      out["first_mismatch_step"] = step;
      out["expected"] = hex(r.hashes[step]);
      out["actual"] = hex(h);
      out["divergence"] = locate(r, o.file, world, step, scene);
      print(out);
      return 1;
    }
  }
  if (!o.save_snapshot.empty()) {
    const std::vector<uint8_t> bytes = save_snapshot(world);
    write_all(snapshot_out, o.save_snapshot, bytes.data(), bytes.size());
    out["snapshot"] = o.save_snapshot;
  }
  if (!o.save_scene.empty()) {
    write_all(scene_out, o.save_scene, r.scene_text.data(), r.scene_text.size());
    out["scene"] = o.save_scene;
  }
  out["match"] = true;
  out["state_hash"] = hex(r.hashes[last]);
  print(out);
  return 0;
}

Json side_json(const SideOptions& side, const World& world) {
  Json j;
  j["threads"] = world.settings().threads;
  j["broadphase"] = broadphase_name(side.broadphase);
  j["substeps"] = world.settings().substeps;
  j["iterations"] = world.settings().iterations;
  if (side.perturb) {
    j["perturb"] = {{"body", side.perturb->body}, {"step", side.perturb->step}};
  }
  return j;
}

// Steps `a` and `b` to `steps` with find_divergence, stopping after each perturbation's step to
// apply it; the step numbers reported are counted from the start.
Divergence step_side_by_side(World& a, World& b, const DivergeOptions& o, Real dt) {
  std::vector<std::pair<uint64_t, int>> stops;  // (step, side) of each perturbation
  if (o.a.perturb && o.a.perturb->step <= o.steps) stops.emplace_back(o.a.perturb->step, 0);
  if (o.b.perturb && o.b.perturb->step <= o.steps) stops.emplace_back(o.b.perturb->step, 1);
  std::sort(stops.begin(), stops.end());
  uint64_t done = 0;
  for (std::size_t i = 0; i < stops.size();) {
    const uint64_t step = stops[i].first;
    Divergence d = find_divergence(a, b, step - done, dt);
    if (d.found) {
      d.step += done;
      return d;
    }
    done = step;
    // Both sides' perturbations of this step are applied before the worlds are compared again:
    // sides given the same perturbation stay identical.
    for (; i < stops.size() && stops[i].first == step; ++i) {
      const int side = stops[i].second;
      nudge(side == 0 ? a : b, (side == 0 ? o.a : o.b).perturb->body);
    }
  }
  Divergence d = find_divergence(a, b, o.steps - done, dt);
  d.step += done;
  return d;
}

// Whether the file `path` starts with a recording's magic bytes (a scene file is JSON text).
bool starts_like_recording(const std::string& path) {
  std::string head;
  try {
    detail::RegularFile file(path, "scene or recording");
    head = file.read(kRecordingMagicBytes);
  } catch (const detail::FileError& e) {
    throw SceneError(e.what());
  }
  try {
    check_recording_magic(head, path);
    return head.size() == kRecordingMagicBytes;
  } catch (const RecordingError&) {
    return false;
  }
}

// `elan diverge RECORDING`: two replays of the recording side by side, each with its side's
// settings, every body compared bit for bit after each step (the recorded calls re-applied
// before each step on both sides).
int diverge_recording(const DivergeOptions& o) {
  const Recording r = load_recording(o.scene);
  if (o.timestep) throw UsageError("--timestep: a recording replays with its recorded timesteps");
  const auto make = [&](const SideOptions& side) {
    Scene unused;
    World world = start_world(r, o.scene, workers(side.threads), side.broadphase, unused);
    if (side.substeps) world.set_substeps(*side.substeps);
    if (side.iterations) world.set_iterations(*side.iterations);
    check_perturb_body(side.perturb, world);
    return Replayer(r, std::move(world));
  };
  Scene scene;
  if (!r.is_program()) scene = parse_scene(r.scene_text, "recorded scene");
  Replayer a = make(o.a);
  Replayer b = make(o.b);
  const uint64_t steps = std::min(o.steps, r.steps);
  Divergence d;
  std::string call_error;
  for (uint64_t step = 0; step <= steps && !d.found && call_error.empty(); ++step) {
    if (step > 0) {
      try {
        a.advance();
        b.advance();
      } catch (const RecordingError& e) {
        call_error = e.what();
        d.step = step;
        break;
      }
    }
    if (o.a.perturb && o.a.perturb->step == step) nudge(a.world(), o.a.perturb->body);
    if (o.b.perturb && o.b.perturb->step == step) nudge(b.world(), o.b.perturb->body);
    d = compare_worlds(a.world(), b.world());
    d.step = step;
  }
  Json out;
  out["recording"] = o.scene;
  out["steps"] = steps;
  out["a"] = side_json(o.a, a.world());
  out["b"] = side_json(o.b, b.world());
  out["diverged"] = d.found || !call_error.empty();
  if (!call_error.empty()) {
    out["step"] = d.step;
    out["call_error"] = call_error;
  } else if (d.found) {
    out["step"] = d.step;
    out["body"] = d.body;
    out["name"] = json_name(scene, d.body);
    out["field"] = d.field;
    out["value_a"] = d.value_a;
    out["value_b"] = d.value_b;
  }
  print(out);
  return out["diverged"].get<bool>() ? 1 : 0;
}

int diverge(const DivergeOptions& o) {
  if (starts_like_recording(o.scene)) return diverge_recording(o);
  const std::string text = detail::read_scene_file(o.scene);
  const Scene scene = parse_scene(text, o.scene);
  const Real dt = o.timestep ? Real(*o.timestep) : scene.timestep;
  const auto make = [&](const SideOptions& side) {
    WorldDef def = scene.world;
    if (side.substeps) def.substeps = *side.substeps;
    if (side.iterations) def.iterations = *side.iterations;
    def.threads = workers(side.threads);
    def.broadphase = side.broadphase;
    World world = make_world(def, o.scene);
    load_into(scene, world, o.scene);
    check_perturb_body(side.perturb, world);
    return world;
  };
  World a = make(o.a);
  World b = make(o.b);
  const Divergence d = step_side_by_side(a, b, o, dt);

  Json out;
  out["scene"] = o.scene;
  out["steps"] = o.steps;
  out["a"] = side_json(o.a, a);
  out["b"] = side_json(o.b, b);
  out["diverged"] = d.found;
  if (d.found) {
    out["step"] = d.step;
    out["body"] = d.body;
    out["name"] = json_name(scene, d.body);
    out["field"] = d.field;
    out["value_a"] = d.value_a;
    out["value_b"] = d.value_b;
  }
  print(out);
  return d.found ? 1 : 0;
}

// `elan view`: the scene (or the recording and its scene) is read, parsed and loaded into a world
// here, before any window opens, so a bad file exits 2 with the usual message whether or not the
// viewer is built, and with no display needed.
int view(const ViewOptions& o) {
  std::optional<Recording> recording;
  Scene scene;
  WorldDef def;
  std::optional<World> world;
  // Read only by the viewer: a build without it checks the file and the options all the same.
  [[maybe_unused]] Real dt = 0;
  std::string name = o.file;
  if (starts_like_recording(o.file)) {
    recording = load_recording(o.file);
    const Recording& r = *recording;
    name = std::string(r.is_program() ? "recorded program" : "recorded scene") +
           (r.scene_name.empty() ? std::string() : " \"" + r.scene_name + "\"");
    if (o.step && *o.step > r.steps) {
      throw UsageError("--step: " + std::to_string(*o.step) + " is past the recording's " +
                       std::to_string(r.steps) + " steps");
    }
    // As `elan replay` starts it: the recorded scene, or a program's starting snapshot.
    const BroadphaseType broadphase = BroadphaseType(r.broadphase);
    world.emplace(start_world(r, o.file, workers(o.threads), broadphase, scene));
    def = world->settings();
    def.thread_pool = nullptr;
    def.broadphase = broadphase;
    dt = Real(r.timestep);
  } else {
    if (o.step) throw UsageError("--step: only with a RECORDING");
    std::string text = detail::read_scene_file(o.file);
    scene = parse_scene(text, o.file);
    std::string().swap(text);
    def = scene.world;
    dt = scene.timestep;
    def.threads = workers(o.threads);
    world.emplace(make_world(def, name));
    load_into(scene, *world, name);
  }
  if (o.body && *o.body >= world->body_count()) {
    throw UsageError("--body: " + std::to_string(*o.body) + " out of range (the " +
                     (recording ? "recording starts with " : "scene has ") +
                     std::to_string(world->body_count()) + " bodies)");
  }
#if defined(ELAN_HAVE_VIEWER)
  viewer::Source source{name, std::move(scene), def, dt, std::move(recording)};
  return viewer::run(o, std::move(source), std::move(*world));
#else
  throw std::runtime_error(
      "view: this elan was built without the viewer (GLFW, Dear ImGui or OpenGL was not found "
      "when it was configured; install libglfw3-dev and libimgui-dev, see tools/setup.sh)");
#endif
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
    std::printf("elan %s (%s)\n", kEngineVersion, kDeterminismPromise);
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
  if (command == "diverge") {
    const DivergeOptions o = parse_diverge_options(rest);
    if (o.help) {
      std::fputs(kDivergeUsage, stdout);
      return 0;
    }
    return diverge(o);
  }
  if (command == "view") {
    const ViewOptions o = parse_view_options(rest);
    if (o.help) {
      std::fputs(kViewUsage, stdout);
      return 0;
    }
    return view(o);
  }
  if (command == "batch") exec_batch(rest);  // --help included: the Python side has the options
  throw UsageError("unknown command '" + command + "'");
}

}  // namespace
}  // namespace elan::cli

int main(int argc, char** argv) {
  using namespace elan::cli;
#if defined(__GLIBC__)
  // Buffers of 128 KiB and more (the contact list, the solver's bundles) come from mmap and go
  // back to the system when they grow. Left to itself, glibc raises this threshold to the size of
  // each such buffer it frees, and later growths then fragment its heap and raise the peak RSS.
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
#endif
  try {
    return dispatch(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& e) {
    std::fprintf(stderr, "elan: %s (see 'elan --help')\n", elan::one_line(e.what()).c_str());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "elan: out of memory\n");
  } catch (const elan::SceneError& e) {
    std::fprintf(stderr, "%s\n", elan::one_line(e.what()).c_str());
  } catch (const RecordingError& e) {
    std::fprintf(stderr, "%s\n", elan::one_line(e.what()).c_str());
  } catch (const std::exception& e) {
    // Any other exception's text may hold a path or a word from the command line: one line.
    std::fprintf(stderr, "elan: %s\n", elan::one_line(e.what()).c_str());
  } catch (...) {
    std::fprintf(stderr, "elan: unexpected error\n");
  }
  return 2;
}
