// SPDX-License-Identifier: MIT
// The checks a fuzz target makes on a world it built from its input: every body finite.
#pragma once

#include "elan/world.hpp"
#include "fuzz/fuzz_input.hpp"

namespace elan::fuzz {

// `energy`: also the kinetic energy, a float sum that a world within the supported ranges
// keeps finite; a snapshot may hold a running world that left them (a body flung at 1e13 m/s
// is finite, its energy in float is not).
inline void require_finite(const World& world, const char* where, bool energy = true) {
  for (std::size_t i = 0; i < world.body_count(); ++i) {
    const BodyId id = world.body_at(i);
    require(world.position(id).allFinite() && world.orientation(id).coeffs().allFinite() &&
                world.linear_velocity(id).allFinite() && world.angular_velocity(id).allFinite(),
            "every body stays finite:", where);
  }
  if (energy)
    require(std::isfinite(world.kinetic_energy()), "the kinetic energy is finite:", where);
}

}  // namespace elan::fuzz
