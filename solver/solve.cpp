// SPDX-License-Identifier: MIT
// The solver stages that run the prepared bundles: substeps, restitution, and the write-back.
#include "solver/solve.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "core/base/grow.hpp"
#include "core/base/parallel.hpp"
#include "elan/profile.hpp"
#include "solver/integrate.hpp"
#include "solver/joint_solver.hpp"
#include "solver/push_out_cap.hpp"

namespace elan::detail {
ELAN_ISA_BEGIN

namespace {

// Blocks of bodies for writing the results back.
constexpr uint32_t kBodyBlock = 128;

enum StageKind : uint32_t {
  kKinematicVelocities,
  kWarmStart,
  kSolve,
  kKinematicPositions,
  kRelax,
  kRestitution,
  kDirectBias,   // the direct solve of the loaded rows after the biased passes
  kDirectRelax,  // and after the relax pass
};

}  // namespace

ContactSolverContext make_solver_context(const SolveSettings& settings, SolverState& state) {
  ContactSolverContext ctx;
  ctx.bodies = state.packets;
  ctx.masses = state.masses;
  ctx.bundles = state.bundles;
  ctx.rows = state.rows;
  ctx.restitution = state.restitution;
  ctx.row_start = state.row_start;
  ctx.lane_manifolds = state.order;
  ctx.lane_start = state.lane_start;
  ctx.written_end = state.half_start[kHalves];
  ctx.h = settings.dt / Real(settings.substeps);
  ctx.inv_h = 1 / ctx.h;
  // Box2D v3: contact stiffness at most a quarter of the substep rate, twice as stiff against
  // static bodies (they do not give way).
  const Real hertz = std::min(settings.contact_hertz, Real(0.25) * ctx.inv_h);
  ctx.contact_softness = make_softness(hertz, settings.contact_damping_ratio, ctx.h);
  ctx.static_softness = make_softness(2 * hertz, settings.contact_damping_ratio, ctx.h);
  ctx.loaded_lanes = state.direct.loaded_lanes;
  ctx.contact_give = give_per_impulse(ctx.contact_softness);
  ctx.static_give = give_per_impulse(ctx.static_softness);
  ctx.sink_speed = kDirectGive / settings.dt;
  ctx.bodies_placed = settings.bodies_placed;
  ctx.bodies_separating = settings.bodies_separating;
  ctx.max_push_velocity = settings.max_push_velocity;
  ctx.restitution_threshold = settings.restitution_threshold;
  ctx.deep_count = state.deep_count;
  ctx.push_cap = state.push_cap;
  return ctx;
}

Real deep_contact_separation(const SolveSettings& settings) {
  const Real h = settings.dt / Real(settings.substeps);
  const Real hertz = std::min(settings.contact_hertz, Real(0.25) / h);
  const Softness soft = make_softness(hertz, settings.contact_damping_ratio, h);
  if (!(soft.bias_rate > 0)) return -std::numeric_limits<Real>::infinity();
  return -settings.max_push_velocity / soft.bias_rate;
}

void solve(const BodyStore& bodies, std::span<ManifoldHead> contacts, std::span<ManifoldTail> tails,
           const SolveSettings& settings, SolverState& st) {
  ContactSolverContext ctx = make_solver_context(settings, st);
  const JointSolverContext joint_ctx = make_joint_context(settings, st);

  // The schedule: every pass is a stage of the two halves (block h solves half h) and then, if
  // any contact crosses the cut, a stage of one block for those (partition.hpp): two syncs a
  // pass. The halves integrate their own packets in the stage before the pass that needs it.
  std::vector<StageSpec>& stages = st.stages;
  stages.clear();
  // The most stages a step can have (every pass cut, kinematic packets, a direct system), so
  // that a step bringing the first of these allocates nothing: per substep two kinematic
  // stages, the warm-start, solve and relax passes of two stages each, and two direct stages;
  // then the restitution pass.
  stages.reserve(std::size_t(settings.substeps) * (2 + 2 * (settings.iterations + 2) + 2) + 2);
  const bool cut = st.bundle_start[kSegments] > st.bundle_start[kCutGroup * kSegmentsPerGroup] ||
                   st.joint_group_start[kGroups] > st.joint_group_start[kCutGroup];
  const uint32_t packet_count = uint32_t(st.packets.size());
  const bool kinematic = packet_count > st.half_start[kHalves];
  auto add_pass = [&](StageKind kind) {
    stages.push_back({kHalves, kind, 0});
    if (cut) stages.push_back({1, kind, kCutGroup});
  };
  // Kinematic packets are read by the contacts of both halves, so they move in a stage of one
  // block between passes, never while a pass runs.
  auto add_kinematic = [&](StageKind kind) {
    if (kinematic) stages.push_back({1, kind, 0});
  };
  // The loaded rows' systems, solved directly after the passes of both halves and the cut
  // (direct_solve.hpp): a system may span the cut, so the stage's blocks are runs of systems,
  // not the halves. No system, no stage.
  const bool direct =
      build_direct_systems(ctx, contacts, st.joint_rows, kJointPrepareGrain, st.island_scratch.root,
                           st.island_scratch.size, st.direct);
  for (int s = 0; s < settings.substeps; ++s) {
    add_kinematic(kKinematicVelocities);
    add_pass(kWarmStart);  // halves: integrate velocities first
    for (int it = 0; it < settings.iterations; ++it) add_pass(kSolve);
    if (direct) stages.push_back({kDirectBlocks, kDirectBias, 0});
    // The bodies move; the relax pass first refreshes each bundle's arms and separations.
    add_kinematic(kKinematicPositions);
    add_pass(kRelax);  // halves: integrate positions first
    if (direct) stages.push_back({kDirectBlocks, kDirectRelax, 0});
  }
  // Restitution, then each bundle's impulses are final and stored.
  add_pass(kRestitution);

  const Real h = ctx.h;
  auto work = [&](const StageSpec& stage, uint32_t block) {
    if (stage.kind == kKinematicVelocities) {
      integrate_velocities(st.packets, st.masses, bodies, settings.gravity, h,
                           st.half_start[kHalves], packet_count);
      return;
    }
    if (stage.kind == kDirectBias || stage.kind == kDirectRelax) {
      solve_direct(ctx, st.joint_rows, stage.kind == kDirectBias, st.direct, block);
      return;
    }
    if (stage.kind == kKinematicPositions) {
      integrate_positions(st.packets, st.masses, bodies, h, st.half_start[kHalves], packet_count);
      return;
    }
    const uint32_t group = stage.arg == kCutGroup ? kCutGroup : block;
    const uint32_t begin = st.bundle_start[group * kSegmentsPerGroup];
    const uint32_t end = st.bundle_start[(group + 1) * kSegmentsPerGroup];
    const bool half = group < kHalves;
    const std::span<JointRow> joints(st.joint_rows.data() + st.joint_group_start[group],
                                     st.joint_group_start[group + 1] - st.joint_group_start[group]);
    switch (stage.kind) {
      case kWarmStart:
        if (half) {
          integrate_velocities(st.packets, st.masses, bodies, settings.gravity, h,
                               st.half_start[group], st.half_start[group + 1]);
        }
        warm_start_joints(joint_ctx, joints);
        warm_start_contacts(ctx, begin, end);
        break;
      case kSolve:
        solve_joints(joint_ctx, joints, true);
        solve_contacts(ctx, begin, end, true);
        break;
      case kRelax:
        if (half) {
          if (!st.capped.empty()) {
            cap_push_out_substep(bodies, settings, st, st.half_start[group],
                                 st.half_start[group + 1]);
          }
          integrate_positions(st.packets, st.masses, bodies, h, st.half_start[group],
                              st.half_start[group + 1]);
        }
        // perf: refreshing a bundle reads only the poses, which no constraint pass changes, and
        // writes only the bundle, so it is done in the relax pass rather than as a pass of its
        // own: one sweep of the bundles' memory and one sync fewer a substep.
        refresh_joints(joint_ctx, joints);
        refresh_contacts(ctx, bodies, contacts, tails, begin, end);
        solve_joints(joint_ctx, joints, false);
        solve_contacts(ctx, begin, end, false);
        break;
      case kRestitution:
        apply_restitution(ctx, begin, end);
        store_impulses(ctx, begin, end, contacts, tails);
        break;
      default:
        break;
    }
  };
  st.executor.run(stages, std::min(settings.participants, int(kHalves)), work);
}

uint32_t finalize_bodies(BodyStore& bodies, std::span<const Shape> shapes,
                         const SolveSettings& settings, SolverState& st) {
  const std::size_t n = bodies.size();
  // determinism: indexed writes per body; the non-finite flag is a per-block OR, combined in
  // block order below. perf: blocks of bodies, not of packets: the packets of a half are bodies
  // from all over the index range, so blocks of packets would have both threads writing the same
  // cache lines of the body columns.
  std::vector<uint8_t>& frozen_any = st.block_flags;
  frozen_any.assign(block_count(n, kBodyBlock) + 1, 0);
  for_blocks(n, kBodyBlock, [&](std::size_t begin, std::size_t end, std::size_t block) {
    for (std::size_t i = begin; i < end; ++i) {
      const uint32_t k = st.packet_of[i];
      if (k == 0) continue;
      const SolverBody& b = st.packets[k];
      const Vec3 p = bodies.position(i) + b.dp;
      const Quat q = (b.dq * bodies.orientation(i)).normalized();
      const bool finite =
          p.allFinite() && q.coeffs().allFinite() && b.v.allFinite() && b.w.allFinite();
      if (!finite) {
        // Quarantine: keep the last good pose, stop it, take it out of the simulation.
        bodies.set_linear_velocity(i, Vec3::Zero());
        bodies.set_angular_velocity(i, Vec3::Zero());
        bodies.flags[i] = uint8_t((bodies.flags[i] | kFrozen) & ~kAwake);
        frozen_any[block] = 1;
        continue;
      }
      bodies.set_position(i, p);
      bodies.set_orientation(i, q);
      bodies.set_linear_velocity(i, b.v);
      bodies.set_angular_velocity(i, b.w);
    }
  });
  // The forces applied for this step are spent on the bodies it moved (a quarantined one's too).
  bodies.drop_forces_if([&](uint32_t i) { return st.packet_of[i] != 0; });
  uint32_t status = 0;
  for (uint8_t f : frozen_any) status |= f ? uint32_t(kStepFrozeNonFinite) : 0u;
  if (settings.allow_sleep) {
    update_sleep_timers(bodies, shapes, settings.dt, settings.sleep_threshold);
  }
  if (st.segment_start.size() == kSegments + 1) {
    for (uint32_t g = 0; g < kGroups; ++g) {
      const uint32_t s = g * kSegmentsPerGroup + kColorCount;
      if (st.segment_start[s + 1] > st.segment_start[s]) status |= kStepColorOverflow;
    }
  }
  return status;
}

ELAN_ISA_END
}  // namespace elan::detail
