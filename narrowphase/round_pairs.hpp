// Closed-form contact manifolds for round shapes (sphere, capsule) and for any shape against a
// plane. Each routine has the signature and conventions of collide() in collide.hpp, with A and B
// in the order of the name (the dispatcher swaps and flips when the pair comes the other way).
#pragma once

#include "core/base/contact.hpp"
#include "core/base/shape.hpp"

namespace elan::detail {

// Feature ids of the round routines: sphere 0, capsule segment ends 0/1 (parallel capsule pairs
// use end-of-A / end-of-B ids), box faces 0..5 (+x,-x,+y,-y,+z,-z), hull and box vertices their
// index, cylinder rim points kFeatureRim + k.
inline constexpr uint32_t kFeatureRim = 0x100;

bool collide_sphere_sphere(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                           Real speculative_distance, Manifold& out);
bool collide_sphere_capsule(const Shape& a, const Transform& xa, const Shape& b,
                            const Transform& xb, Real speculative_distance, Manifold& out);
bool collide_capsule_capsule(const Shape& a, const Transform& xa, const Shape& b,
                             const Transform& xb, Real speculative_distance, Manifold& out);
bool collide_sphere_box(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                        Real speculative_distance, Manifold& out);
// B is a convex hull or a cylinder (any shape with a support function).
bool collide_sphere_convex(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                           Real speculative_distance, Manifold& out);
// A is any non-plane shape, B a plane (static). Normal = minus the plane's world normal.
bool collide_convex_plane(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                          Real speculative_distance, Manifold& out);

}  // namespace elan::detail
