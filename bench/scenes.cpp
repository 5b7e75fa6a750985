// SPDX-License-Identifier: MIT
// Whole steps: the standard scenes, the joint scenes, the geometry scenes and a generated pile
// sweep at 1 and 2 threads, the same scenes in Bullet (the joint and geometry scenes also paired
// with it back to back), heap bytes per body, and the 2-thread ceiling of this machine (an FMA
// kernel and a streaming kernel) measured in the same run; the target scenes' speedups and the FMA
// ceiling also from 1- and 2-thread runs paired back to back. bench/run_suite.sh drives it; flags
// in usage().
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/world/memory_use.hpp"
#include "core/world/world_access.hpp"
#include "elan/scene.hpp"
#include "elan/world.hpp"
#ifdef ELAN_HAVE_BULLET
#include "bench/peer/bullet_world.hpp"
#endif

namespace {

using elan::Real;
using elan::Vec3;
using Clock = std::chrono::steady_clock;

struct Options {
  int warmup = 20, steps = 20, reps = 3;
  int sweep_warmup = 30, sweep_steps = 10, sweep_reps = 1;
  int calib_reps = 5;
  std::vector<std::string> scenes = {"jolt_pyramid", "pyramid20", "tower20", "many_pyramids",
                                     "pile1k",       "pile4k",    "pile10k", "spheres_in_box",
                                     "rain",         "tumbler",   "towers"};
  // Scenes that fall asleep within the warm-up, run once more with allow_sleep = false under the
  // name "<scene>-no-sleep", so that the work of their stacks is timed, not only their sleep.
  std::vector<std::string> no_sleep = {"pyramid20"};
  // Scenes with joints, with warm-up and timed steps of their own (-1: --warmup, --steps): they
  // are timed against Bullet's constraints, elan at 1 thread and Bullet paired back to back.
  std::vector<std::string> joint_scenes = {"joint_grid", "ragdolls", "chains"};
  int joint_warmup = -1, joint_steps = -1;
  // Scenes with meshes, heightfields and compounds (issue 38), with warm-up and timed steps of
  // their own (-1: --warmup, --steps): their bodies take a second or more to land, and a step of
  // thousands of bodies on a surface is long. Timed at 1 and 2 threads and against Bullet (its
  // btBvhTriangleMeshShape, btHeightfieldTerrainShape and btCompoundShape), paired back to back.
  std::vector<std::string> geometry_scenes = {"convex_vs_mesh", "heightfield_rain", "compounds"};
  int geometry_warmup = -1, geometry_steps = -1;
  std::vector<int> sweep = {1000, 2000, 4000, 8000, 16000, 32000};
  int allpairs_max = 8000;
  bool bullet = true;
};

void usage() {
  std::fprintf(
      stderr,
      "bench_scenes [benchmark flags] [--warmup=N] [--steps=N] [--reps=N]\n"
      "  [--sweep_warmup=N] [--sweep_steps=N] [--sweep_reps=N] [--calib_reps=N]\n"
      "  [--scenes=a,b,...] [--no_sleep=a,b,...] [--sweep=1000,2000,...] [--allpairs_max=N]\n"
      "  [--joint_scenes=a,b,...] [--joint_warmup=N] [--joint_steps=N]\n"
      "  [--geometry_scenes=a,b,...] [--geometry_warmup=N] [--geometry_steps=N]\n"
      "  (a scene named scene:kind, e.g. heightfield_rain:box, keeps its static bodies and its\n"
      "  moving bodies of that shape type only)\n"
      "  [--no_bullet]\n");
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// Takes our flags out of argv so that Google Benchmark sees only its own.
Options parse_options(int& argc, char** argv) {
  Options o;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto eq = a.find('=');
    const std::string key = a.substr(0, eq),
                      value = eq == std::string::npos ? "" : a.substr(eq + 1);
    const auto number = [&] { return std::atoi(value.c_str()); };
    if (key == "--warmup")
      o.warmup = number();
    else if (key == "--steps")
      o.steps = number();
    else if (key == "--reps")
      o.reps = number();
    else if (key == "--sweep_warmup")
      o.sweep_warmup = number();
    else if (key == "--sweep_steps")
      o.sweep_steps = number();
    else if (key == "--sweep_reps")
      o.sweep_reps = number();
    else if (key == "--calib_reps")
      o.calib_reps = number();
    else if (key == "--allpairs_max")
      o.allpairs_max = number();
    else if (key == "--scenes")
      o.scenes = split(value);
    else if (key == "--no_sleep")
      o.no_sleep = split(value);
    else if (key == "--joint_scenes")
      o.joint_scenes = split(value);
    else if (key == "--joint_warmup")
      o.joint_warmup = number();
    else if (key == "--joint_steps")
      o.joint_steps = number();
    else if (key == "--geometry_scenes")
      o.geometry_scenes = split(value);
    else if (key == "--geometry_warmup")
      o.geometry_warmup = number();
    else if (key == "--geometry_steps")
      o.geometry_steps = number();
    else if (key == "--no_bullet")
      o.bullet = false;
    else if (key == "--sweep") {
      o.sweep.clear();
      for (const auto& n : split(value)) o.sweep.push_back(std::atoi(n.c_str()));
    } else if (key == "--help_scenes") {
      usage();
      std::exit(0);
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  if (o.joint_warmup < 0) o.joint_warmup = o.warmup;
  if (o.joint_steps < 0) o.joint_steps = o.steps;
  if (o.geometry_warmup < 0) o.geometry_warmup = o.warmup;
  if (o.geometry_steps < 0) o.geometry_steps = o.steps;
  if (o.steps < 1 || o.reps < 1 || o.sweep_steps < 1 || o.warmup < 0 || o.joint_steps < 1 ||
      o.geometry_steps < 1) {
    usage();
    std::exit(2);
  }
  return o;
}

// A container filling up: n mixed bodies (boxes, spheres, capsules, hulls of about 0.3-0.4 m)
// on a 1.1 m lattice ten layers deep, over a floor sized for n, inside four static walls. The
// bodies drop 0..10 m, so after the warm-up the lower layers are colliding while the upper fall.
elan::Scene make_pile(int n) {
  elan::Scene s;
  const int side = int(std::ceil(std::sqrt(n / 10.0)));
  const Real half = Real(0.55 * side + 0.5);
  const auto wall = [&](const Vec3& he, const Vec3& pos) {
    elan::SceneBody b;
    b.shape.type = elan::ShapeType::Box;
    b.shape.half_extents = he;
    b.body.motion = elan::MotionType::Static;
    b.body.position = pos;
    s.bodies.push_back(b);
  };
  wall(Vec3(half + 1, 1, half + 1), Vec3(0, -1, 0));
  wall(Vec3(0.5, 7, half), Vec3(-half - 0.5, 7, 0));
  wall(Vec3(0.5, 7, half), Vec3(half + 0.5, 7, 0));
  wall(Vec3(half, 7, 0.5), Vec3(0, 7, -half - 0.5));
  wall(Vec3(half, 7, 0.5), Vec3(0, 7, half + 0.5));
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> size(0.3, 0.42), jitter(-0.05, 0.05), unit(-1, 1);
  for (int i = 0; i < n; ++i) {
    const int col = i % (side * side), layer = i / (side * side);
    elan::SceneBody b;
    const Real r = Real(size(rng));
    switch (i % 4) {
      case 0:
        b.shape.type = elan::ShapeType::Box;
        b.shape.half_extents = Vec3(r, Real(size(rng)), Real(size(rng)));
        break;
      case 1:
        b.shape.type = elan::ShapeType::Sphere;
        b.shape.radius = r;
        break;
      case 2:
        b.shape.type = elan::ShapeType::Capsule;
        b.shape.radius = r * Real(0.6);
        b.shape.half_height = r * Real(0.5);
        break;
      default:
        b.shape.type = elan::ShapeType::ConvexHull;
        for (int k = 0; k < 10; ++k) {
          Vec3 d(Real(unit(rng)), Real(unit(rng)), Real(unit(rng)));
          b.shape.points.push_back(d.normalized() * r);
        }
        break;
    }
    b.body.position =
        Vec3(Real(-0.55 * side + 0.55 + 1.1 * (col % side) + jitter(rng)), Real(0.6 + 1.1 * layer),
             Real(-0.55 * side + 0.55 + 1.1 * (col / side) + jitter(rng)));
    b.body.orientation =
        elan::Quat(Real(1), Real(unit(rng) * 0.1), Real(unit(rng) * 0.1), Real(unit(rng) * 0.1))
            .normalized();
    s.bodies.push_back(b);
  }
  return s;
}

// Indices of the highest dynamic bodies (the tops of pyramids and towers) at the start.
std::vector<std::size_t> top_bodies(const elan::Scene& s) {
  Real top = -std::numeric_limits<Real>::infinity();
  for (const auto& b : s.bodies)
    if (b.body.motion == elan::MotionType::Dynamic) top = std::max(top, b.body.position.y());
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < s.bodies.size(); ++i)
    if (s.bodies[i].body.motion == elan::MotionType::Dynamic &&
        s.bodies[i].body.position.y() > top - Real(1e-3))
      out.push_back(i);
  return out;
}

// How far the top moved, cm: horizontally (a toppled or sliding stack) and down. A stack built
// with vertical gaps (jolt_pyramid: 0.5 m between levels) settles by expected_drop_cm.
struct TopMotion {
  double drift_cm = 0, drop_cm = 0;
};
template <class PositionOf>
TopMotion top_motion(const elan::Scene& s, const std::vector<std::size_t>& tops, PositionOf pos) {
  TopMotion m;
  for (std::size_t i : tops) {
    const Vec3 d = pos(i) - s.bodies[i].body.position;
    m.drift_cm = std::max(m.drift_cm, 100 * std::hypot(double(d.x()), double(d.z())));
    m.drop_cm = std::max(m.drop_cm, -100 * double(d.y()));
  }
  return m;
}

// Expected settling of the top of a stack of box levels: its height minus the solid height of
// the distinct box levels below it (each level counted once, as pyramids and towers are built).
double expected_drop_cm(const elan::Scene& s, const std::vector<std::size_t>& tops) {
  if (tops.empty()) return 0;
  std::map<double, double> levels;  // centre y -> half height of the boxes there
  double floor = std::numeric_limits<double>::infinity();
  for (const auto& b : s.bodies) {
    if (b.body.motion != elan::MotionType::Dynamic) continue;
    if (b.shape.type != elan::ShapeType::Box) return 0;
    const double y = b.body.position.y(), h = b.shape.half_extents.y();
    levels[y] = h;
    floor = std::min(floor, y - h);
  }
  double solid = 0;
  for (const auto& [y, h] : levels) solid += 2 * h;
  const auto& top = s.bodies[tops.front()];
  const double top_y = top.body.position.y(), top_h = top.shape.half_extents.y();
  return std::max(0.0, 100 * (top_y + top_h - floor - solid));
}

// The farthest any dynamic body went from its start, m: a joint scene that blew up (bodies flung
// away, a chain torn apart) shows here, where its timing alone would not.
template <class PositionOf>
double max_move_m(const elan::Scene& s, PositionOf pos) {
  double most = 0;
  for (std::size_t i = 0; i < s.bodies.size(); ++i)
    if (s.bodies[i].body.motion == elan::MotionType::Dynamic)
      most = std::max(most, double((pos(i) - s.bodies[i].body.position).norm()));
  return most;
}

// The state hash after warm-up + steps must be one value whatever the thread count, broadphase
// and repetition; the first run of a (scene, step count) sets it, every later run is checked.
struct HashBook {
  std::map<std::string, uint64_t> expected;
  bool check(const std::string& key, uint64_t hash) {
    auto [it, inserted] = expected.emplace(key, hash);
    return inserted || it->second == hash;
  }
};

struct Case {
  std::string name;  // scene name, also the hash key's stem
  std::shared_ptr<const elan::Scene> scene;
  int warmup, steps;
};

void set_hash_counters(benchmark::State& state, uint64_t hash) {
  // Counters are doubles: the 64-bit hash goes in two exact 32-bit halves (and the label).
  state.counters["hash_hi"] = double(hash >> 32);
  state.counters["hash_lo"] = double(hash & 0xffffffffu);
  char label[32];
  std::snprintf(label, sizeof label, "hash=%016llx", static_cast<unsigned long long>(hash));
  state.SetLabel(label);
}

// One timed run of a scene: a fresh world, `warmup` steps, then `steps` timed.
struct ElanRun {
  double seconds = 0;
  elan::StepProfile sum;  // per-stage ms, summed over the timed steps
  elan::StepStats last;
  uint64_t hash = 0;
  TopMotion moved;
  double max_move_m = 0;
};

ElanRun run_elan(const Case& c, int threads, elan::BroadphaseType bp,
                 const std::vector<std::size_t>& tops) {
  tbb::task_arena arena(threads);
  ElanRun r;
  arena.execute([&] {
    elan::WorldDef def = c.scene->world;
    def.threads = threads;
    def.broadphase = bp;
    elan::World world(def);
    elan::load_into(*c.scene, world, c.name);
    for (int i = 0; i < c.warmup; ++i) world.step(c.scene->timestep);
    elan::StepProfile& sum = r.sum;
    const auto t0 = Clock::now();
    for (int i = 0; i < c.steps; ++i) {
      world.step(c.scene->timestep);
      const elan::StepProfile& p = world.last_step().profile;
      sum.bounds += p.bounds, sum.pairs += p.pairs, sum.collide += p.collide;
      sum.islands += p.islands, sum.split += p.split, sum.packets += p.packets;
      sum.color += p.color, sum.bundles += p.bundles, sum.prepare += p.prepare;
      sum.solve += p.solve, sum.ccd += p.ccd, sum.finalize += p.finalize, sum.total += p.total;
    }
    r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    r.last = world.last_step();
    r.hash = world.state_hash();
    const auto position = [&](std::size_t i) { return world.position(world.body_at(i)); };
    r.moved = top_motion(*c.scene, tops, position);
    if (!c.scene->joints.empty()) r.max_move_m = max_move_m(*c.scene, position);
  });
  return r;
}

std::string hash_key(const Case& c) {
  return c.name + "/" + std::to_string(c.warmup) + "+" + std::to_string(c.steps);
}

void bm_elan(benchmark::State& state, Case c, int threads, elan::BroadphaseType bp,
             HashBook* book) {
  const auto tops = top_bodies(*c.scene);
  ElanRun r;
  for (auto _ : state) {
    r = run_elan(c, threads, bp, tops);
    state.SetIterationTime(r.seconds);
    state.counters["ms_per_step"] = 1000 * r.seconds / c.steps;
  }
  const double n = c.steps;
  state.counters["bounds_ms"] = r.sum.bounds / n;
  state.counters["pairs_ms"] = r.sum.pairs / n;
  state.counters["collide_ms"] = r.sum.collide / n;
  state.counters["islands_ms"] = r.sum.islands / n;
  state.counters["split_ms"] = r.sum.split / n;
  state.counters["packets_ms"] = r.sum.packets / n;
  state.counters["color_ms"] = r.sum.color / n;
  state.counters["bundles_ms"] = r.sum.bundles / n;
  state.counters["prepare_ms"] = r.sum.prepare / n;
  state.counters["solve_ms"] = r.sum.solve / n;
  state.counters["ccd_ms"] = r.sum.ccd / n;
  state.counters["finalize_ms"] = r.sum.finalize / n;
  state.counters["total_ms"] = r.sum.total / n;
  state.counters["pairs"] = double(r.last.pairs);
  state.counters["contacts"] = double(r.last.contacts);
  state.counters["colors"] = double(r.last.colors);
  state.counters["awake"] = double(r.last.awake);
  state.counters["bodies"] = double(c.scene->bodies.size());
  state.counters["top_drift_cm"] = r.moved.drift_cm;
  state.counters["top_drop_cm"] = r.moved.drop_cm;
  state.counters["expected_drop_cm"] = expected_drop_cm(*c.scene, tops);
  if (!c.scene->joints.empty()) {
    state.counters["joints"] = double(c.scene->joints.size());
    state.counters["max_move_m"] = r.max_move_m;
  }
  state.SetItemsProcessed(int64_t(c.scene->bodies.size()) * c.steps * state.iterations());
  set_hash_counters(state, r.hash);
  if (!book->check(hash_key(c), r.hash))
    state.SkipWithError("state hash differs between runs of this scene");
}

// The paired benchmarks: a repetition runs two things back to back (1 and 2 threads; elan and
// Bullet) and reports their ratio. Load from other processes changes over minutes on this shared
// machine, and the two halves of a pair are seconds apart, so the median of the pairs' ratios
// follows the engines, where a ratio of two medians (runs minutes apart under random
// interleaving) also follows the load. The order alternates from one repetition to the next, so
// neither side always runs with a warm or a cold cache.
template <class A, class B>
void back_to_back(int& repetition, A&& a, B&& b) {
  if (repetition++ % 2 == 0) {
    a();
    b();
  } else {
    b();
    a();
  }
}

void bm_paired(benchmark::State& state, Case c, HashBook* book, std::shared_ptr<int> repetition) {
  const auto tops = top_bodies(*c.scene);
  const auto run = [&](int threads) {
    return run_elan(c, threads, elan::BroadphaseType::SweepAndPrune, tops);
  };
  for (auto _ : state) {
    ElanRun r1, r2;
    back_to_back(
        *repetition, [&] { r1 = run(1); }, [&] { r2 = run(2); });
    state.SetIterationTime(r1.seconds + r2.seconds);
    state.counters["ms_1t"] = 1000 * r1.seconds / c.steps;
    state.counters["ms_2t"] = 1000 * r2.seconds / c.steps;
    state.counters["speedup"] = r1.seconds / r2.seconds;
    if (!book->check(hash_key(c), r1.hash) || !book->check(hash_key(c), r2.hash))
      state.SkipWithError("state hash differs between runs of this scene");
  }
}

#ifdef ELAN_HAVE_BULLET
// One timed run of a scene in Bullet, as run_elan's.
struct BulletRun {
  double seconds = 0;
  elan::peer::BulletCounts counts;
  TopMotion moved;
  double max_move_m = 0;
  std::size_t joints_left = 0;
};

BulletRun run_bullet(const Case& c, const std::vector<std::size_t>& tops) {
  BulletRun r;
  elan::peer::BulletWorld world(*c.scene);
  for (int i = 0; i < c.warmup; ++i) world.step();
  const auto t0 = Clock::now();
  for (int i = 0; i < c.steps; ++i) world.step();
  r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  r.counts = world.counts();
  const auto position = [&](std::size_t i) { return world.position(i); };
  r.moved = top_motion(*c.scene, tops, position);
  if (!c.scene->joints.empty()) r.max_move_m = max_move_m(*c.scene, position);
  r.joints_left = world.joint_count();
  return r;
}

void bm_bullet(benchmark::State& state, Case c) {
  const auto tops = top_bodies(*c.scene);
  BulletRun r;
  for (auto _ : state) {
    r = run_bullet(c, tops);
    state.SetIterationTime(r.seconds);
    state.counters["ms_per_step"] = 1000 * r.seconds / c.steps;
  }
  state.counters["contacts"] = double(r.counts.contacts);
  state.counters["manifolds"] = double(r.counts.manifolds);
  state.counters["awake"] = double(r.counts.awake);
  state.counters["bodies"] = double(c.scene->bodies.size());
  state.counters["top_drift_cm"] = r.moved.drift_cm;
  state.counters["top_drop_cm"] = r.moved.drop_cm;
  state.counters["expected_drop_cm"] = expected_drop_cm(*c.scene, tops);
  if (!c.scene->joints.empty()) {
    state.counters["joints"] = double(c.scene->joints.size());
    state.counters["joints_left"] = double(r.joints_left);
    state.counters["max_move_m"] = r.max_move_m;
  }
  state.SetItemsProcessed(int64_t(c.scene->bodies.size()) * c.steps * state.iterations());
}

// elan at 1 thread and Bullet back to back (back_to_back).
void bm_paired_bullet(benchmark::State& state, Case c, HashBook* book,
                      std::shared_ptr<int> repetition) {
  const auto tops = top_bodies(*c.scene);
  for (auto _ : state) {
    ElanRun e;
    BulletRun b;
    back_to_back(
        *repetition, [&] { e = run_elan(c, 1, elan::BroadphaseType::SweepAndPrune, tops); },
        [&] { b = run_bullet(c, tops); });
    state.SetIterationTime(e.seconds + b.seconds);
    state.counters["ms_1t"] = 1000 * e.seconds / c.steps;
    state.counters["ms_bullet"] = 1000 * b.seconds / c.steps;
    state.counters["bullet_ratio"] = b.seconds / e.seconds;
    if (!book->check(hash_key(c), e.hash))
      state.SkipWithError("state hash differs between runs of this scene");
  }
}
#endif

// Heap bytes in use (glibc mallinfo2: small-chunk arena plus mmapped blocks).
double heap_in_use() {
  const struct mallinfo2 m = mallinfo2();
  return double(m.uordblks + m.hblkhd);
}

// Heap held by a live world after warm-up + steps, per body: what the engine keeps, the scene
// description (held by the benchmark for both engines) excluded.
void bm_memory(benchmark::State& state, Case c, bool bullet) {
  double per_body = 0;
  elan::detail::MemoryUse use;
  for (auto _ : state) {
    const double before = heap_in_use();
    double after = before;
    if (bullet) {
#ifdef ELAN_HAVE_BULLET
      elan::peer::BulletWorld world(*c.scene);
      for (int i = 0; i < c.warmup + c.steps; ++i) world.step();
      after = heap_in_use();
#endif
    } else {
      elan::WorldDef def = c.scene->world;
      def.threads = 1;
      elan::World world(def);
      elan::load_into(*c.scene, world, c.name);
      for (int i = 0; i < c.warmup + c.steps; ++i) world.step(c.scene->timestep);
      after = heap_in_use();
      use = elan::detail::memory_use(elan::detail::state_of(world));
    }
    per_body = (after - before) / double(c.scene->bodies.size());
    state.SetIterationTime(1e-3);
  }
  state.counters["heap_bytes_per_body"] = per_body;
  state.counters["bodies"] = double(c.scene->bodies.size());
  if (!bullet) {
    // Where elan's bytes are (buffer capacities, allocator overhead not included).
    const double n = double(c.scene->bodies.size());
    state.counters["mem_bodies"] = double(use.bodies) / n;
    state.counters["mem_shapes"] = double(use.shapes) / n;
    state.counters["mem_broadphase"] = double(use.broadphase) / n;
    state.counters["mem_contacts"] = double(use.contacts) / n;
    state.counters["mem_solver"] = double(use.solver) / n;
    state.counters["mem_api"] = double(use.api) / n;
    state.counters["mem_scratch"] = double(use.scratch) / n;
  }
}

// Calibration kernels: the same total work split into kChunks independent pieces, run in an
// arena of 1 or 2 threads; the 2-thread speedup of each is the ceiling this machine allows now.
constexpr int kChunks = 64;

// Seconds for the FMA kernel in an arena of `threads`.
double run_fma(int threads) {
  tbb::task_arena arena(threads);
  std::vector<float> out(kChunks);
  const auto t0 = Clock::now();
  arena.execute([&] {
    tbb::parallel_for(0, kChunks, [&](int c) {
      // 16 independent FMA chains keep the FMA units busy without touching memory.
      float acc[16];
      for (int k = 0; k < 16; ++k) acc[k] = float(c + k) * 1e-3f;
      for (int it = 0; it < 200000; ++it)
        for (int k = 0; k < 16; ++k) acc[k] = std::fma(acc[k], 0.999999f, 1e-7f);
      float s = 0;
      for (float a : acc) s += a;
      out[std::size_t(c)] = s;
    });
  });
  benchmark::DoNotOptimize(out.data());
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void bm_calib_fma(benchmark::State& state, int threads) {
  for (auto _ : state) state.SetIterationTime(run_fma(threads));
}

// The FMA ceiling measured as bm_paired measures a scene: 1 and 2 threads back to back.
void bm_paired_fma(benchmark::State& state, std::shared_ptr<int> repetition) {
  for (auto _ : state) {
    double t1 = 0, t2 = 0;
    back_to_back(
        *repetition, [&] { t1 = run_fma(1); }, [&] { t2 = run_fma(2); });
    state.SetIterationTime(t1 + t2);
    state.counters["ms_1t"] = 1000 * t1;
    state.counters["ms_2t"] = 1000 * t2;
    state.counters["speedup"] = t1 / t2;
  }
}

void bm_calib_stream(benchmark::State& state, int threads, std::vector<float>* a,
                     std::vector<float>* b) {
  tbb::task_arena arena(threads);
  const std::size_t n = a->size(), chunk = n / kChunks;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    arena.execute([&] {
      tbb::parallel_for(0, kChunks, [&](int c) {
        float* __restrict pb = b->data() + std::size_t(c) * chunk;
        const float* __restrict pa = a->data() + std::size_t(c) * chunk;
        for (std::size_t i = 0; i < chunk; ++i) pb[i] = pa[i] * 1.0001f + pb[i];
      });
    });
    benchmark::DoNotOptimize(b->data());
    state.SetIterationTime(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  state.SetBytesProcessed(int64_t(3 * n * sizeof(float)) * state.iterations());
}

// The shape type a `scene:kind` name selects (the scene format's type names).
elan::ShapeType kind_of(const std::string& name, const std::string& kind) {
  if (const std::optional<elan::ShapeType> type = elan::shape_type_from_name(kind)) return *type;
  std::fprintf(stderr, "bench_scenes: %s: no such kind of body '%s'\n", name.c_str(), kind.c_str());
  std::exit(2);
}

// A scene of scenes/ by name. `scene:kind` (heightfield_rain:box) keeps the scene's bodies that do
// not move and its moving bodies of that shape type only, so that what one kind of body costs
// against a surface, in both engines, is measured apart from the rest of the scene.
std::shared_ptr<const elan::Scene> load(const std::string& name, bool allow_sleep = true) {
  const auto colon = name.find(':');
  const std::string file = name.substr(0, colon);
  elan::Scene scene = elan::load_scene(std::string(ELAN_SCENE_DIR) + "/" + file + ".json");
  if (!allow_sleep) scene.world.allow_sleep = false;
  if (colon != std::string::npos) {
    const elan::ShapeType kind = kind_of(name, name.substr(colon + 1));
    if (!scene.joints.empty()) {
      std::fprintf(stderr, "bench_scenes: %s: a scene with joints cannot be split by kind\n",
                   name.c_str());
      std::exit(2);
    }
    std::erase_if(scene.bodies, [kind](const elan::SceneBody& b) {
      return b.body.motion != elan::MotionType::Static && b.shape.type != kind;
    });
  }
  return std::make_shared<const elan::Scene>(std::move(scene));
}

void register_all(const Options& o, HashBook* book, std::vector<float>* a, std::vector<float>* b) {
  for (int t : {1, 2}) {
    benchmark::RegisterBenchmark(("calib/fma/threads:" + std::to_string(t)).c_str(), bm_calib_fma,
                                 t)
        ->UseManualTime()
        ->Iterations(3)
        ->Repetitions(o.calib_reps)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("calib/stream/threads:" + std::to_string(t)).c_str(),
                                 bm_calib_stream, t, a, b)
        ->UseManualTime()
        ->Iterations(3)
        ->Repetitions(o.calib_reps)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("paired/calib/fma", bm_paired_fma, std::make_shared<int>(0))
      ->UseManualTime()
      ->Iterations(1)
      ->Repetitions(o.calib_reps)
      ->Unit(benchmark::kMillisecond);
  const auto add = [&](const std::string& name, auto fn, int reps, auto... args) {
    benchmark::RegisterBenchmark(name.c_str(), fn, args...)
        ->UseManualTime()
        ->Iterations(1)
        ->Repetitions(reps)
        ->Unit(benchmark::kMillisecond);
  };
  for (const auto& name : o.scenes) {
    const Case c{name, load(name), o.warmup, o.steps};
    for (int t : {1, 2})
      add("elan/" + name + "/threads:" + std::to_string(t), bm_elan, o.reps, c, t,
          elan::BroadphaseType::SweepAndPrune, book);
    if (std::find(o.no_sleep.begin(), o.no_sleep.end(), name) != o.no_sleep.end()) {
      const Case awake{name + "-no-sleep", load(name, false), o.warmup, o.steps};
      for (int t : {1, 2})
        add("elan/" + awake.name + "/threads:" + std::to_string(t), bm_elan, o.reps, awake, t,
            elan::BroadphaseType::SweepAndPrune, book);
#ifdef ELAN_HAVE_BULLET
      if (o.bullet) add("bullet/" + awake.name, bm_bullet, o.reps, awake);
#endif
    }
    // The scenes of the speedup targets (and of the README's): their 2-thread speedup paired too.
    if (name == "jolt_pyramid" || name == "pile4k" || name == "pile10k")
      add("paired/elan/" + name, bm_paired, o.reps, c, book, std::make_shared<int>(0));
#ifdef ELAN_HAVE_BULLET
    if (o.bullet) add("bullet/" + name, bm_bullet, o.reps, c);
    // The scene of the against-Bullet target: the ratio paired too.
    if (o.bullet && name == "pile4k")
      add("paired-bullet/" + name, bm_paired_bullet, o.reps, c, book, std::make_shared<int>(0));
#endif
  }
  for (const auto& name : o.joint_scenes) {
    const Case c{name, load(name), o.joint_warmup, o.joint_steps};
    for (int t : {1, 2})
      add("elan/" + name + "/threads:" + std::to_string(t), bm_elan, o.reps, c, t,
          elan::BroadphaseType::SweepAndPrune, book);
#ifdef ELAN_HAVE_BULLET
    if (o.bullet) {
      add("bullet/" + name, bm_bullet, o.reps, c);
      add("paired-bullet/" + name, bm_paired_bullet, o.reps, c, book, std::make_shared<int>(0));
    }
#endif
  }
  for (const auto& name : o.geometry_scenes) {
    const Case c{name, load(name), o.geometry_warmup, o.geometry_steps};
    for (int t : {1, 2})
      add("elan/" + name + "/threads:" + std::to_string(t), bm_elan, o.reps, c, t,
          elan::BroadphaseType::SweepAndPrune, book);
#ifdef ELAN_HAVE_BULLET
    if (o.bullet) {
      add("bullet/" + name, bm_bullet, o.reps, c);
      add("paired-bullet/" + name, bm_paired_bullet, o.reps, c, book, std::make_shared<int>(0));
    }
#endif
  }
  for (int n : o.sweep) {
    const Case c{"pile_n" + std::to_string(n), std::make_shared<const elan::Scene>(make_pile(n)),
                 o.sweep_warmup, o.sweep_steps};
    const std::string tail = "/N:" + std::to_string(n);
    for (int t : {1, 2}) {
      const std::string th = "/threads:" + std::to_string(t);
      add("sweep/sap" + tail + th, bm_elan, o.sweep_reps, c, t, elan::BroadphaseType::SweepAndPrune,
          book);
      if (n <= o.allpairs_max)
        add("sweep/all-pairs" + tail + th, bm_elan, o.sweep_reps, c, t,
            elan::BroadphaseType::AllPairs, book);
    }
#ifdef ELAN_HAVE_BULLET
    if (o.bullet) add("sweep/bullet" + tail, bm_bullet, o.sweep_reps, c);
#endif
  }
  if (std::find(o.scenes.begin(), o.scenes.end(), "pile10k") != o.scenes.end()) {
    const Case c{"pile10k", load("pile10k"), o.warmup, o.steps};
    add("memory/elan/pile10k", bm_memory, 1, c, false);
#ifdef ELAN_HAVE_BULLET
    if (o.bullet) add("memory/bullet/pile10k", bm_memory, 1, c, true);
#endif
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse_options(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  HashBook book;
  // 2 x 64 MiB: well beyond the last-level cache, so the stream kernel measures DRAM bandwidth.
  std::vector<float> a(std::size_t(16) << 20, 1.0f), b(std::size_t(16) << 20, 2.0f);
  register_all(options, &book, &a, &b);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
