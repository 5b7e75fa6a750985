// SPDX-License-Identifier: MIT
// Stable, generation-checked handles of the public API.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

namespace elan {

/// A body handle. Stays valid until the body is destroyed; a destroyed body's id is reported
/// invalid even after its slot is reused, because the generation no longer matches.
struct BodyId {
  uint32_t slot = UINT32_MAX;
  uint32_t generation = 0;
  bool is_null() const { return slot == UINT32_MAX; }
  friend bool operator==(BodyId, BodyId) = default;
};

/// A shape handle. Shapes are immutable and may be shared by many bodies.
struct ShapeId {
  uint32_t index = UINT32_MAX;
  bool is_null() const { return index == UINT32_MAX; }
  friend bool operator==(ShapeId, ShapeId) = default;
};

}  // namespace elan

/// Ids hash as their bits, so they can key std::unordered_map and std::unordered_set (iterating
/// such a container is in no fixed order: keep its order out of anything that must replay).
template <>
struct std::hash<elan::BodyId> {
  std::size_t operator()(elan::BodyId id) const noexcept {
    return std::hash<uint64_t>{}(uint64_t(id.generation) << 32 | id.slot);
  }
};

template <>
struct std::hash<elan::ShapeId> {
  std::size_t operator()(elan::ShapeId id) const noexcept {
    return std::hash<uint32_t>{}(id.index);
  }
};
