// SPDX-License-Identifier: MIT
// WorldState: everything a World owns, laid out as the step's stages read and write it.
#pragma once

#include <tbb/task_arena.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "broadphase/bounds.hpp"
#include "broadphase/find_pairs.hpp"
#include "core/base/body_store.hpp"
#include "core/base/contact.hpp"
#include "core/base/shape.hpp"
#include "core/base/step_scratch.hpp"
#include "core/world/api_state.hpp"
#include "core/world/query_tree.hpp"
#include "elan/defs.hpp"
#include "elan/profile.hpp"
#include "narrowphase/collide.hpp"
#include "solver/joint_store.hpp"
#include "solver/solve.hpp"
#include "solver/solver_kernels.hpp"

namespace elan::detail {

struct CallLog;  // core/world/recorder_hooks.hpp

inline constexpr Real kSpeculativeDistance = Real(0.02);
// Margin added to every bounding box, m: two boxes this far out overlap whenever their shapes are
// within 2.5 cm, a quarter more than the speculative distance. The boxes are rebuilt every step
// and swept over the step's motion and turn (compute_bounds), so pairs that close faster are
// found by the sweep, and nothing else needs slack. perf: a wider margin finds more pairs for the
// same manifolds, and a pair found apart still costs a cache check.
inline constexpr Real kBoundsMargin = Real(0.625) * kSpeculativeDistance;

struct WorldState {
  WorldDef def;
  int threads = 1;  // resolved worker count
  std::unique_ptr<tbb::task_arena> arena;

  BodyStore bodies;
  std::vector<Shape> shapes;

  // Ids: slot -> dense index and generation; freed slots are reused last-freed first.
  std::vector<uint32_t> slot_index;
  std::vector<uint32_t> slot_generation;
  std::vector<uint32_t> free_slots;

  // Per-step buffers of the sweep, the collide stage and the solver, which are never in use at
  // once (StepScratch). Declared before the stages that take from it, so it is destroyed after.
  StepScratch scratch;
  // Broadphase. The boxes are the scratch's only for the sweep. The body kinds are written by the
  // bounds stage (BodyKindColumns).
  BoundsColumns bounds;
  std::vector<uint8_t> broad_kind;
  std::vector<uint8_t> is_plane;
  std::vector<uint8_t> idle;  // static or asleep: contacts carried (collide_pairs)
  AllPairs all_pairs;
  SweepAndPrune sap;
  TreePairs tree_pairs;
  // This step's pairs, sorted: the scratch's from the broadphase to the end of the collide stage,
  // which leaves the continuous stage its candidates in the separation list. memory: no pair list
  // is kept between steps.
  ScratchVector<uint64_t> pairs;
  // The deep-pair budget's flags (per pair, per block of pairs) and its count per body
  // (limit_deep_pairs, deep_pairs.hpp); kept so that a warm step does not allocate.
  std::vector<uint8_t> deep_pair;
  std::vector<uint8_t> deep_block;
  std::vector<uint32_t> deep_kept;
  // The bodies' inner balls, the broadphase's sieve of deep pairs and the candidates it keeps
  // (prepare_deep_sieve, add_deep_candidates).
  std::vector<DeepBall> deep_balls;
  DeepSieve deep_sieve;
  std::vector<uint64_t> deep_candidates;
  bool deep_sieved = false;    // this step's pairs went through the sieve
  std::size_t deep_taken = 0;  // deep pairs the sieve took this step
  bool deep_crowd = false;     // some body is crowded (deep_sieve.crowded())

  // Contacts kept from step to step (manifolds, the body pair cache, the separation cache),
  // which the collide stage rewrites, with what it changed (the contact events).
  ContactStore contacts;

  // Joints kept from step to step, and what the step derives from them: the island links, the
  // pair keys of the joints that keep their bodies from colliding (sorted; rebuilt when the
  // store's version moves), and the joints that broke in the step.
  JointStore joints;
  std::vector<JointLink> joint_links;
  std::vector<uint64_t> unconnected_pairs;
  uint64_t unconnected_version = UINT64_MAX;
  std::vector<uint32_t> broken_joints;
  // Some body carries kPlaced (placed by the API since the last step): the next step's solver
  // looks for their supports (prepare_bundle) and then clears every kPlaced.
  bool bodies_placed = false;
  // Some body carries kSeparating (solver/separating_mark.hpp): the step updates the marks and
  // caps the marked bodies' velocities; false in every scene without a spawn overlap.
  bool bodies_separating = false;

  SolverState solver;
  // The solver kernels of def.simd's path, chosen when the world is made (never null).
  const SolverKernels* kernels = nullptr;
  ApiState api;
  // Every body's box for the scene queries, kept in step by the API, and by the first query after
  // a step (fresh_query_tree): mutable, because that refit happens inside const queries.
  mutable QueryTree query;
  StepStats stats;
  uint32_t reported_status = 0;  // flags already reported once
  uint64_t step_count = 0;
  // The program recorder, when one is attached (elan/recorder.hpp): every recorded method
  // checks it first.
  std::shared_ptr<CallLog> recorder;
};

}  // namespace elan::detail
