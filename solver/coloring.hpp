// Stage 5, colour: greedy graph colouring of the contact constraints so that no two constraints
// of one colour touch the same dynamic body (Box2D v3's constraint graph, rebuilt each step).
//
// Reads: for each candidate constraint its two packets and whether each side is dynamic.
// Writes: an order of the candidates grouped by colour, and each colour's start.
// Serial, in key order: the colouring depends on the scene alone (determinism rule 5).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace elan::detail {

// Colours beyond this go to the overflow, solved by one thread (Box2D v3 uses 24 as well).
inline constexpr uint32_t kColorCount = 24;

struct ColorInput {
  uint32_t packet_a, packet_b;
  bool dynamic_a, dynamic_b;
};

struct ColorScratch {
  std::vector<uint64_t> bits;  // kColorCount bitsets over packets
  std::vector<uint8_t> color_of;
  std::vector<uint32_t> cursor;
};

// `color_start` gets kColorCount + 2 entries: colour c is order[color_start[c], color_start[c+1]),
// the overflow is the last range. Within a colour, candidates keep their input order.
void build_colors(std::span<const ColorInput> constraints, std::size_t packet_count,
                  ColorScratch& scratch, std::vector<uint32_t>& order,
                  std::vector<uint32_t>& color_start);

}  // namespace elan::detail
