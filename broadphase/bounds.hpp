// SPDX-License-Identifier: MIT
// The bounds stage: a world-space box per body covering its motion over the step, and what the
// broadphase and the collide stage read of each body beside its box (BodyKindColumns).
//
// Reads: body pose, velocity, shape, motion type, awake and frozen flags. Writes: out.min_*/max_*
// of every body, and the body kinds.
// Parallel over fixed blocks of bodies; indexed writes only (determinism rule 1).
#pragma once

#include <array>
#include <span>

#include "broadphase/broad_kind.hpp"
#include "core/base/body_store.hpp"
#include "core/base/bvh.hpp"
#include "core/base/shape.hpp"
#include "core/base/step_scratch.hpp"

namespace elan::detail {

// The step's boxes are read by the broadphase and by nothing after it, so the world takes their
// columns from the step scratch for the sweep's phase (take_from, release); other holders (the
// queries' boxes, tests) keep them on the heap, each column on a cache line either way.
struct BoundsColumns {
  ScratchVector<Real> min_x, min_y, min_z, max_x, max_y, max_z;  // m, world
  std::array<ScratchVector<Real>*, 6> columns() {
    return {&min_x, &min_y, &min_z, &max_x, &max_y, &max_z};
  }
  void resize(std::size_t n);
  std::size_t size() const { return min_x.size(); }
  void take_from(StepScratch& scratch);
  void release();
};

// Box of the shape at its current pose, united with the box at the pose it reaches moving for
// `dt` with its current velocities (the seed's answer to tunneling: the box covers before and
// after), grown by `margin` on every side. Planes get an infinite box (+-inf on the unbounded
// axes); the broadphase treats planes separately.
void compute_bounds(const BodyStore& bodies, std::span<const Shape> shapes, Real dt, Real margin,
                    BoundsColumns& out);

// Per body, one byte each: its BroadKind (broad_kind.hpp); 1 if its shape is a plane (the
// broadphase keeps planes apart); 1 if it is idle, static or asleep (a frozen body is out of the
// simulation and keeps no contacts), whose contacts collide_pairs carries. They are derived in the
// bounds pass, which reads the same columns in parallel blocks, rather than kept as body flags in
// step with every change of motion type, sleep and quarantine.
struct BodyKindColumns {
  std::span<uint8_t> broad_kind, is_plane, idle;  // each sized to the body count
};

// As above, and fills `kinds` in the same pass.
void compute_bounds(const BodyStore& bodies, std::span<const Shape> shapes, Real dt, Real margin,
                    BoundsColumns& out, const BodyKindColumns& kinds);

// The exact box (no motion, no margin) of `shape` at principal-frame pose (position, rotation),
// by the same formula as compute_bounds; planes get their infinite box. For the query tree.
void shape_bounds(const Shape& shape, const Vec3& position, const Quat& rotation, Vec3& lo,
                  Vec3& hi);
// The same box as an Aabb: what World::bounds and the debug drawer report.
inline Aabb shape_box(const Shape& shape, const Vec3& position, const Quat& rotation) {
  Vec3 lo, hi;
  shape_bounds(shape, position, rotation, lo, hi);
  return Aabb{lo, hi};
}

}  // namespace elan::detail
