// SPDX-License-Identifier: MIT
// One step: bounds, pairs, collide, islands and sleep, the median cut, packets, colour, bundles,
// prepare (contacts, then joints), substeps and restitution, continuous collision, finalize. Each
// stage is a function over the world's arrays; this file orders and times them, and shows every
// scratch buffer that one stage leaves to another.
#include "core/world/step.hpp"

#include <chrono>

#include "core/world/continuous.hpp"
#include "core/world/deep_pairs.hpp"
#include "core/world/events.hpp"
#include "core/world/joints.hpp"
#include "core/world/sensors.hpp"
#include "narrowphase/collide.hpp"
#include "solver/bundles.hpp"
#include "solver/color_contacts.hpp"
#include "solver/joint_solver.hpp"
#include "solver/packets.hpp"
#include "solver/push_out_cap.hpp"
#include "solver/separating_mark.hpp"
#include "solver/solver_kernels.hpp"

namespace elan::detail {

namespace {

double ms_between(std::chrono::steady_clock::time_point a,
                  std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

uint32_t run_step(WorldState& w, Real dt) {
  using clock = std::chrono::steady_clock;
  StepStats& stats = w.stats;
  BodyStore& bodies = w.bodies;
  const std::size_t n = bodies.size();
  const auto t0 = clock::now();
  w.api.joint_events.clear();

  w.scratch.begin_phase();
  w.bounds.take_from(w.scratch);
  w.broad_kind.resize(n);
  w.is_plane.resize(n);
  w.idle.resize(n);
  compute_bounds(bodies, w.shapes, dt, kBoundsMargin, w.bounds, {w.broad_kind, w.is_plane, w.idle});
  const auto t1 = clock::now();

  BroadphaseInput input{&w.bounds, w.broad_kind, bodies.traits, bodies.trait_table.entries(),
                        w.is_plane};
  input.simd = w.kernels->path;
  // Bodies spawned into each other: the deep pairs go to the sieve (deep_pairs.hpp).
  input.deep = prepare_deep_sieve(w);
  take_from_back(w.pairs, w.scratch);
  if (w.def.broadphase == BroadphaseType::AllPairs) {
    w.all_pairs.find_pairs(input, w.pairs);
  } else if (w.def.broadphase == BroadphaseType::Tree) {
    w.tree_pairs.find_pairs(input, w.pairs);
  } else {
    w.sap.find_pairs(input, w.pairs, w.scratch);
  }
  w.bounds.release();
  // The sweep's buffers are all back; the pair list, at the back, is held through the collide
  // stage, whose buffers start at the front again.
  w.scratch.rewind_front();
  add_deep_candidates(w);
  filter_pairs(w);
  drop_jointed_pairs(w);
  // Sensors take no part in contact response: their pairs go to the overlap test after the step.
  divert_sensor_pairs(w);
  // Bodies spawned into each other: a bounded number of deep pairs each (deep_pairs.hpp).
  const std::size_t dropped_deep_pairs = limit_deep_pairs(w);
  const auto t2 = clock::now();

  CollideSettings collide_settings;
  collide_settings.speculative_distance = kSpeculativeDistance;
  collide_settings.dt = dt;
  collide_settings.deep_contacts = dropped_deep_pairs > 0 || w.deep_crowd;
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
  solve_settings.bodies_placed = w.bodies_placed;
  solve_settings.bodies_separating = w.bodies_separating;
  // The solver's phase of the scratch. Each stage takes and gives back its own buffers, but for
  // the bundles and their rows: build_bundles takes them, release_bundles gives them back.
  w.scratch.begin_phase();
  joint_links(w.joints, w.slot_index, w.joint_links);
  update_islands(bodies, w.contacts.heads(), w.joint_links,
                 {solve_settings.allow_sleep, solve_settings.time_to_sleep},
                 w.solver.island_scratch, w.scratch);
  const auto t_islands = clock::now();
  split_halves(bodies, w.solver, w.scratch);
  const auto t_split = clock::now();
  load_packets(bodies, w.solver, solve_settings.participants);
  const auto t_packets = clock::now();
  const ColorStats colors =
      color_contacts(bodies, w.contacts.heads(), w.contacts.tails(), w.solver, w.scratch,
                     solve_settings.participants, deep_contact_separation(solve_settings));
  // Which bodies' speeds the push-out cap bounds in this step (push_out_cap.hpp).
  find_capped(bodies, w.contacts.heads(), w.bodies_separating, w.solver);
  const auto t_color = clock::now();
  // Restitution inputs are kept only in a world that has something to bounce: on a pile of
  // inelastic bodies they would be read by a pass that finds nothing to do.
  build_bundles(w.contacts.heads(), bodies.trait_table.any_restitution(), w.solver, w.scratch);
  const auto t_bundles = clock::now();
  // The solver kernels of the world's SIMD path (solver/solver_kernels.hpp): chosen once.
  const SolverKernels& kernels = *w.kernels;
  kernels.prepare_contacts(bodies, w.contacts.heads(), w.contacts.tails(), solve_settings,
                           w.solver);
  prepare_joints(bodies, w.joints, w.slot_index, solve_settings, w.solver);
  const auto t4 = clock::now();
  kernels.solve(bodies, w.contacts.heads(), w.contacts.tails(), solve_settings, w.solver);
  // The push-out of bodies spawned into each other moves them; it is not kept as velocity
  // beyond the cap (push_out_cap.hpp) by the bodies marked as separating (separating_mark.hpp).
  w.bodies_separating = mark_separating(bodies, w.contacts.heads(), w.bodies_separating, w.solver);
  cap_push_out_velocity(bodies, w.shapes, solve_settings, w.solver);
  release_bundles(w.solver);
  if (!w.joints.empty()) {
    store_joint_impulses(w.solver.joint_rows, make_joint_context(solve_settings, w.solver),
                         w.joints, w.solver.joint_broke, w.broken_joints);
  }
  // The body columns still hold the step's start poses: finalize_bodies writes the new ones.
  compute_contact_events(w, bodies);
  const auto t5 = clock::now();
  const ApartCandidates candidates = w.contacts.continuous_candidates();
  // It reads only the query tree's static leaves, each its body's box grown by the margin, set by
  // the API's hooks (query_tree.cpp, place): no refit of the pending leaves, which are never
  // static, and the same candidates whenever the world was last queried.
  solve_continuous(bodies, w.shapes, candidates.separated, candidates.keys, w.contacts.heads(),
                   w.query.tree, w.solver, dt);
  const auto t6 = clock::now();
  const uint32_t status = kernels.finalize_bodies(bodies, w.shapes, solve_settings, w.solver);
  if (!w.broken_joints.empty()) remove_broken_joints(w);
  update_sensors(w);
  query_tree_after_step(w, dt);
  const auto t7 = clock::now();

  stats.manifolds = w.contacts.size();
  // perf: counted by color_contacts' pass over the list, not by one more.
  stats.contacts = colors.points;
  stats.awake = w.solver.simulated.size();
  stats.colors = colors.colors;
  stats.overflow = colors.overflow;
  stats.status = status;
  StepProfile& p = stats.profile;
  p.bounds = ms_between(t0, t1);
  p.pairs = ms_between(t1, t2);
  p.collide = ms_between(t2, t3);
  p.islands = ms_between(t3, t_islands);
  p.split = ms_between(t_islands, t_split);
  p.packets = ms_between(t_split, t_packets);
  p.color = ms_between(t_packets, t_color);
  p.bundles = ms_between(t_color, t_bundles);
  p.prepare = ms_between(t_bundles, t4);
  p.solve = ms_between(t4, t5);
  p.ccd = ms_between(t5, t6);
  p.finalize = ms_between(t6, t7);
  p.total = ms_between(t0, t7);
  if (w.bodies_placed) {
    // Placed before this step: from now on their contacts have warm impulses.
    for (uint8_t& f : bodies.flags) f &= uint8_t(~kPlaced);
    w.bodies_placed = false;
  }
  ++w.step_count;
  return status;
}

}  // namespace elan::detail
