// SPDX-License-Identifier: MIT
// The general convex pair path: GJK/EPA for the normal, then the contact points by clipping the
// two supporting features (faces, segments) against each other, as Jolt's
// ManifoldBetweenTwoFaces does. Used for cylinders and any pair without a specialised routine.
#pragma once

#include "core/base/contact.hpp"
#include "core/base/shape.hpp"
#include "narrowphase/separation.hpp"

namespace elan::detail {

// Same contract as collide() in collide.hpp; neither shape may be a plane.
bool collide_general(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                     Real speculative_distance, Manifold& out, Separation* separation = nullptr);

}  // namespace elan::detail
