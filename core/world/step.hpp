// SPDX-License-Identifier: MIT
// The step pipeline: the stages of ARCHITECTURE.md called in order over the world's arrays.
#pragma once

#include "core/world/world_state.hpp"

namespace elan::detail {

// Advances `w` by dt (validated by the caller). Runs inside the world's arena. Returns status.
uint32_t run_step(WorldState& w, Real dt);

}  // namespace elan::detail
