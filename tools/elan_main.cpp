// SPDX-License-Identifier: MIT
// The elan command: `elan run` simulates a scene file and prints a JSON summary, `elan replay`
// re-simulates a recording and compares every step's state hash, `elan diverge` steps a scene
// under two settings side by side. Every error exits with status 2.
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

Json vec(const Vec3& v) {
  return Json::array({double(v.x()), double(v.y()), double(v.z())});
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
    total.split += p.split;
    total.packets += p.packets;
    total.color += p.color;
    total.bundles += p.bundles;
    total.prepare += p.prepare;
    total.solve += p.solve;
    total.ccd += p.ccd;
    total.finalize += p.finalize;
    total.total += p.total;
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
  out["joints"] = world.joint_count();  // still in the world: broken ones are gone
  out["steps"] = o.steps;
  out["threads"] = def.threads;
  out["broadphase"] = broadphase_name(def.broadphase);
  out["simd"] = simd_path_name(world.simd_path());
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
      {"bounds", total.bounds},   {"pairs", total.pairs},     {"collide", total.collide},
      {"islands", total.islands}, {"split", total.split},     {"packets", total.packets},
      {"color", total.color},     {"bundles", total.bundles}, {"prepare", total.prepare},
      {"solve", total.solve},     {"ccd", total.ccd},         {"finalize", total.finalize},
      {"total", total.total}};
  print(out);
  return unsound_run_status(out, status);
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

// Finds the first body and field that differ at step `d`, the first step whose hash differs.
// The recorded state at d is known in full only where a keyframe sits at d; otherwise it is
// rebuilt by restoring the last keyframe before d and stepping it to d with the recorded thread
// count and broadphase, which reproduces the recording exactly when the difference comes from
// the replay's own settings (or --perturb) and not from another build; the recorded hashes from
// the keyframe to d check that, and when they do not match, no body is named.
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
  World reference = load_keyframe(*k, file);
  reference.set_threads(resolve_threads(int(r.threads)));
  reference.set_broadphase(BroadphaseType(r.broadphase));
  const Real dt = Real(r.timestep);
  for (uint64_t step = k->step; step <= d; ++step) {
    if (step > k->step) reference.step(dt);
    if (reference.state_hash() != r.hashes[step]) {
      out["body"] = nullptr;
      out["keyframe"] = k->step;
      out["reason"] = "re-simulating from the keyframe at step " + std::to_string(k->step) +
                      " with the recorded settings does not reproduce the recorded hash at step " +
                      std::to_string(step) +
                      ": the recording comes from another build, or a step is not deterministic";
      return out;
    }
  }
  const Divergence div = compare_worlds(reference, replayed);
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

int replay(const ReplayOptions& o) {
  const std::string bytes = read_recording(o.file);
  const Recording r = decode_recording(bytes, o.file);
  if (r.real_bytes != sizeof(Real)) {
    throw RecordingError(o.file + ": recorded by a build with " + std::to_string(r.real_bytes * 8) +
                         "-bit Real, this build uses " + std::to_string(sizeof(Real) * 8) +
                         "-bit: hashes are comparable only on one build");
  }
  // The recording's checksum held, so a scene or settings that do not load mean a corrupt (or
  // forged) recording: the message names the recording, and the recorded scene path only as
  // part of what is wrong in it.
  const std::string embedded =
      "recorded scene" + (r.scene_name.empty() ? std::string() : " \"" + r.scene_name + "\"");
  const auto corrupt = [&](const std::string& what) {
    return RecordingError(o.file + ": corrupt recording: " + what);
  };
  Scene scene;
  WorldDef def;
  try {
    scene = parse_scene(r.scene_text, embedded);
    def = scene.world;
  } catch (const SceneError& e) {
    throw corrupt(e.what());
  }
  def.substeps = r.substeps;
  def.iterations = r.iterations;
  def.threads = workers(o.threads);
  def.broadphase = o.broadphase.value_or(BroadphaseType(r.broadphase));
  const Real dt = Real(r.timestep);
  World world = [&] {
    try {
      World w(def);
      load_into(scene, w, embedded);
      return w;
    } catch (const SceneError& e) {
      throw corrupt(e.what());
    } catch (const Error& e) {
      throw corrupt(embedded + ": " + e.what());
    }
  }();
  check_perturb_body(o.perturb, world);

  Json out;
  out["recording"] = o.file;
  out["steps"] = r.steps;
  out["threads"] = def.threads;
  out["broadphase"] = broadphase_name(def.broadphase);
  out["keyframes"] = r.keyframes.size();
  Progress progress("replay", r.steps);
  for (uint64_t step = 0; step <= r.steps; ++step) {
    if (step > 0) {
      world.step(dt);
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
  out["match"] = true;
  out["state_hash"] = hex(r.hashes.back());
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

int diverge(const DivergeOptions& o) {
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

// `elan view`: the scene (or the recording and its scene) is read, parsed and loaded into a world
// here, before any window opens, so a bad file exits 2 with the usual message whether or not the
// viewer is built, and with no display needed.
int view(const ViewOptions& o) {
  std::string text;
  std::optional<Recording> recording;
  Scene scene;
  WorldDef def;
  // Read only by the viewer: a build without it checks the file and the options all the same.
  [[maybe_unused]] Real dt = 0;
  std::string name = o.file;
  if (starts_like_recording(o.file)) {
    recording = decode_recording(read_recording(o.file), o.file);
    const Recording& r = *recording;
    if (r.real_bytes != sizeof(Real)) {
      throw RecordingError(o.file + ": recorded by a build with " +
                           std::to_string(r.real_bytes * 8) + "-bit Real, this build uses " +
                           std::to_string(sizeof(Real) * 8) + "-bit");
    }
    name = "recorded scene" + (r.scene_name.empty() ? std::string() : " \"" + r.scene_name + "\"");
    try {
      scene = parse_scene(r.scene_text, name);
    } catch (const SceneError& e) {
      throw RecordingError(o.file + ": corrupt recording: " + e.what());
    }
    def = scene.world;
    def.substeps = r.substeps;
    def.iterations = r.iterations;
    def.broadphase = BroadphaseType(r.broadphase);
    dt = Real(r.timestep);
    if (o.step && *o.step > r.steps) {
      throw UsageError("--step: " + std::to_string(*o.step) + " is past the recording's " +
                       std::to_string(r.steps) + " steps");
    }
  } else {
    if (o.step) throw UsageError("--step: only with a RECORDING");
    text = detail::read_scene_file(o.file);
    scene = parse_scene(text, o.file);
    std::string().swap(text);
    def = scene.world;
    dt = scene.timestep;
  }
  def.threads = workers(o.threads);
  World world = make_world(def, name);
  load_into(scene, world, name);
  if (o.body && *o.body >= world.body_count()) {
    throw UsageError("--body: " + std::to_string(*o.body) + " out of range (the scene has " +
                     std::to_string(world.body_count()) + " bodies)");
  }
#if defined(ELAN_HAVE_VIEWER)
  viewer::Source source{name, std::move(scene), def, dt, std::move(recording)};
  return viewer::run(o, std::move(source), std::move(world));
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
