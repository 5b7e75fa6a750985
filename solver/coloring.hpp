// SPDX-License-Identifier: MIT
// The colour stage: greedy graph colouring of the contact constraints so that no two constraints
// of one colour touch the same dynamic body (Box2D v3's constraint graph, rebuilt each step).
//
// Reads: for each candidate constraint its two packets and whether each side is dynamic.
// Writes: an order of the candidates grouped by colour, and each colour's start.
// Serial over one list in key order: the colouring depends on the scene alone (determinism rule
// 5). The solver colours each of its groups (partition.hpp) apart, so that the colours only keep
// the SIMD lanes of a bundle apart: one thread solves a group's colours one after another.
#pragma once

#include <cstdint>
#include <span>

#include "core/base/step_scratch.hpp"

namespace elan::detail {

// Colours beyond this go to the overflow, solved by one thread (Box2D v3 uses 24 as well).
inline constexpr uint32_t kColorCount = 24;

struct ColorInput {
  uint32_t packet_a, packet_b;
  bool dynamic_a, dynamic_b;
};

// The caller may give each array its room beforehand (see solve.cpp): build_colors sizes them.
struct ColorScratch {
  ScratchVector<uint64_t> bits;     // kColorCount bitsets over packets: color_words(packets)
  ScratchVector<uint8_t> color_of;  // per constraint
  ScratchVector<uint32_t> cursor;   // kColorCount + 1
};

inline std::size_t color_words(std::size_t packet_count) {
  return (packet_count + 63) / 64 * kColorCount;
}

// `order` (one entry per constraint) gets the constraints' positions in `constraints`, grouped by
// colour; `color_start` (kColorCount + 2 entries) the ranges: colour c is
// order[color_start[c], color_start[c+1]), the overflow the last range. Greedy in input order:
// a constraint takes the first colour free at both its dynamic sides, trying colour 0 up for a
// constraint between two dynamic bodies and colour kColorCount - 1 down for one with a single
// dynamic side; the overflow gets, in input order, those no colour is free for. Within a colour,
// too, constraints keep their input order. Packets of dynamic sides are below `packet_count`.
void build_colors(std::span<const ColorInput> constraints, std::size_t packet_count,
                  ColorScratch& scratch, std::span<uint32_t> order,
                  std::span<uint32_t> color_start);

}  // namespace elan::detail
