// SPDX-License-Identifier: MIT
// 500 cylinders created at one point (bench/cliffs/cylinders500_one_point.json): each keeps 8
// deep pairs (core/world/deep_pairs.hpp), whose contacts come from the deep contact
// (narrowphase/deep_contact.hpp), the virtual direction of coincident centres included. The
// same state hash at every step under 1 and 2 threads and either broadphase kind that sorts its
// pairs differently (sweep and prune, tree). Five steps: the first pushes the cloud apart from
// one point, the next ones take the line of centres.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "physics/physics_util.hpp"

namespace elan {
namespace deep_contact_determinism_test {

std::vector<uint64_t> hashes(int threads, BroadphaseType broadphase, int steps) {
  Real dt = 0;
  World world =
      test::load_world("../bench/cliffs/cylinders500_one_point.json", threads, dt, broadphase);
  std::vector<uint64_t> out;
  for (int n = 0; n < steps; ++n) {
    world.step(dt);
    EXPECT_TRUE(test::all_finite(world)) << "step " << n + 1;
    out.push_back(world.state_hash());
  }
  return out;
}

TEST(DeepContactDeterminism, CylindersAtOnePointSameHashAtOneAndTwoThreads) {
  constexpr int kSteps = 5;
  const std::vector<uint64_t> one = hashes(1, BroadphaseType::SweepAndPrune, kSteps);
  EXPECT_EQ(one, hashes(2, BroadphaseType::SweepAndPrune, kSteps));
  EXPECT_EQ(one, hashes(2, BroadphaseType::Tree, kSteps));
}

}  // namespace deep_contact_determinism_test
}  // namespace elan
