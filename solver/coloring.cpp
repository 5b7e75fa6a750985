// SPDX-License-Identifier: MIT
// Greedy constraint colouring with per-colour body bitsets.
#include "solver/coloring.hpp"

#include <algorithm>

#include "core/base/grow.hpp"

namespace elan::detail {

void build_colors(std::span<const ColorInput> constraints, std::size_t packet_count,
                  ColorScratch& s, std::span<uint32_t> order, std::span<uint32_t> start) {
  const std::size_t words = (packet_count + 63) / 64;
  s.bits.assign(color_words(packet_count), 0);
  grow_to(s.color_of, constraints.size());
  std::fill(start.begin(), start.end(), 0);
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const ColorInput& c = constraints[i];
    uint32_t chosen = kColorCount;  // overflow
    // perf: a constraint against a static body touches one dynamic body only; Box2D v3 puts
    // those in the later colours so the early colours stay large for dynamic pairs.
    const bool one_sided = !(c.dynamic_a && c.dynamic_b);
    for (uint32_t k = 0; k < kColorCount; ++k) {
      const uint32_t color = one_sided ? kColorCount - 1 - k : k;
      uint64_t* bits = s.bits.data() + std::size_t(color) * words;
      const bool a_free = !c.dynamic_a || !((bits[c.packet_a >> 6] >> (c.packet_a & 63)) & 1);
      const bool b_free = !c.dynamic_b || !((bits[c.packet_b >> 6] >> (c.packet_b & 63)) & 1);
      if (a_free && b_free) {
        if (c.dynamic_a) bits[c.packet_a >> 6] |= uint64_t{1} << (c.packet_a & 63);
        if (c.dynamic_b) bits[c.packet_b >> 6] |= uint64_t{1} << (c.packet_b & 63);
        chosen = color;
        break;
      }
    }
    s.color_of[i] = uint8_t(chosen);
    ++start[chosen + 1];
  }
  for (uint32_t c = 1; c < kColorCount + 2; ++c) start[c] += start[c - 1];
  s.cursor.assign(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < constraints.size(); ++i)
    order[s.cursor[s.color_of[i]]++] = uint32_t(i);
}

}  // namespace elan::detail
