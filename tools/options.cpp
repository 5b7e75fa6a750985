// SPDX-License-Identifier: MIT
// Command-line parsing for the elan tool. Hand-written: two commands with a dozen options do not
// justify a dependency (CLI11 is not in Debian's default set of installed packages).
#include "tools/options.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <utility>
#include <vector>

#include "core/base/range_checks.hpp"
#include "elan/debug_draw.hpp"
#include "elan/limits.hpp"

namespace elan::cli {

const char* const kMainUsage =
    "usage: elan <command> [options]\n"
    "\n"
    "commands:\n"
    "  run SCENE.json [options]   simulate a scene, print a JSON summary on stdout\n"
    "  replay FILE [options]      re-simulate a recording and compare every step's state hash\n"
    "  diverge SCENE.json --a OPTS --b OPTS\n"
    "                             step a scene under two settings side by side and report the\n"
    "                             first step, body and field that differ\n"
    "  view SCENE.json|RECORDING  open a window on a scene (or play a recording); with\n"
    "                             --screenshot, render a picture off screen and exit\n"
    "  batch SWEEP.json [options] run many simulations (a sweep of parameters or a list of\n"
    "                             scenes) on a Dask cluster; a table of their summaries\n"
    "                             (Python: python3 -m elan.batch, docs/batch.md)\n"
    "\n"
    "'elan COMMAND --help' lists a command's options.\n";

const char* const kRunUsage =
    "usage: elan run SCENE.json [options]\n"
    "\n"
    "  --steps N            steps to simulate (default 600; 0 loads the scene only)\n"
    "  --timestep S         seconds per step (default: the scene's, else 1/60)\n"
    "  --substeps K         solver substeps per step, 1..64 (default: the scene's, else the\n"
    "                       engine's)\n"
    "  --iterations K       solver iterations per substep, 1..64 (default: the scene's, else\n"
    "                       the engine's)\n"
    "  --threads T          worker threads, at most the cores (default: all cores)\n"
    "  --broadphase B       sap, all-pairs or tree (default sap)\n"
    "  --simd P             SIMD path: sse2, avx2, avx512 (default: ELAN_SIMD, else the widest\n"
    "                       this CPU runs; a native build has only native)\n"
    "  --trajectory F.csv   write every non-static body's state at step 0, every K-th and the "
    "last\n"
    "  --every K            trajectory interval in steps (default 1)\n"
    "  --record FILE        save the scene, the settings and every step's state hash\n"
    "  --keyframe-every K   with --record: also a full snapshot every K steps and at step 0\n"
    "                       (default 60; 0 = none), used by replay to find the body that diverged\n"
    "\n"
    "Prints one JSON object on stdout at the end; progress and warnings go to stderr.\n"
    "Exit status: 0 ok, 2 bad arguments or input.\n";

const char* const kReplayUsage =
    "usage: elan replay FILE [options]\n"
    "\n"
    "  --threads T          worker threads, at most the cores (default: all cores)\n"
    "  --broadphase B       sap, all-pairs or tree (default: the recorded one)\n"
    "  --perturb BODY:STEP  testing aid: nudge body BODY's x position up by one ulp after STEP\n"
    "                       steps, to check that the divergence is found\n"
    "  --until STEP         stop after STEP steps\n"
    "  --save-snapshot OUT  with --until: write the state there as a snapshot\n"
    "  --save-scene OUT     with --until: write it as a scene (a scene recording at step 0 only)\n"
    "\n"
    "Re-simulates a recording made with 'elan run --record' or by a program's recorder\n"
    "(elan/recorder.hpp: the program's calls are re-applied before each step) and prints one\n"
    "JSON line. At the\n"
    "first step whose hash differs it names the first body and field that differ, found against\n"
    "the recording's keyframe at that step, or by re-simulating from the keyframe before it with\n"
    "the recorded settings.\n"
    "Exit status: 0 all steps match, 1 a step's hash differs, 2 bad arguments or file.\n";

const char* const kDivergeUsage =
    "usage: elan diverge SCENE.json --a \"OPTIONS\" --b \"OPTIONS\" [options]\n"
    "\n"
    "  --steps N            steps to compare (default 600)\n"
    "  --timestep S         seconds per step (default: the scene's, else 1/60)\n"
    "  --a OPTIONS          settings of world a, e.g. \"--threads 1\"\n"
    "  --b OPTIONS          settings of world b, e.g. \"--threads 2 --broadphase all-pairs\"\n"
    "\n"
    "OPTIONS (default --threads 1 --broadphase sap, the scene's substeps and iterations):\n"
    "  --threads T, --broadphase sap|all-pairs|tree, --substeps K, --iterations K,\n"
    "  --perturb BODY:STEP (testing aid: nudge BODY's x position by one ulp after STEP steps)\n"
    "\n"
    "Steps both worlds side by side, compares every body's stored pose, velocities, sleep timer\n"
    "and flags bit for bit after each step, and prints one JSON line.\n"
    "Exit status: 0 no difference, 1 they diverged, 2 bad arguments or scene.\n";

const char* const kViewUsage =
    "usage: elan view SCENE.json|RECORDING [options]\n"
    "\n"
    "  --paused             open paused\n"
    "  --threads T          worker threads, at most the cores (default: all cores)\n"
    "  --steps N            simulate N steps first (default 0)\n"
    "  --size WxH           window or picture size in pixels (default 1280x720)\n"
    "  --camera EX,EY,EZ,AX,AY,AZ\n"
    "                       camera eye and target (m, world; default: frame every non-static\n"
    "                       body)\n"
    "  --screenshot F.png   render the state after N steps off screen to F.png and exit\n"
    "  --frames DIR         render frames DIR/frame_00000.png ... off screen, one every K steps\n"
    "                       up to step N, and exit\n"
    "  --every K            with --frames: the frame interval in steps (default 1)\n"
    "  --step N             recording: open at step N (e.g. the first_mismatch_step of\n"
    "                       'elan replay')\n"
    "  --body K             recording: select and highlight body K (e.g. the divergence's body)\n"
    "  --draw LIST          overlays, comma-separated: bounds, contacts (points and normals),\n"
    "                       joints, islands (bodies coloured by island), com (centres of mass),\n"
    "                       halves (bodies coloured by the solver's half, the cut's contacts)\n"
    "\n"
    "Off screen (--screenshot, --frames) one JSON line is printed on stdout: the state hash and\n"
    "step count, as 'elan run' prints them. A display is needed (under no X server, run it under\n"
    "'xvfb-run -a'). Keys and mouse: docs/viewer.md.\n"
    "Exit status: 0 ok, 2 bad arguments, input, or no display.\n";

namespace {

constexpr uint64_t kMaxSteps = 1'000'000'000;
// --substeps, --iterations and --threads take the library's own ranges (elan/defs.hpp), so a
// value the world would refuse is refused here, naming the flag.

uint64_t parse_count(const std::string& option, const std::string& text, uint64_t lo, uint64_t hi) {
  // strtoull accepts a sign and leading spaces; a count is digits only.
  bool digits = !text.empty() && text.size() <= 19;
  for (char c : text) digits = digits && c >= '0' && c <= '9';
  if (!digits) throw UsageError(option + ": expected a whole number, got '" + text + "'");
  const uint64_t v = std::strtoull(text.c_str(), nullptr, 10);
  if (v < lo || v > hi) {
    throw UsageError(option + ": must be in " + std::to_string(lo) + ".." + std::to_string(hi) +
                     ", got " + text);
  }
  return v;
}

double parse_seconds(const std::string& option, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double v = text.empty() ? 0 : std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v)) {
    throw UsageError(option + ": expected a finite number, got '" + text + "'");
  }
  if (!(v > 0) || !(Real(v) > 0) || !std::isfinite(Real(v))) {
    throw UsageError(option + ": must be positive, got " + text);
  }
  // The step's range (elan/limits.hpp): outside it World::step would simulate nothing.
  if (!(Real(v) >= Real(limits::kMinTimestep) && Real(v) <= Real(limits::kMaxTimestep))) {
    throw UsageError(option + ": must be in [" + detail::show_value(limits::kMinTimestep) + ", " +
                     detail::show_value(limits::kMaxTimestep) + "] s, got " + text);
  }
  return v;
}

BroadphaseType parse_broadphase(const std::string& option, const std::string& text) {
  if (text == "sap") return BroadphaseType::SweepAndPrune;
  if (text == "all-pairs") return BroadphaseType::AllPairs;
  if (text == "tree") return BroadphaseType::Tree;
  throw UsageError(option + ": expected sap, all-pairs or tree, got '" + text + "'");
}

SimdPath parse_simd(const std::string& option, const std::string& text) {
  for (const SimdPath p : {SimdPath::Sse2, SimdPath::Avx2, SimdPath::Avx512, SimdPath::Native}) {
    if (text == simd_path_name(p)) return p;
  }
  throw UsageError(option + ": expected sse2, avx2, avx512 or native, got '" + text + "'");
}

Perturbation parse_perturbation(const std::string& option, const std::string& text) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) {
    throw UsageError(option + ": expected BODY:STEP, got '" + text + "'");
  }
  Perturbation p;
  p.body = parse_count(option, text.substr(0, colon), 0, UINT32_MAX);
  p.step = parse_count(option, text.substr(colon + 1), 0, kMaxSteps);
  return p;
}

// Splits an option string on spaces (no quoting: none of the values has a space).
std::vector<std::string> split_words(const std::string& text) {
  std::vector<std::string> words;
  std::string word;
  for (char c : text + " ") {
    if (c == ' ' || c == '\t') {
      if (!word.empty()) words.push_back(word);
      word.clear();
    } else {
      word.push_back(c);
    }
  }
  return words;
}

// Walks `args`, accepting `--name value` and `--name=value`; the single positional argument goes
// to `positional`, each option's value to `on_option`.
void walk(std::span<const std::string> args, const std::string& command, std::string& positional,
          bool& help, const std::function<void(const std::string&, const std::string&)>& on_option,
          const std::function<bool(const std::string&)>& takes_value) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      help = true;
      continue;
    }
    if (a.size() > 1 && a[0] == '-') {
      std::string name = a;
      std::string value;
      bool has_value = false;
      if (const std::size_t eq = a.find('='); eq != std::string::npos) {
        name = a.substr(0, eq);
        value = a.substr(eq + 1);
        has_value = true;
      }
      if (!takes_value(name)) {
        throw UsageError("elan " + command + ": unknown option '" + name + "'");
      }
      if (!has_value) {
        if (i + 1 >= args.size()) throw UsageError(name + ": missing value");
        value = args[++i];
      }
      on_option(name, value);
      continue;
    }
    if (!positional.empty()) {
      throw UsageError("elan " + command + ": unexpected argument '" + a + "'");
    }
    positional = a;
  }
}

}  // namespace

RunOptions parse_run_options(std::span<const std::string> args) {
  RunOptions o;
  const auto takes_value = [](const std::string& n) {
    return n == "--steps" || n == "--timestep" || n == "--substeps" || n == "--iterations" ||
           n == "--threads" || n == "--broadphase" || n == "--trajectory" || n == "--every" ||
           n == "--record" || n == "--keyframe-every" || n == "--simd";
  };
  const auto on_option = [&o](const std::string& n, const std::string& v) {
    if (n == "--steps") {
      o.steps = parse_count(n, v, 0, kMaxSteps);
    } else if (n == "--timestep") {
      o.timestep = parse_seconds(n, v);
    } else if (n == "--substeps") {
      o.substeps = int(parse_count(n, v, 1, kMaxSubsteps));
    } else if (n == "--iterations") {
      o.iterations = int(parse_count(n, v, 1, kMaxIterations));
    } else if (n == "--threads") {
      o.threads = int(parse_count(n, v, 1, kMaxThreads));
    } else if (n == "--broadphase") {
      o.broadphase = parse_broadphase(n, v);
    } else if (n == "--simd") {
      o.simd = parse_simd(n, v);
    } else if (n == "--trajectory" || n == "--record") {
      if (v.empty()) throw UsageError(n + ": empty file name");
      (n == "--trajectory" ? o.trajectory : o.record) = v;
    } else if (n == "--every") {
      o.every = parse_count(n, v, 1, kMaxSteps);
      o.has_every = true;
    } else if (n == "--keyframe-every") {
      o.keyframe_every = parse_count(n, v, 0, kMaxSteps);
      o.has_keyframe_every = true;
    }
  };
  walk(args, "run", o.scene, o.help, on_option, takes_value);
  if (!o.help && o.scene.empty()) throw UsageError("elan run: missing SCENE.json");
  return o;
}

ReplayOptions parse_replay_options(std::span<const std::string> args) {
  ReplayOptions o;
  const auto takes_value = [](const std::string& n) {
    return n == "--threads" || n == "--broadphase" || n == "--perturb" || n == "--until" ||
           n == "--save-snapshot" || n == "--save-scene";
  };
  const auto on_option = [&o](const std::string& n, const std::string& v) {
    if (n == "--threads") {
      o.threads = int(parse_count(n, v, 1, kMaxThreads));
    } else if (n == "--perturb") {
      o.perturb = parse_perturbation(n, v);
    } else if (n == "--until") {
      o.until = parse_count(n, v, 0, kMaxSteps);
    } else if (n == "--save-snapshot") {
      o.save_snapshot = v;
    } else if (n == "--save-scene") {
      o.save_scene = v;
    } else {
      o.broadphase = parse_broadphase(n, v);
    }
  };
  walk(args, "replay", o.file, o.help, on_option, takes_value);
  if (!o.help && o.file.empty()) throw UsageError("elan replay: missing FILE");
  if ((!o.save_snapshot.empty() || !o.save_scene.empty()) && !o.until) {
    throw UsageError("--save-snapshot and --save-scene need --until STEP");
  }
  return o;
}

namespace {

SideOptions parse_side(const std::string& option, const std::string& text) {
  SideOptions side;
  const std::vector<std::string> words = split_words(text);
  std::string positional;
  bool help = false;
  const auto takes_value = [](const std::string& n) {
    return n == "--threads" || n == "--broadphase" || n == "--substeps" || n == "--iterations" ||
           n == "--perturb";
  };
  const auto on_option = [&side](const std::string& n, const std::string& v) {
    if (n == "--threads") {
      side.threads = int(parse_count(n, v, 1, kMaxThreads));
    } else if (n == "--broadphase") {
      side.broadphase = parse_broadphase(n, v);
    } else if (n == "--substeps") {
      side.substeps = int(parse_count(n, v, 1, kMaxSubsteps));
    } else if (n == "--iterations") {
      side.iterations = int(parse_count(n, v, 1, kMaxIterations));
    } else {
      side.perturb = parse_perturbation(n, v);
    }
  };
  try {
    walk(words, "diverge " + option, positional, help, on_option, takes_value);
  } catch (const UsageError& e) {
    throw UsageError(option + " \"" + text + "\": " + e.what());
  }
  if (help || !positional.empty()) {
    throw UsageError(option + ": unexpected '" + (help ? std::string("--help") : positional) + "'");
  }
  return side;
}

}  // namespace

DivergeOptions parse_diverge_options(std::span<const std::string> args) {
  DivergeOptions o;
  const auto takes_value = [](const std::string& n) {
    return n == "--steps" || n == "--timestep" || n == "--a" || n == "--b";
  };
  const auto on_option = [&o](const std::string& n, const std::string& v) {
    if (n == "--steps") {
      o.steps = parse_count(n, v, 0, kMaxSteps);
    } else if (n == "--timestep") {
      o.timestep = parse_seconds(n, v);
    } else {
      (n == "--a" ? o.a : o.b) = parse_side(n, v);
    }
  };
  walk(args, "diverge", o.scene, o.help, on_option, takes_value);
  if (!o.help && o.scene.empty()) throw UsageError("elan diverge: missing SCENE.json");
  return o;
}

namespace {

// `WxH`, each side in 16..8192 pixels.
void parse_size(const std::string& option, const std::string& text, int& w, int& h) {
  const std::size_t x = text.find('x');
  if (x == std::string::npos) throw UsageError(option + ": expected WxH, got '" + text + "'");
  w = int(parse_count(option, text.substr(0, x), 16, 8192));
  h = int(parse_count(option, text.substr(x + 1), 16, 8192));
}

// Six finite numbers separated by commas.
void parse_camera(const std::string& option, const std::string& text, double (&out)[6]) {
  std::size_t start = 0;
  for (int i = 0; i < 6; ++i) {
    const std::size_t comma = text.find(',', start);
    const bool last = i == 5;
    if ((comma == std::string::npos) != last) {
      throw UsageError(option + ": expected six numbers EX,EY,EZ,AX,AY,AZ, got '" + text + "'");
    }
    const std::string word = text.substr(start, last ? std::string::npos : comma - start);
    char* end = nullptr;
    errno = 0;
    const double v = word.empty() ? 0 : std::strtod(word.c_str(), &end);
    if (word.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v) || std::abs(v) > 1e6) {
      throw UsageError(option + ": expected a finite number within 1e6 m, got '" + word + "'");
    }
    out[i] = v;
    start = comma + 1;
  }
  const double dx = out[3] - out[0], dy = out[4] - out[1], dz = out[5] - out[2];
  if (!(dx * dx + dy * dy + dz * dz > 1e-12)) {
    throw UsageError(option + ": the eye and the target must differ");
  }
}

// "bounds,contacts,..." -> elan::DebugDrawFlags; each name once at most.
uint32_t parse_overlays(const std::string& option, const std::string& text) {
  static constexpr std::pair<const char*, uint32_t> kNames[] = {
      {"bounds", kDrawBounds},   {"contacts", kDrawContacts}, {"joints", kDrawJoints},
      {"islands", kDrawIslands}, {"com", kDrawCentersOfMass}, {"halves", kDrawSolverHalves}};
  uint32_t flags = 0;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string name =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    uint32_t bit = 0;
    for (const auto& [known, b] : kNames) {
      if (name == known) bit = b;
    }
    if (bit == 0) {
      throw UsageError(option + ": unknown overlay '" + name +
                       "' (bounds, contacts, joints, islands, com, halves)");
    }
    if (flags & bit) throw UsageError(option + ": '" + name + "' given twice");
    flags |= bit;
    if (comma == std::string::npos) return flags;
    start = comma + 1;
  }
}

}  // namespace

ViewOptions parse_view_options(std::span<const std::string> args) {
  ViewOptions o;
  bool has_every = false;
  // --paused takes no value: it is taken out before the common walk.
  std::vector<std::string> rest;
  for (const std::string& a : args) {
    if (a == "--paused") {
      o.paused = true;
    } else {
      rest.push_back(a);
    }
  }
  const auto takes_value = [](const std::string& n) {
    return n == "--threads" || n == "--screenshot" || n == "--frames" || n == "--every" ||
           n == "--steps" || n == "--size" || n == "--camera" || n == "--step" || n == "--body" ||
           n == "--draw";
  };
  const auto on_option = [&](const std::string& n, const std::string& v) {
    if (n == "--threads") {
      o.threads = int(parse_count(n, v, 1, kMaxThreads));
    } else if (n == "--screenshot" || n == "--frames") {
      if (v.empty()) throw UsageError(n + ": empty file name");
      (n == "--screenshot" ? o.screenshot : o.frames) = v;
    } else if (n == "--every") {
      o.every = parse_count(n, v, 1, kMaxSteps);
      has_every = true;
    } else if (n == "--steps") {
      o.steps = parse_count(n, v, 0, kMaxSteps);
    } else if (n == "--size") {
      parse_size(n, v, o.width, o.height);
    } else if (n == "--camera") {
      parse_camera(n, v, o.camera);
      o.has_camera = true;
    } else if (n == "--step") {
      o.step = parse_count(n, v, 0, kMaxSteps);
    } else if (n == "--draw") {
      o.draw = parse_overlays(n, v);
    } else {
      o.body = parse_count(n, v, 0, UINT32_MAX);
    }
  };
  walk(rest, "view", o.file, o.help, on_option, takes_value);
  if (o.help) return o;
  if (o.file.empty()) throw UsageError("elan view: missing SCENE.json or RECORDING");
  if (has_every && o.frames.empty()) throw UsageError("--every: only with --frames");
  if (!o.screenshot.empty() && !o.frames.empty()) {
    throw UsageError("elan view: --screenshot and --frames exclude each other");
  }
  return o;
}

}  // namespace elan::cli
