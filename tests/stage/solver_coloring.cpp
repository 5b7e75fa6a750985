// SPDX-License-Identifier: MIT
// Colouring (build_colors): no dynamic body twice in one colour, every constraint exactly once,
// input order kept within each colour and in the overflow, and the documented colour choice for
// constraints with one dynamic side.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "solver/coloring.hpp"

namespace elan::detail {
namespace solver_coloring_test {

struct Colored {
  std::vector<uint32_t> order;
  std::vector<uint32_t> start;  // kColorCount + 2
};

Colored color(const std::vector<ColorInput>& in, std::size_t packets) {
  ColorScratch scratch;
  Colored out;
  out.order.assign(in.size(), 0xFFFFFFFFu);
  out.start.assign(kColorCount + 2, 0);
  build_colors(in, packets, scratch, out.order, out.start);
  return out;
}

std::vector<ColorInput> random_constraints(std::size_t count, uint32_t packets, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> packet(1, packets - 1);
  std::uniform_int_distribution<int> kind(0, 3);
  std::vector<ColorInput> in;
  for (std::size_t i = 0; i < count; ++i) {
    const int k = kind(rng);  // 0: A alone dynamic, 1: B alone, 2 and 3: both
    uint32_t a = packet(rng), b = packet(rng);
    while (b == a) b = packet(rng);
    in.push_back({k == 1 ? 0 : a, k == 0 ? 0 : b, k != 1, k != 0});
  }
  return in;
}

TEST(Coloring, NoDynamicBodyTwiceInOneColor) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    // Few packets for many constraints, so that colours fill and some spill into the overflow.
    const std::vector<ColorInput> in = random_constraints(3000, 200, seed);
    const Colored c = color(in, 200);
    for (uint32_t k = 0; k < kColorCount; ++k) {
      std::set<uint32_t> bodies;
      for (uint32_t j = c.start[k]; j < c.start[k + 1]; ++j) {
        const ColorInput& x = in[c.order[j]];
        if (x.dynamic_a) {
          EXPECT_TRUE(bodies.insert(x.packet_a).second) << "colour " << k;
        }
        if (x.dynamic_b) {
          EXPECT_TRUE(bodies.insert(x.packet_b).second) << "colour " << k;
        }
      }
    }
    EXPECT_GT(c.start[kColorCount + 1], c.start[kColorCount]) << "the test should overflow";
  }
}

TEST(Coloring, EveryConstraintOnceInInputOrderWithinEachRange) {
  const std::vector<ColorInput> in = random_constraints(2000, 300, 11);
  const Colored c = color(in, 300);
  ASSERT_EQ(c.start.front(), 0u);
  ASSERT_EQ(c.start.back(), in.size());
  std::vector<int> seen(in.size(), 0);
  for (uint32_t k = 0; k <= kColorCount; ++k) {
    ASSERT_LE(c.start[k], c.start[k + 1]);
    for (uint32_t j = c.start[k]; j < c.start[k + 1]; ++j) {
      ASSERT_LT(c.order[j], in.size());
      ++seen[c.order[j]];
      if (j > c.start[k]) {
        EXPECT_LT(c.order[j - 1], c.order[j]) << "range " << k;
      }
    }
  }
  for (std::size_t i = 0; i < in.size(); ++i) EXPECT_EQ(seen[i], 1) << i;
}

TEST(Coloring, OverflowTakesWhatNoColourFitsInInputOrder) {
  // Constraints 0 .. kColorCount + 5 all touch dynamic packet 1: the first kColorCount take
  // colours 0, 1, ... in turn, the rest overflow in input order.
  std::vector<ColorInput> in;
  const uint32_t count = kColorCount + 6;
  for (uint32_t i = 0; i < count; ++i) in.push_back({1, 2 + i, true, true});
  const Colored c = color(in, count + 2);
  for (uint32_t k = 0; k < kColorCount; ++k) {
    ASSERT_EQ(c.start[k + 1] - c.start[k], 1u) << k;
    EXPECT_EQ(c.order[c.start[k]], k);
  }
  const std::vector<uint32_t> overflow(c.order.begin() + c.start[kColorCount], c.order.end());
  EXPECT_EQ(overflow, (std::vector<uint32_t>{24, 25, 26, 27, 28, 29}));
  // The same input gives the same order (a reused scratch too).
  EXPECT_EQ(color(in, count + 2).order, c.order);
}

TEST(Coloring, OneDynamicSideFillsTheColoursFromTheLast) {
  // Against static bodies (packet 0, not dynamic), packet 3 takes the last colour, then the one
  // before; a constraint between two dynamic bodies still starts at colour 0.
  const std::vector<ColorInput> in = {
      {3, 0, true, false}, {0, 3, false, true}, {4, 5, true, true}, {3, 4, true, true}};
  const Colored c = color(in, 6);
  auto colour_of = [&](uint32_t i) {
    for (uint32_t k = 0; k <= kColorCount; ++k)
      for (uint32_t j = c.start[k]; j < c.start[k + 1]; ++j)
        if (c.order[j] == i) return k;
    return kColorCount + 1;
  };
  EXPECT_EQ(colour_of(0), kColorCount - 1);
  EXPECT_EQ(colour_of(1), kColorCount - 2);
  EXPECT_EQ(colour_of(2), 0u);
  EXPECT_EQ(colour_of(3), 1u);  // packet 4 is in colour 0, packet 3 is not
}

}  // namespace solver_coloring_test
}  // namespace elan::detail
