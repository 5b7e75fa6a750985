// SPDX-License-Identifier: MIT
// Joint constraints of the soft step (Box2D v3's joint.c and solver.c, Catto 2024): prepared once
// a step, then in every substep warm started, solved with the soft bias and relaxed without it,
// in the same passes as the contacts and before them (a joint's rows see the contacts' last
// impulses and the contacts see the joints' new ones, as in Box2D).
//
// Rows are split by the halves of split_halves like the contacts: a joint whose awake bodies are
// all in one half is solved by that half's thread, one across the cut after both halves. Within a
// group joints are solved one after another in joint order (Gauss-Seidel), so the result depends
// on the joint order and the halves, never on the thread count.
//
// Angles and frames: each joint keeps a frame per body whose x axis is the joint axis. With
// rel = conj(q_b f_b) q_a f_a (A's joint frame in B's), the hinge angle and the cone twist are
// 2 atan2(rel.x, rel.w), the cone swing the angle of rel x from x, and the orientation lock's
// error the rotation vector 2 rel.xyz (small-angle), in world coordinates.
#pragma once

#include <cstdint>
#include <span>

#include "core/base/body_store.hpp"
#include "solver/joint_rows.hpp"
#include "solver/joint_store.hpp"
#include "solver/solve.hpp"

namespace elan::detail {

// The island links of the joints (JointLink per joint, dense body indices). Reads the store and
// the body slots' indices. Writes `links` (resized, no allocation once grown).
void joint_links(const JointStore& joints, std::span<const uint32_t> slot_index,
                 std::vector<JointLink>& links);

// Joint rows prepared (and stored back) per block of the parallel loops.
inline constexpr std::size_t kJointPrepareGrain = 256;

// The stage after load_packets: the rows of the joints with an awake dynamic body, group by group
// (SolverState::joint_rows, joint_group_start). Reads the store, the bodies' poses, the packets.
void prepare_joints(const BodyStore& bodies, const JointStore& joints,
                    std::span<const uint32_t> slot_index, const SolveSettings& settings,
                    SolverState& state);

struct JointSolverContext {
  std::span<SolverBody> bodies;  // packets
  std::span<const SolverBodyMass> masses;
  uint32_t written_end = 1;  // packets [1, written_end) are written
  Real h = 0, inv_h = 0;
};
JointSolverContext make_joint_context(const SolveSettings& settings, SolverState& state);

// The passes over rows [begin, end) of SolverState::joint_rows. refresh_joints re-reads the
// packets' pose changes and inverse inertias after the positions moved (the relax pass, before
// any other pass over the rows), as refresh_contacts does for the contacts.
void refresh_joints(const JointSolverContext& ctx, std::span<JointRow> rows);
void warm_start_joints(const JointSolverContext& ctx, std::span<JointRow> rows);
void solve_joints(const JointSolverContext& ctx, std::span<JointRow> rows, bool use_bias);

// After the solve, in parallel blocks of rows (`broke`: a flag per row, scratch): copies each
// row's impulses back into the store, and sets each joint's force
// and torque on A (the last substep's impulses over the substep time). Appends the dense indices
// of joints whose force exceeds their break_force to `broken`, in row order (group by group).
void store_joint_impulses(std::span<const JointRow> rows, const JointSolverContext& ctx,
                          JointStore& joints, std::vector<uint8_t>& broke,
                          std::vector<uint32_t>& broken);

// The joint's coordinate (JointDef: hinge angle, cone twist, slider position, distance) for
// bodies at poses (c_a, q_a) and (c_b, q_b): centres of mass and principal frames (for the
// world: the origin and identity).
Real joint_coordinate(const Joint& joint, const Vec3& c_a, const Quat& q_a, const Vec3& c_b,
                      const Quat& q_b);

}  // namespace elan::detail
