// SPDX-License-Identifier: MIT
// The scene format's names of the shape types (elan/defs.hpp): one table for the scene tools,
// the benchmarks and the Python package.
#include <array>
#include <string_view>

#include "elan/defs.hpp"

namespace elan {
namespace {

// In ShapeType's order.
constexpr std::array<const char*, 9> kNames = {"sphere",   "box",         "capsule",
                                               "cylinder", "convex_hull", "plane",
                                               "mesh",     "heightfield", "compound"};
static_assert(std::size_t(ShapeType::Compound) + 1 == kNames.size(), "a name for every shape type");

}  // namespace

const char* shape_type_name(ShapeType type) {
  const auto i = std::size_t(type);
  return i < kNames.size() ? kNames[i] : "unknown";
}

std::optional<ShapeType> shape_type_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kNames.size(); ++i) {
    if (name == kNames[i]) return ShapeType(i);
  }
  return std::nullopt;
}

}  // namespace elan
