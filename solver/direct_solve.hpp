// SPDX-License-Identifier: MIT
// The direct solve of loaded rows: the normal rows of contacts and the point rows of joints that
// carry a load their soft spring would give under (s = lambda gamma / m_eff, see kDirectGive),
// face contacts only (three points or more), in islands of at most kDirectMaxBodies bodies,
// gathered into linear systems, one per connected set of bodies (but a lone manifold, see
// build_direct_systems), and solved exactly once per biased pass and once per relax pass of every
// substep, after the Gauss-Seidel passes.
//
// Why: a soft row is a spring on the row's effective mass m_eff, so it settles at a penetration
// F / (m_eff omega^2) under a load F. A tower's lower contacts carry many bodies' weight, a light
// box under a heavy one has m_eff of the light box, a light chain link holds the weight below:
// the give grows with the load over the row's own mass, and Gauss-Seidel, which moves the heavy
// body by m_eff / M of the error per pass, cannot carry the load through the light bodies within
// a few passes. Solved exactly (the seed's "linear systems for resting contact"), the rows are
// rigid: the velocity meets the target J v = -beta C (the soft step's bias rate beta, capped by
// max_push_velocity) with no spring compliance, whatever the masses, and the position error
// decays at rate beta. The rows that carry no such load stay in Gauss-Seidel: the direct solve is
// one block of a block Gauss-Seidel step over all rows.
//
// The system A lambda = b, A = J M^-1 J^T, is assembled in double in an envelope (skyline) and
// factored by Cholesky: rows are ordered by their manifold's key (bodies in index order: a tower
// or a pile's column is then a band) and joints by joint order (a chain is a band), so the
// factor has the envelope's fill only. A face's four points give three independent rows: a
// compliance of 1e-6 of each row's diagonal (on the whole impulse) makes the system definite and
// the split of a load between the points the least-squares one, and each manifold's biased
// targets are fitted by one plane, those of one rigid motion. Contacts are unilateral and their
// friction bounded: an active-set loop fixes at zero the normal rows whose impulse would turn
// negative, fixes on the cone the friction that would leave it (mu times the manifold's normal
// impulse; the twist within mu times the points' levers), and frees the separated rows the solution
// would violate (principal pivoting, a few rounds; in a resting stack the first set is right; a set
// that does not settle, or impulses far beyond the bodies' momentum, leave the passes' impulses
// standing). Friction is in the system because the normal rows move a light body's rotation, and a
// light body held by Gauss-Seidel friction between a heavy one and the ground would slide: its
// friction has the same mass ratio.
//
// Determinism: the systems are built serially in a fixed order (bundle order, then sorted by
// key), each solved by one thread in a stage of its own, in system order (rules 3 and 5).
// Memory: every buffer is a member kept between steps (grown, never shrunk within a step).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/base/contact.hpp"
#include "solver/contact_solver.hpp"
#include "solver/joint_rows.hpp"

namespace elan::detail {

// A row's soft spring gives s = lambda * gamma / m_eff under the impulse lambda it carries per
// substep, gamma = impulse_scale / (mass_scale * bias_rate) = 1 / (h omega^2) (the soft step's
// fixed point: 0 = -m_eff mass_scale (0 + bias_rate s) - impulse_scale lambda). Rows that would
// give more than this are solved directly. A single 0.5 m cube resting on another gives 0.2 mm;
// three cubes on it, 0.5 mm.
inline constexpr Real kDirectGive = Real(0.0005);  // m
// A joint's point rows are loaded past a larger give: a ragdoll heap's joints give a millimetre
// and hold (its limbs are not a load path), while a light chain under a heavy weight gives
// centimetres.
inline constexpr Real kDirectJointGive = Real(0.001);  // m
// A face contact of a body just placed (kPlaced), with no warm impulse, is solved directly if its
// bodies approach slower than this (prepare_bundle): a resting support, not an impact; about a
// step of gravity at 60 Hz and half the restitution threshold.
// Depth alone is no criterion: the direct solve is for resting load, not impacts. A body landing
// at speed v presses in by the overshoot of its soft row, about v / omega (0.5 m/s: 1.7 mm at
// 46 Hz; 14 m/s: 4.8 cm), whatever it weighs, so a depth threshold (a single body at rest already
// sits g / omega^2 deep, 0.1 mm at 46 Hz) takes every landing body's rows. They settle in the
// passes within a few steps, while in the direct solve the active set chases the bouncing,
// tumbling body and often does not settle, its work thrown away. A tower placed at rest, which
// sinks while Gauss-Seidel carries its weight up, is taken by the placed rule on its first step,
// and by its warm impulses (lambda gamma / m_eff > kDirectGive) from then on.
inline constexpr Real kDirectRestSpeed = Real(0.5);  // m/s
// A face pressed into a static or kinematic body deeper than this and sinking is solved directly
// too (prepare_bundle), even a lone manifold: a body sinking into a surface under a load its rows
// do not carry yet. Sinking: its patch centre still closes, faster than kDirectGive a step,
//   v_c = (1 / n) sum_k v_k < -kDirectGive / dt   (ContactSolverContext::sink_speed),
// v_k = n . (v_B(p_k) - v_A(p_k)) the points' relative normal velocities at the step's start
// (linear in the point, so their mean is the centre's), and no point closes faster than
// kDirectRestSpeed. The relax pass leaves rows that carry their load at v_n = 0, so a face that
// still closes by more than a loaded row may give within a step is one the passes did not hold.
// A landing's deep face is not sinking: in the step it strikes, it closes faster than
// kDirectRestSpeed (an impact), and in the steps after, its rows push it out (v_c > 0) or hold it
// (v_c about 0): the passes settle it. Two dynamic bodies that deep have met in an impact (a
// table's leg through another's top) or were spawned overlapping: the push-out, not a load.
// Three times the overshoot v / omega of a landing at kDirectRestSpeed.
inline constexpr Real kDirectDepth = Real(0.005);  // m
// A system of contacts only, none deep, of at most this many manifolds whose bodies' masses are
// within kDirectEvenMass of each other is left to Gauss-Seidel (build_direct_systems): a column
// of four even bodies on the ground, whose upper contacts carry three bodies' weight and give
// about kDirectGive (three 0.5 m cubes on one: 0.5 mm), the ground's a quarter of that under four
// (twice as stiff), while the passes carry the weight of so short a chain of even masses within
// a step or two. A light body under a heavy one, a taller column, a pyramid, or any joint, is
// solved directly as before.
inline constexpr uint32_t kDirectShortStack = 4;
inline constexpr Real kDirectEvenMass = 2;  // heaviest over lightest
// Systems with more rows are left to Gauss-Seidel: the envelope of a large pile is dense, and
// its factor would cost more than the passes it replaces.
inline constexpr uint32_t kDirectMaxRows = 640;
// Islands of more bodies are not looked at (a pile, a joint grid): they are left to
// Gauss-Seidel, and their rows not even gathered.
inline constexpr uint32_t kDirectMaxBodies = 96;
inline constexpr std::size_t kDirectMaxEnvelope = 64 * 1024;  // factor entries

// gamma of `loaded_give` for one softness, s (0 for a rigid or bias-free softness).
Real give_per_impulse(const Softness& s);

// What a row of a direct system is: a contact's normal row at one point, its friction at the
// manifold centre (two tangents and the twist, as the passes solve them), or a joint point row.
enum DirectRowKind : uint8_t {
  kDirectNormal,
  kDirectTangent0,
  kDirectTangent1,
  kDirectTwist,
  kDirectJoint,
};

// One row of a direct system. A manifold's rows are consecutive: its points' normal rows, then
// its two tangent rows and its twist row.
struct DirectRow {
  uint32_t source = 0;  // contact: the bundle; joint: the index in SolverState::joint_rows
  uint32_t head = 0;    // contact: the system's index of the manifold's first normal row
  uint8_t lane = 0;     // contact: the lane
  uint8_t point = 0;    // contact normal: the point; joint: the axis (x, y, z)
  uint8_t kind = kDirectNormal;
  uint8_t count = 0;           // contact: the manifold's points
  int32_t slot[2] = {-1, -1};  // the written packets of sides A and B (DirectState::packets)
};

// A system's rows and packets: rows [row_begin, row_end), packets [packet_begin, packet_end).
struct DirectSystem {
  uint32_t row_begin = 0, row_end = 0;
  uint32_t packet_begin = 0, packet_end = 0;
};

// One block's solve scratch, per row of the largest system and per slot: each block of the
// direct stage solves its own systems with its own (solve_direct).
struct DirectScratch {
  std::vector<double> jac, mjac;  // 12 a row: per side sigma (d, r x d), and M^-1 of it
  std::vector<double> target, lambda, rhs, delta, fixed, lever;
  std::vector<double> diagonal;         // A_ii, per row
  std::vector<double> velocity, trial;  // 6 a slot
  std::vector<uint32_t> active;
  std::vector<uint8_t> in_set;
  std::vector<int32_t> first, slot_first;
  std::vector<std::size_t> offset;
  std::vector<double> factor;
  std::vector<uint8_t> dependent;
  // A's envelope over all the system's rows, built once a pass (solve_direct): row i's entries
  // for rows [whole_first[i], i) from whole[whole_offset[i]]; whole_ready when it fit.
  std::vector<double> whole;
  std::vector<uint32_t> whole_first;
  std::vector<std::size_t> whole_offset;
  bool whole_ready = false;

  std::size_t heap_bytes() const {
    std::size_t sum = 0;
    auto add = [&](const auto& v) { sum += v.capacity() * sizeof(v[0]); };
    add(jac), add(mjac), add(target), add(lambda), add(rhs), add(delta), add(fixed), add(lever);
    add(diagonal);
    add(velocity), add(trial), add(active), add(in_set), add(first), add(slot_first);
    add(offset), add(factor), add(dependent), add(whole), add(whole_first), add(whole_offset);
    return sum;
  }
};

// The direct stage's blocks: the systems are dealt into this many runs of about equal rows, one a
// block of the stage. Systems share no written body, but two systems' rows can be lanes of one
// contact bundle, and a store into one lane of a SIMD vector may be a read-modify-write of the
// whole vector (clang at -O1 makes it one): blocks cut by rows alone raced on the bundle (the
// sanitized build's 2-thread hashes changed from run to run). So systems that share a bundle are
// dealt as a group, a group to one block (build_direct_systems).
inline constexpr uint32_t kDirectBlocks = 2;

// The loaded lanes' bits of DirectState::loaded_lanes; the deep lanes' are above them.
static_assert(2 * kLanes <= 32, "loaded_lanes: two bits a lane");
inline constexpr uint32_t kLaneBits = (uint32_t(1) << kLanes) - 1;

struct DirectState {
  // Per bundle (prepare_bundle): the lanes whose rows are loaded, a bit a lane (bits
  // [0, kLanes)), and of those the faces sinking into a static or kinematic body (kDirectDepth)
  // (bits [kLanes, 2 kLanes)).
  std::vector<uint32_t> loaded_lanes;
  // Per block of prepare_joints' loop: some row in it is loaded (JointRow kJointLoaded).
  std::vector<uint8_t> loaded_joint_blocks;
  std::vector<DirectSystem> systems;  // this step's
  // Block b of the direct stage solves systems [block_begin[b], block_begin[b + 1]).
  uint32_t block_begin[kDirectBlocks + 1] = {};
  std::vector<DirectRow> rows;
  std::vector<uint32_t> packets;  // system by system: the written packets
  // Build scratch.
  std::vector<uint64_t> items;  // (root << 32 | order) then the item's index in item_source
  std::vector<uint64_t> item_source;
  std::vector<uint32_t> parent;  // per packet (union-find)
  std::vector<int32_t> slot_of;  // per packet
  std::vector<uint32_t> order;   // the items sorted by key
  // Deal scratch: per bundle the first system on it (UINT32_MAX between steps); per system its
  // group's root (union-find), and at a root the group's rows, then its block; the systems in
  // block order.
  std::vector<uint32_t> system_of_bundle;
  std::vector<uint32_t> group;
  std::vector<uint64_t> group_rows;
  std::vector<DirectSystem> dealt;
  DirectScratch scratch[kDirectBlocks];

  // The bytes its buffers hold (the memory report).
  std::size_t heap_bytes() const {
    std::size_t sum = 0;
    auto add = [&](const auto& v) { sum += v.capacity() * sizeof(v[0]); };
    add(loaded_lanes), add(loaded_joint_blocks), add(systems), add(rows), add(packets);
    add(items), add(item_source), add(parent), add(slot_of), add(order);
    add(system_of_bundle), add(group), add(group_rows), add(dealt);
    for (const DirectScratch& w : scratch) sum += w.heap_bytes();
    return sum;
  }
};

// Serial, before the substeps: the loaded rows of islands (islands.hpp: `island_root` per body,
// `island_size` per root) of at most kDirectMaxBodies bodies, one system per set of them linked
// through their bodies, but for a set of one manifold that is not sinking (kDirectDepth; left to
// the passes: one contact's give is bounded by its bodies' weight; direct_solve.cpp) and a short
// stack of even masses (kDirectShortStack). Reads ds.loaded_lanes, ds.loaded_joint_blocks (block
// size `joint_grain`), the bundles' lanes and point counts, the joint rows' packets and flags.
// Returns whether any system is to be solved.
bool build_direct_systems(const ContactSolverContext& ctx, std::span<const ManifoldHead> contacts,
                          std::span<const JointRow> joints, std::size_t joint_grain,
                          std::span<const uint32_t> island_root,
                          std::span<const uint32_t> island_size, DirectState& ds);

// Solves every system of block `block` (< kDirectBlocks) once: `use_bias` the biased pass
// (targets -beta C), else the relax pass (targets 0; a speculative row may close its gap). The
// blocks may run at once: their systems share no written body. Reads and writes the packets'
// velocities, the rows' accumulated impulses (bundles, joint rows) and the restitution's largest
// impulses.
void solve_direct(ContactSolverContext& ctx, std::span<JointRow> joints, bool use_bias,
                  DirectState& ds, uint32_t block);

}  // namespace elan::detail
