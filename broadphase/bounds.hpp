// Stage 1, bounds: a world-space box per body covering its motion over the step.
//
// Reads: body pose, velocity, shape, motion type. Writes: out.min_*/max_* of every body.
// Parallel over fixed blocks of bodies; indexed writes only (determinism rule 1).
#pragma once

#include <array>
#include <span>

#include "core/base/body_store.hpp"
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

}  // namespace elan::detail
