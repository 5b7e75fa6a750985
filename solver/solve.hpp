// SPDX-License-Identifier: MIT
// The solver's settings and state, and the stages that run the prepared constraints: the
// substeps, restitution and impulse storage (solve), and writing results back (finalize_bodies).
// The stages before them, in run_step's order: update_islands (islands.hpp), split_halves and
// load_packets (packets.hpp), color_contacts (color_contacts.hpp), build_bundles and
// prepare_contacts (bundles.hpp).
//
// Parallel work runs in fixed blocks through the StageExecutor; all layouts depend on the scene
// alone.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/base/body_store.hpp"
#include "core/base/contact.hpp"
#include "core/base/isa.hpp"
#include "core/base/shape.hpp"
#include "core/base/step_scratch.hpp"
#include "solver/coloring.hpp"
#include "solver/contact_solver.hpp"
#include "solver/direct_solve.hpp"
#include "solver/islands.hpp"
#include "solver/joint_rows.hpp"
#include "solver/solver_types.hpp"
#include "solver/stage_executor.hpp"

namespace elan::detail {

struct SolveSettings {
  Real dt = Real(1.0 / 60.0);  // s
  int substeps = 4;
  // Solve passes per substep (relax is one more; Box2D v3 runs one and the relax). At 2 a base-20
  // pyramid of cubes (20 layers, four supports per cube) settles 1.5 cm at the top (0.4 cm at 4)
  // and sleeps within 2 s; a 2028-body mixed pile is asleep at 15 s (at 3 or 4 a few bodies keep
  // the whole pile awake). At 1 the pyramid's top sinks 4.3 cm and a 1000-body pile keeps
  // rattling (5 J at 15 s). perf: each pass is about a tenth of a pile's step.
  int iterations = 2;
  Vec3 gravity = Vec3(0, Real(-9.81), 0);
  bool allow_sleep = true;
  // Hz, capped at a quarter of the substep rate. A soft contact under a steady load W settles
  // at a penetration 2 W / (m omega^2) (m the body's mass, omega = 2 pi hertz), so a tower of N
  // equal cubes compresses g N (N - 1) / omega^2 in all: 4.5 cm for 20 cubes at 46 Hz, 5.9 cm at
  // 40 Hz. Much stiffer (60 Hz) lets a base-20 pyramid creep at 3 solver passes per substep.
  Real contact_hertz = 46;
  Real contact_damping_ratio = 10;
  Real max_push_velocity = 3;         // m/s
  Real restitution_threshold = 1;     // m/s
  Real sleep_threshold = Real(0.05);  // m/s
  Real time_to_sleep = Real(0.5);     // s
  int participants = 1;        // threads that may take part in the solve (at most kHalves are used)
  bool bodies_placed = false;  // some body carries kPlaced (body_store.hpp)
  bool bodies_separating = false;  // some body carries kSeparating (body_store.hpp)
};

// The solver's groups of contact constraints: those within half 0, within half 1 (both bodies
// on one side of the cut of partition.hpp, or one side static or kinematic), and across the cut.
// One thread solves a group; the two halves at once, the cut after both.
inline constexpr uint32_t kHalves = 2;
inline constexpr uint32_t kGroups = kHalves + 1;
inline constexpr uint32_t kCutGroup = kHalves;
// A group's colours and then its overflow are its segments: segment g * kSegmentsPerGroup + c.
inline constexpr uint32_t kSegmentsPerGroup = kColorCount + 1;
inline constexpr uint32_t kSegments = kGroups * kSegmentsPerGroup;

// A fast body's first impact in the step (the continuous stage): its packet and the time.
struct Impact {
  uint32_t packet = 0;
  Real t = 1;
};

struct SolverState {
  std::vector<uint32_t> packet_of;  // per body: its packet, 0 when not simulated
  std::vector<uint32_t> simulated;  // the awake dynamic bodies, ascending
  std::vector<uint8_t> side;        // per awake dynamic body: its half
  ScratchVector<uint64_t>
      split_keys;  // split_in_halves' keys, taken and given back by split_halves
  // Half h: packets [half_start[h], half_start[h + 1]); the kinematic bodies' follow.
  uint32_t half_start[kHalves + 1] = {1, 1, 1};
  std::vector<SolverBody> packets;  // 0 = static dummy; half 0, half 1, kinematic
  std::vector<SolverBodyMass> masses;
  // Contact indices that take part, group by group, and per candidate its packets as its group's
  // colouring sees them. These, order_scratch and the colourings' arrays are taken from the
  // step's scratch and given back within color_contacts; the bundles laid out next reuse the
  // bytes.
  ScratchVector<uint32_t> candidates;
  ScratchVector<ColorInput> color_input;
  uint32_t group_start[kGroups + 1] = {};  // group g: candidates [group_start[g], [g + 1])
  std::vector<uint32_t> order;             // contact indices, segment by segment
  std::vector<uint32_t> segment_start;     // segment s is order[segment_start[s], [s + 1])
  ScratchVector<uint32_t> order_scratch;
  // The bundles, their point rows and restitution inputs are taken from the step's scratch by
  // build_bundles and given back by release_bundles after solve(): between steps they are empty.
  ScratchVector<ContactBundle> bundles;  // segment by segment
  std::vector<uint32_t> row_start;       // bundle j's point rows are [row_start[j], row_start[j+1])
  std::vector<uint32_t> lane_start;      // bundle j's lanes are order[lane_start[j], [j + 1])
  ScratchVector<WideContactPoint> rows;
  ScratchVector<BundleRestitution> restitution;  // per bundle; empty when no body bounces
  std::vector<uint32_t> bundle_start;  // segment s is bundles[bundle_start[s], bundle_start[s+1])
  // The joints' rows, group by group (prepare_joints): group g is
  // joint_rows[joint_group_start[g], joint_group_start[g + 1]); joint_group is per joint.
  std::vector<JointRow> joint_rows;
  uint32_t joint_group_start[kGroups + 1] = {};
  std::vector<uint8_t> joint_group;
  std::vector<uint8_t> joint_broke;  // per row: broke in the step (store_joint_impulses)
  DirectState direct;                // the loaded rows' direct solve (direct_solve.hpp)
  ColorScratch color_scratch[kGroups];
  IslandScratch island_scratch;
  StageExecutor executor;
  std::vector<StageSpec> stages;
  std::vector<uint8_t> block_flags;  // per body block: went non-finite
  std::vector<uint8_t> fast;         // per packet: moved far for its size (continuous stage)
  std::vector<std::vector<Impact>> impacts;  // per thread (continuous stage)
  std::vector<Real> earliest_toi;
  // The push-out share (push_share in color_contacts.hpp): per packet, how many of its
  // manifolds are deep enough for the push-out cap to bind, and the most of any packet; per
  // bundle, its lanes' caps, m/s, kept only while some body has more than one such manifold.
  std::vector<uint32_t> deep_count;
  uint32_t most_deep = 0;
  std::vector<WideValue> push_cap;
  std::vector<uint8_t> separating;  // per packet: the step's new mark (separating_mark.hpp)
  // Per packet: its speed is capped in this step (find_capped, push_out_cap.hpp); empty when
  // no packet's is.
  std::vector<uint8_t> capped;
};

ELAN_ISA_BEGIN

// The separation below which a manifold between dynamic bodies pushes out at the cap,
// settings.max_push_velocity: where the soft spring's bias_rate * (-s) reaches it, m (negative).
Real deep_contact_separation(const SolveSettings& settings);

// The context the contact solver's functions read: the packets, bundles and rows of `state`.
ContactSolverContext make_solver_context(const SolveSettings& settings, SolverState& state);

// The substeps, restitution and impulse storage. Reads: the bundles and rows (prepare_contacts),
// the joint rows (prepare_joints), the bodies' poses. Writes: state.packets, the bundles, the
// joint rows, the contacts' impulses. Results stay in
// state.packets; the bundles stay taken (release_bundles).
void solve(const BodyStore& bodies, std::span<ManifoldHead> contacts, std::span<ManifoldTail> tails,
           const SolveSettings& settings, SolverState& state);

// Writes the packets back into the body columns; quarantines bodies whose state went non-finite
// (restored to the step's start pose, velocities zeroed, flagged frozen); updates sleep timers;
// clears applied forces. Returns StepStatus flags.
uint32_t finalize_bodies(BodyStore& bodies, std::span<const Shape> shapes,
                         const SolveSettings& settings, SolverState& state);

ELAN_ISA_END

}  // namespace elan::detail
