// SPDX-License-Identifier: MIT
// The state hash: 64 bits over every stored bit of every body's pose and velocities.
#pragma once

#include <cstdint>

#include "core/base/body_store.hpp"

namespace elan::detail {

// Hashes position, orientation, linear and angular velocity of every body, in index order, as
// stored (bit patterns, so -0 and +0 differ and a NaN is visible).
// determinism: serial, in index order (rule 3); the mixing is a fixed function of the bits.
uint64_t hash_bodies(const BodyStore& bodies);

}  // namespace elan::detail
