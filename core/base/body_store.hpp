// SPDX-License-Identifier: MIT
// BodyStore: every body's state as a structure of arrays indexed by a dense body index.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/base/body_traits.hpp"
#include "core/base/column.hpp"
#include "elan/defs.hpp"
#include "elan/math.hpp"

namespace elan::detail {

enum BodyFlags : uint8_t {
  kAwake = 1u << 0,   // dynamic body being simulated (static/kinematic: unused)
  kFrozen = 1u << 1,  // went non-finite and was quarantined
  // Dynamic, placed by the API (created or teleported) and not simulated since: its face contacts
  // have nothing to warm start, so the direct solve takes its supports on that first step
  // (prepare_bundle). The step clears it on every body (WorldState::bodies_placed).
  kPlaced = 1u << 2,
  // Dynamic, being pushed out of a spawn overlap (solver/separating_mark.hpp): its velocity is
  // capped after the solve (push_out_cap.hpp) and its rows are not solved directly. Kept from
  // step to step until the overlap ends (WorldState::bodies_separating).
  kSeparating = 1u << 3,
};

// A force and torque applied to one body for the next step. Few bodies have one at a time (a game
// pushes a handful: thrusters, wind, a player), so the store keeps them in a list of its own and
// a slot a body, not six columns (24 bytes a body, a sixth of the store, zero on nearly all).
struct AppliedForce {
  uint32_t body = 0;
  Vec3 force = Vec3::Zero();   // N, world
  Vec3 torque = Vec3::Zero();  // N m, world
};
inline constexpr uint32_t kNoForce = ~uint32_t{0};

// The pose is that of the centre of mass and principal axes (the shape's principal frame); the
// user-facing pose of the shape frame is derived with Shape::frame_*.
struct BodyStore {
  Column<Real> px, py, pz;              // m, world: centre of mass
  Column<Real> qw, qx, qy, qz;          // principal frame to world, unit
  Column<Real> vx, vy, vz;              // m/s, world
  Column<Real> wx, wy, wz;              // rad/s, world
  Column<Real> inv_mass;                // 1/kg (0: static or kinematic)
  Column<Real> inv_ix, inv_iy, inv_iz;  // 1/(kg m^2), principal axes
  Column<Real> sleep_time;              // s spent below the sleep threshold
  Column<uint32_t> shape;               // index into the world's shapes
  Column<uint32_t> traits;              // index into trait_table
  Column<uint32_t> slot;                // id slot owning this index
  Column<uint32_t> applied;             // index into applied_forces, or kNoForce
  Column<uint8_t> motion;               // MotionType
  Column<uint8_t> flags;                // BodyFlags
  // Not columns (for_each_column does not walk them): the forces and torques applied for the
  // next step, in the order their bodies were first given one; the bodies' distinct traits.
  std::vector<AppliedForce> applied_forces;
  TraitTable trait_table;

  std::size_t size() const { return px.size(); }

  // Appends a body; returns its dense index. Values are the caller's, already validated.
  std::size_t push_back();
  // Moves the last body into `index` and shrinks by one (swap-remove).
  void swap_remove(std::size_t index);
  void reserve(std::size_t n);
  // Bytes of column storage per body (capacity-based), for the memory report.
  std::size_t bytes_per_body() const;

  Vec3 position(std::size_t i) const { return {px[i], py[i], pz[i]}; }
  Quat orientation(std::size_t i) const { return Quat(qw[i], qx[i], qy[i], qz[i]); }
  Vec3 linear_velocity(std::size_t i) const { return {vx[i], vy[i], vz[i]}; }
  Vec3 angular_velocity(std::size_t i) const { return {wx[i], wy[i], wz[i]}; }
  void set_position(std::size_t i, const Vec3& p) {
    px[i] = p.x();
    py[i] = p.y();
    pz[i] = p.z();
  }
  void set_orientation(std::size_t i, const Quat& q) {
    qw[i] = q.w();
    qx[i] = q.x();
    qy[i] = q.y();
    qz[i] = q.z();
  }
  void set_linear_velocity(std::size_t i, const Vec3& v) {
    vx[i] = v.x();
    vy[i] = v.y();
    vz[i] = v.z();
  }
  void set_angular_velocity(std::size_t i, const Vec3& w) {
    wx[i] = w.x();
    wy[i] = w.y();
    wz[i] = w.z();
  }
  bool is_dynamic(std::size_t i) const { return motion[i] == uint8_t(MotionType::Dynamic); }
  bool is_static(std::size_t i) const { return motion[i] == uint8_t(MotionType::Static); }
  bool is_awake(std::size_t i) const { return (flags[i] & kAwake) != 0; }

  const BodyTraits& traits_of(std::size_t i) const { return trait_table[traits[i]]; }
  void set_traits(std::size_t i, const BodyTraits& t) {
    const uint32_t k =
        trait_table.acquire(t);  // before the release: the same values keep their entry
    trait_table.release(traits[i]);
    traits[i] = k;
  }

  // The force and torque applied to body i for the next step (zero if none).
  Vec3 force(std::size_t i) const {
    return applied[i] == kNoForce ? Vec3::Zero() : applied_forces[applied[i]].force;
  }
  Vec3 torque(std::size_t i) const {
    return applied[i] == kNoForce ? Vec3::Zero() : applied_forces[applied[i]].torque;
  }
  // Body i's entry, added (zero) if it has none.
  AppliedForce& applied_force(std::size_t i);
  // Drops the entries of the bodies `spent(body)` names, keeping the others in their order.
  template <class F>
  void drop_forces_if(F&& spent) {
    std::size_t kept = 0;
    for (const AppliedForce& a : applied_forces) {
      if (spent(a.body)) {
        applied[a.body] = kNoForce;
        continue;
      }
      applied[a.body] = uint32_t(kept);
      applied_forces[kept++] = a;
    }
    applied_forces.resize(kept);
  }
};

// The store's one list of columns, in declaration order: push_back, swap_remove, reserve,
// the memory report and snapshots all walk it, so a column added here is handled by all of them.
template <class S, class F>
void for_each_column(S& s, F&& f) {
  f(s.px);
  f(s.py);
  f(s.pz);
  f(s.qw);
  f(s.qx);
  f(s.qy);
  f(s.qz);
  f(s.vx);
  f(s.vy);
  f(s.vz);
  f(s.wx);
  f(s.wy);
  f(s.wz);
  f(s.inv_mass);
  f(s.inv_ix);
  f(s.inv_iy);
  f(s.inv_iz);
  f(s.sleep_time);
  f(s.shape);
  f(s.traits);
  f(s.slot);
  f(s.applied);
  f(s.motion);
  f(s.flags);
}

}  // namespace elan::detail
