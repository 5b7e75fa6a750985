// Stable, generation-checked handles of the public API.
#pragma once

#include <cstdint>

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
