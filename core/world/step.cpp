// One step: bounds, pairs, collide, islands and sleep, colour, prepare, substeps, restitution,
// continuous collision, finalize. Each stage is a function over the world's arrays; this file only
// orders them.
#include "core/world/step.hpp"

#include <chrono>

#include "core/world/continuous.hpp"
#include "core/world/events.hpp"
#include "narrowphase/collide.hpp"

namespace elan::detail {

namespace {

double ms_between(std::chrono::steady_clock::time_point a,
                  std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

BroadKind broad_kind(const BodyStore& b, std::size_t i) {
  switch (MotionType(b.motion[i])) {
    case MotionType::Static:
      return BroadKind::Static;
    case MotionType::Kinematic:
      return BroadKind::Kinematic;
    case MotionType::Dynamic:
      break;
  }
  return b.is_awake(i) && !(b.flags[i] & kFrozen) ? BroadKind::Awake : BroadKind::Sleeping;
}

}  // namespace

uint32_t run_step(WorldState& w, Real dt) {
  using clock = std::chrono::steady_clock;
  StepStats& stats = w.stats;
  BodyStore& bodies = w.bodies;
  const std::size_t n = bodies.size();
  const auto t0 = clock::now();

  w.scratch.begin_phase();
  w.bounds.take_from(w.scratch);
  compute_bounds(bodies, w.shapes, dt, kBoundsMargin, w.bounds);
  const auto t1 = clock::now();

  w.broad_kind.resize(n);
  w.is_plane.resize(n);
  w.idle.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const BroadKind kind = broad_kind(bodies, i);
    w.broad_kind[i] = uint8_t(kind);
    w.is_plane[i] = w.shapes[bodies.shape[i]].type == ShapeType::Plane;
    // Static, or asleep (a frozen body is out of the simulation and keeps no contacts).
    w.idle[i] =
        kind == BroadKind::Static || (kind == BroadKind::Sleeping && !(bodies.flags[i] & kFrozen));
  }
  BroadphaseInput input{&w.bounds, w.broad_kind, bodies.traits, bodies.trait_table.entries(),
                        w.is_plane};
  take_from_back(w.pairs, w.scratch);
  if (w.def.broadphase == BroadphaseType::AllPairs) {
    w.all_pairs.find_pairs(input, w.pairs);
  } else {
    w.sap.find_pairs(input, w.pairs, w.scratch);
  }
  w.bounds.release();
  // The sweep's buffers are all back; the pair list, at the back, is held through the collide
  // stage, whose buffers start at the front again.
  w.scratch.rewind_front();
  filter_pairs(w);
  const auto t2 = clock::now();

  CollideSettings collide_settings;
  collide_settings.speculative_distance = kSpeculativeDistance;
  collide_settings.dt = dt;
  // The same phase of the scratch as the sweep's: the pair list is held through both.
  collide_pairs(w.pairs, bodies, w.shapes, collide_settings, w.idle, w.contacts, &w.scratch);
  stats.pairs = w.pairs.size();
  release(w.pairs);
  const auto t3 = clock::now();

  SolveSettings solve_settings;
  solve_settings.dt = dt;
  solve_settings.substeps = w.def.substeps;
  solve_settings.iterations = w.def.iterations;
  solve_settings.gravity = w.def.gravity;
  solve_settings.allow_sleep = w.def.allow_sleep;
  solve_settings.participants = w.threads;
  SolveStats solve_stats;
  w.scratch.begin_phase();
  prepare_solve(bodies, w.contacts.heads(), w.contacts.tails(), solve_settings, w.solver,
                solve_stats, w.scratch);
  const auto t4 = clock::now();
  solve(bodies, w.contacts.heads(), w.contacts.tails(), solve_settings, w.solver);
  // The body columns still hold the step's start poses: finalize_bodies writes the new ones.
  compute_contact_events(w, bodies);
  const auto t5 = clock::now();
  const ApartCandidates candidates = w.contacts.continuous_candidates();
  solve_continuous(bodies, w.shapes, candidates.separated, candidates.keys, w.solver);
  const auto t6 = clock::now();
  const uint32_t status = finalize_bodies(bodies, w.shapes, solve_settings, w.solver);
  const auto t7 = clock::now();

  stats.manifolds = w.contacts.size();
  // perf: counted by prepare_solve's pass over the list, not by one more (pile10k: 5 MB a step).
  stats.contacts = solve_stats.points;
  stats.awake = solve_stats.awake;
  stats.colors = solve_stats.colors;
  stats.overflow = solve_stats.overflow;
  stats.status = status;
  StepProfile& p = stats.profile;
  p.bounds = ms_between(t0, t1);
  p.pairs = ms_between(t1, t2);
  p.collide = ms_between(t2, t3);
  p.islands = solve_stats.islands_ms;
  p.color = solve_stats.color_ms;
  p.solve = ms_between(t4, t5);
  p.ccd = ms_between(t5, t6);
  p.finalize = ms_between(t6, t7);
  p.total = ms_between(t0, t7);
  ++w.step_count;
  return status;
}

}  // namespace elan::detail
