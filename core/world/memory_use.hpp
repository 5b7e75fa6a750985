// SPDX-License-Identifier: MIT
// memory_use(): the heap a world keeps between steps, by part, for the benchmark's memory report
// (the "store + broadphase + contacts + solver", with shapes apart).
#pragma once

#include <cstddef>

#include "core/world/world_state.hpp"

namespace elan::detail {

// Bytes of every buffer's capacity (what the allocator keeps, overhead not included).
struct MemoryUse {
  std::size_t bodies = 0;      // body columns, id slots
  std::size_t shapes = 0;      // shape records and hull geometry (each hull counted once)
  std::size_t broadphase = 0;  // per-body kinds, the broadphases' kept order and scratch
  std::size_t contacts = 0;    // the contact list, the collide stage's blocks, event records
  std::size_t solver = 0;      // packets, colouring, bundles, rows, islands, executor
  std::size_t api = 0;         // events, pair filter answers, query bounds, id cache
  // The step's scratch: the sweep's buffers and the pair list, then the collide stage's, then
  // the solver's bundles and point rows, in the same bytes (StepScratch).
  std::size_t scratch = 0;
  std::size_t total() const {
    return bodies + shapes + broadphase + contacts + solver + api + scratch;
  }
};

MemoryUse memory_use(const WorldState& w);

}  // namespace elan::detail
