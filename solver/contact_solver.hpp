// SPDX-License-Identifier: MIT
// Contact constraints of the soft step (Box2D v3 "solver2d" soft step, Catto 2024): prepare once
// per step, then per substep warm start, solve with bias, relax without bias; restitution and
// impulse storage once per step.
//
// Constraints are solved kLanes at a time (ContactBundle): the lanes of a bundle are constraints
// of one colour, so they touch distinct dynamic bodies and can be gathered, solved and scattered
// together. The overflow colour has one lane per bundle.
//
// Reads: manifolds, body packets and masses. Writes: constraint impulses and the packets of
// the dynamic bodies a constraint touches. Threading: the functions take a range of bundles; a
// caller runs ranges of one colour in parallel (no two constraints of a colour share a dynamic
// body), colours and the overflow one after another.
#pragma once

#include <cstdint>
#include <span>

#include "core/base/body_store.hpp"
#include "core/base/contact.hpp"
#include "core/base/isa.hpp"
#include "solver/solver_types.hpp"

namespace elan::detail {

// Radius of the contact patch that a point contact stands for, m: the twist friction of a
// manifold is at least mu * kTorsionPatch * sum(lambda_n). An ideal point contact has no
// torsional friction, so a sphere pinched between two bodies would spin about the normal for
// ever and keep its island awake; real contacts have a patch (MuJoCo's default torsional
// friction length is the same 5 mm).
inline constexpr Real kTorsionPatch = Real(0.005);

// The solver's tangent basis of each lane's normal: tangent_basis() across the lanes, the same
// operations in the same order. perf: derived in every pass, not kept in the bundle (12 bytes a
// lane): a compare and one division a bundle (Duff et al.'s basis needs no square root) cost
// less than streaming it. Unused lanes (zero normal) get the x and y axes, which move nothing:
// their masses are zero.
struct WideTangents {
  WideVec3 t0, t1;
};
inline WideTangents tangents_of(const WideVec3& n) {
  const Wide one = splat(1);
  const Wide sign = n.z >= Wide{} ? one : -one;
  const Wide a = splat(-1) / (sign + n.z);
  const Wide b = n.x * n.y * a;
  return {{one + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}};
}

// The push-out share's free count (color_contacts.hpp): a body with up to this many deep
// manifolds keeps the whole push-out cap on each.
inline constexpr uint32_t kPushShare = 4;

struct ContactSolverContext {
  std::span<SolverBody> bodies;  // packets (0 = static dummy)
  std::span<const SolverBodyMass> masses;
  std::span<ContactBundle> bundles;     // grouped by colour
  std::span<WideContactPoint> rows;     // the bundles' points past the first
  std::span<const uint32_t> row_start;  // bundle j's are rows [row_start[j], row_start[j + 1])
  // Bundle j's lanes are the manifolds lane_manifolds[lane_start[j], lane_start[j + 1]) of the
  // contact list (SolverState::order), lane l the l-th.
  std::span<const uint32_t> lane_manifolds;
  std::span<const uint32_t> lane_start;
  std::span<BundleRestitution> restitution;  // per bundle; empty when no body bounces
  uint32_t written_end = 1;                  // packets [1, written_end) are written back
  Real h = 0;                                // s, substep
  Real inv_h = 0;
  Softness contact_softness;   // dynamic vs dynamic
  Softness static_softness;    // against a static or kinematic body (stiffer)
  Real max_push_velocity = 3;  // m/s: cap of the position-correction speed
  // The push-out share (color_contacts.hpp): per packet its deep manifolds; per bundle the
  // lanes' caps (written by prepare_bundle), empty when every lane has max_push_velocity.
  std::span<const uint32_t> deep_count;
  std::span<WideValue> push_cap;
  Real restitution_threshold = 1;  // m/s: slower approaches do not bounce
  // Per bundle, written by prepare_bundle: the lanes whose rows carry a load their soft spring
  // would give under by more than kDirectGive (direct_solve.hpp), a bit a lane, and above them
  // those sinking into a static body (kDirectDepth, DirectState). Empty: not
  // wanted. The give per impulse of each softness (give_per_impulse), s/kg.
  std::span<uint32_t> loaded_lanes;
  Real contact_give = 0, static_give = 0;
  // m/s: a deep face whose patch centre closes faster than this is sinking (kDirectDepth):
  // kDirectGive a step.
  Real sink_speed = 0;
  // Some body carries kPlaced: its new face supports are loaded rows, and the direct solve's
  // active set starts with the rows closing at no speed (direct_solve.cpp). Else neither is
  // looked for, at no cost.
  bool bodies_placed = false;
  // Some body carries kSeparating (separating_mark.hpp): its rows are not solved directly.
  bool bodies_separating = false;

  // Bundle j's points: as many as the most points of its lanes, the first in the bundle
  // (ContactBundle::first), the others rows_of(j)[0, point_count(j) - 1).
  WideContactPoint* rows_of(uint32_t j) const { return rows.data() + row_start[j]; }
  int point_count(uint32_t j) const { return 1 + int(row_start[j + 1] - row_start[j]); }
  std::span<const uint32_t> manifolds_of(uint32_t j) const {
    return lane_manifolds.subspan(lane_start[j], lane_start[j + 1] - lane_start[j]);
  }
};

ELAN_ISA_BEGIN

// Builds bundle `bundle` from its manifolds (ctx.manifolds_of(bundle): at most kLanes, sharing
// no dynamic body). Its rows (ctx.row_start) must be one fewer than the most points of its
// manifolds; every field of it, of its rows and of its BundleRestitution is written, unused
// lanes and points with zero mass so they apply nothing.
// The manifolds' points past the first are read from `tails` (ManifoldHead::tail), here and in
// the refresh and the impulses' storage.
void prepare_bundle(const ContactSolverContext& ctx, const BodyStore& bodies,
                    std::span<const ManifoldHead> manifolds, std::span<const ManifoldTail> tails,
                    std::span<const uint32_t> packet_of, uint32_t bundle);

void warm_start_contacts(ContactSolverContext& ctx, uint32_t begin, uint32_t end);
// Re-places the lever arms of every point between two dynamic bodies at one shared point: the
// step's contact point moved by the two bodies' mean translation, keeping the current
// separation. With arms fixed at the step's start, once the bodies have slid apart the two
// halves of an impulse act at different points and angular momentum about any origin changes by
// (dp_b - dp_a) x P; with one shared point it cannot. Also sets each row's current_separation.
// Called after every position update of the substeps, before any other pass over the bundle
// (before the first update, nothing has moved). Reads the packets' pose changes (no velocity),
// their current inverse inertias, the bodies' positions and the manifolds' anchors; writes
// the bundles [begin, end) only, so it may run inside a constraint pass of the same colour.
void refresh_contacts(ContactSolverContext& ctx, const BodyStore& bodies,
                      std::span<const ManifoldHead> manifolds, std::span<const ManifoldTail> tails,
                      uint32_t begin, uint32_t end);
void solve_contacts(ContactSolverContext& ctx, uint32_t begin, uint32_t end, bool use_bias);
void apply_restitution(ContactSolverContext& ctx, uint32_t begin, uint32_t end);
// Copies accumulated impulses back into the manifolds (for next step's warm start and events).
void store_impulses(const ContactSolverContext& ctx, uint32_t begin, uint32_t end,
                    std::span<ManifoldHead> manifolds, std::span<ManifoldTail> tails);

ELAN_ISA_END

}  // namespace elan::detail
