// SPDX-License-Identifier: MIT
// Integration of the body packets over one substep: velocities from gravity, forces and damping;
// positions and orientations from velocities, keeping the angular momentum of a torque-free body.
//
// Reads/writes: packets [begin, end). Parallel over fixed blocks of packets; indexed writes.
#pragma once

#include <cstdint>
#include <span>

#include "core/base/body_store.hpp"
#include "core/base/isa.hpp"
#include "solver/solver_types.hpp"

namespace elan::detail {

ELAN_ISA_BEGIN

// v += h (s g + F/m), s the body's gravity scale, w += h I^-1 tau, then implicit damping v /= (1 +
// h d) (dv/dt = -d v). The force, torque and damping are the body's (masses[i].body) in the store;
// I^-1 is the packet's current world inverse inertia. Kinematic packets (no inverse mass) keep
// their velocities.
void integrate_velocities(std::span<SolverBody> packets, std::span<const SolverBodyMass> masses,
                          const BodyStore& bodies, const Vec3& gravity, Real h, uint32_t begin,
                          uint32_t end);

// dp += h v; dq advanced by the exact rotation of w over h. For anisotropic dynamic bodies the
// angular velocity is then re-derived from the conserved world angular momentum,
// w' = I(q')^-1 I(q) w (the body spins "from momentum": L is unchanged by the rotation update,
// so a torque-free body conserves L and shows the intermediate-axis flip). Gyroscopic bodies'
// masses[i].inv_inertia is updated to the new orientation.
void integrate_positions(std::span<SolverBody> packets, std::span<SolverBodyMass> masses,
                         const BodyStore& bodies, Real h, uint32_t begin, uint32_t end);

// A body's principal moments of inertia, kg m^2, from its inverses (the body store keeps those).
inline Vec3 principal_moments(const BodyStore& bodies, uint32_t i) {
  return Vec3(bodies.inv_ix[i], bodies.inv_iy[i], bodies.inv_iz[i]).cwiseInverse();
}

// Rotation by angle |w| h about w, as a unit quaternion (the exponential map): one body through
// the map integrate_positions applies to its lanes, to within float rounding of the closed form.
Quat rotation_from_angular_velocity(const Vec3& w, Real h);

ELAN_ISA_END

}  // namespace elan::detail
