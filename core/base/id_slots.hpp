// SPDX-License-Identifier: MIT
// Generation-checked id slots, shared by bodies and joints: a slot maps to a dense index
// (UINT32_MAX when free) and carries a generation that a removal bumps, so a stale id never
// matches a reused slot. Freed slots are reused last-freed first.
#pragma once

#include <cstdint>
#include <vector>

namespace elan::detail {

// Is (slot, generation) a live id?
inline bool slot_live(const std::vector<uint32_t>& index, const std::vector<uint32_t>& generation,
                      uint32_t slot, uint32_t gen) {
  return slot < index.size() && generation[slot] == gen && index[slot] != UINT32_MAX;
}

// A slot for dense index `dense`: the last freed one, else a new one.
inline uint32_t take_slot(std::vector<uint32_t>& index, std::vector<uint32_t>& generation,
                          std::vector<uint32_t>& free, uint32_t dense) {
  uint32_t slot;
  if (!free.empty()) {
    slot = free.back();
    free.pop_back();
  } else {
    slot = uint32_t(index.size());
    index.push_back(UINT32_MAX);
    generation.push_back(0);
  }
  index[slot] = dense;
  return slot;
}

// Frees `slot`: its ids go stale.
inline void release_slot(std::vector<uint32_t>& index, std::vector<uint32_t>& generation,
                         std::vector<uint32_t>& free, uint32_t slot) {
  index[slot] = UINT32_MAX;
  ++generation[slot];
  free.push_back(slot);
}

}  // namespace elan::detail
