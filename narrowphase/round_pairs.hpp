// SPDX-License-Identifier: MIT
// Closed-form contact manifolds for round shapes (sphere, capsule) and for any shape against a
// plane. Each routine has the signature and conventions of collide() in collide.hpp, with A and B
// in the order of the name (the dispatcher swaps and flips when the pair comes the other way).
#pragma once

#include "core/base/contact.hpp"
#include "core/base/shape.hpp"
#include "narrowphase/separation.hpp"

namespace elan::detail {

// Feature ids (stable while the same features touch): sphere 0; capsule-capsule end-of-A 0/1,
// end-of-B 2/3, segment-segment 4; sphere-box region code (outside) or 27 + face (inside);
// plane contacts the vertex index (box corner bits x,y,z; capsule end 0 = -Y), cylinder rim
// points kFeatureRim + k.
inline constexpr uint32_t kFeatureRim = 0x100;

bool collide_sphere_sphere(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                           Real speculative_distance, Manifold& out,
                           Separation* separation = nullptr);
bool collide_sphere_capsule(const Shape& a, const Transform& xa, const Shape& b,
                            const Transform& xb, Real speculative_distance, Manifold& out,
                            Separation* separation = nullptr);
bool collide_capsule_capsule(const Shape& a, const Transform& xa, const Shape& b,
                             const Transform& xb, Real speculative_distance, Manifold& out,
                             Separation* separation = nullptr);
bool collide_sphere_box(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                        Real speculative_distance, Manifold& out, Separation* separation = nullptr);
// B is a convex hull or a cylinder (any shape with a support function).
bool collide_sphere_convex(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                           Real speculative_distance, Manifold& out,
                           Separation* separation = nullptr);
// A is any non-plane shape, B a plane (static). Normal = minus the plane's world normal.
bool collide_convex_plane(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                          Real speculative_distance, Manifold& out,
                          Separation* separation = nullptr);

}  // namespace elan::detail
