// SPDX-License-Identifier: MIT
// The solver's median cut: half the bodies on each side, every body of side 0 at or before every
// body of side 1 along the axis of largest spread, and the same sides whatever the order of the
// bodies in memory; non-finite coordinates go to side 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "solver/partition.hpp"

namespace elan::detail {
namespace solver_partition_test {

BodyStore store_with(const std::vector<Vec3>& centres) {
  BodyStore s;
  for (const Vec3& c : centres) s.set_position(s.push_back(), c);
  return s;
}

std::vector<uint8_t> sides(const BodyStore& s, const std::vector<uint32_t>& simulated) {
  std::vector<uint64_t> keys(simulated.size());
  std::vector<uint8_t> side(simulated.size(), 9);
  split_in_halves(s, simulated, keys, side);
  return side;
}

TEST(SolverPartition, CutsAtTheMedianOfTheWidestAxis) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<Vec3> centres;
  // Wider in z (4 m) than in x (2 m) and y (1 m).
  for (int i = 0; i < 1001; ++i) centres.push_back(Vec3{u(rng), Real(0.5) * u(rng), 2 * u(rng)});
  const BodyStore s = store_with(centres);
  std::vector<uint32_t> simulated;
  for (uint32_t i = 0; i < 1001; i += 1) simulated.push_back(i);
  const std::vector<uint8_t> side = sides(s, simulated);
  EXPECT_EQ(std::count(side.begin(), side.end(), 0), 500);
  EXPECT_EQ(std::count(side.begin(), side.end(), 1), 501);
  Real last_of_0 = -1e9, first_of_1 = 1e9;
  for (std::size_t k = 0; k < side.size(); ++k) {
    const Real z = centres[simulated[k]].z();
    if (side[k] == 0) last_of_0 = std::max(last_of_0, z);
    if (side[k] == 1) first_of_1 = std::min(first_of_1, z);
  }
  EXPECT_LE(last_of_0, first_of_1);
}

TEST(SolverPartition, TiesAreBrokenByIndexAndNonFiniteGoesLast) {
  // Every body at one x but for a spread in y; the cut is along y, ties by index.
  std::vector<Vec3> centres = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 5, 0}, {0, -5, 0}};
  centres.emplace_back(0, std::numeric_limits<Real>::quiet_NaN(), 0);
  const BodyStore s = store_with(centres);
  const std::vector<uint32_t> simulated = {0, 1, 2, 3, 4, 5, 6};
  const std::vector<uint8_t> side = sides(s, simulated);
  // Order: 5 (-5), 0, 1, 2, 3 (1, by index), 4 (5), 6 (NaN); the first 3 go to side 0.
  EXPECT_EQ(side, (std::vector<uint8_t>{0, 0, 1, 1, 1, 0, 1}));
}

TEST(SolverPartition, OnlyTheSimulatedBodiesAreCut) {
  const BodyStore s = store_with({{-3, 0, 0}, {100, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {3, 0, 0}});
  // Body 1 far away is not simulated (static or asleep): it neither moves the median nor gets a
  // side.
  const std::vector<uint32_t> simulated = {0, 2, 3, 4};
  EXPECT_EQ(sides(s, simulated), (std::vector<uint8_t>{0, 0, 1, 1}));
}

}  // namespace solver_partition_test
}  // namespace elan::detail
