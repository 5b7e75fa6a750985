// SPDX-License-Identifier: MIT
// Shape casts and exact overlap of one shape against another: the kernels of the scene queries'
// cast_shape, overlap_shape and the character mover.
#pragma once

#include "core/base/shape.hpp"

namespace elan::detail {

struct CastContact {
  Real fraction = 0;            // in [0, 1] of the translation
  Vec3 point = Vec3::Zero();    // world, on B's surface (within the target gap)
  Vec3 normal = Vec3::UnitY();  // unit, world, from B towards A
};

// Sweeps A (convex or compound) from principal-frame pose xa along `translation` (world) against
// B (any kind) at xb, and finds the first fraction at which they come within `target` (m, >= 0)
// of each other: conservative advancement on the GJK distance (time_of_impact, toi.cpp), stopping
// within max(target / 4, 1e-4 of the larger bounding radius) of the target; a plane B in closed
// form (the support of A against the plane's normal). Fraction 0 when they are already within
// target; then the normal and point are those of the deepest contact. False when they do not come
// within target over the translation.
bool shape_cast(const Shape& a, const Transform& xa, const Vec3& translation, const Shape& b,
                const Transform& xb, Real target, CastContact& out);

// The normal (from B towards A) and point of the contact of A and B at their poses, looked for up
// to `gap` apart; false when they are farther apart.
bool contact_normal(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                    Real gap, Vec3& normal, Vec3& point);

// Whether the solids of A (convex or compound) and B (any kind) overlap or touch: the narrowphase's
// exact contact test with no speculative gap (GJK/EPA, SAT, closed forms, the triangles of a
// surface), not the bounding boxes.
bool shapes_overlap(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb);

}  // namespace elan::detail
