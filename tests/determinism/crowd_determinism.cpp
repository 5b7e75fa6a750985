// SPDX-License-Identifier: MIT
// Bodies spawned at one point: which of their deep pairs each keeps (the deep sieve in the
// broadphase, then the budget: core/world/deep_pairs.hpp) is a function of the scene alone, so a
// crowd steps to the same bits for any thread count and every broadphase, although each finder
// meets the pairs in its own order and two threads split them differently.
#include <gtest/gtest.h>

#include <vector>

#include "physics/physics_util.hpp"

namespace elan {
namespace crowd_determinism_test {

using test::add_body;
using test::at;
using test::kDt;

// 2,000 unit boxes at one point on a slab: 2 million deep pairs, each body keeping a few.
// Three steps: the first from coincident centres, the next two from the centres it spread.
std::vector<uint64_t> crowd_hashes(int threads, BroadphaseType broadphase, int boxes, int steps) {
  WorldDef def;
  def.threads = threads;
  def.broadphase = broadphase;
  World world(def);
  add_body(world, test::box_shape(Vec3(50, 1, 50)), at(Vec3(0, -1, 0), MotionType::Static));
  for (int i = 0; i < boxes; ++i) {
    add_body(world, test::box_shape(Vec3::Constant(Real(0.5))), at(Vec3(0, Real(0.5), 0)));
  }
  std::vector<uint64_t> out;
  for (int n = 0; n < steps; ++n) {
    world.step(kDt);
    out.push_back(world.state_hash());
  }
  return out;
}

void expect_same_hashes(int boxes, int steps) {
  const std::vector<uint64_t> reference =
      crowd_hashes(1, BroadphaseType::SweepAndPrune, boxes, steps);
  for (const BroadphaseType bp :
       {BroadphaseType::SweepAndPrune, BroadphaseType::AllPairs, BroadphaseType::Tree}) {
    for (int threads = 1; threads <= 2; ++threads) {
      if (threads == 1 && bp == BroadphaseType::SweepAndPrune) continue;
      EXPECT_EQ(crowd_hashes(threads, bp, boxes, steps), reference)
          << threads << " threads, "
          << (bp == BroadphaseType::AllPairs ? "all-pairs"
              : bp == BroadphaseType::Tree   ? "tree"
                                             : "sap");
    }
  }
}

TEST(CrowdDeterminism, SameHashForOneAndTwoThreadsAndEveryBroadphase) {
  // Under the sanitizers a step is about ten times slower: 1,000 boxes (999 deep partners each,
  // 125 times the 8 a body keeps) hold the test to a few seconds.
  expect_same_hashes(test::kSanitized ? 1000 : 2000, 3);
}

// Past the step where the crowd's runs of 9 have parted (step 9 or so), its bodies are open at
// level 1 and SAP closes them in their groups of 8 runs and more (broadphase/closed_runs.hpp),
// found from the last step's crowded bodies: still the same bits for every finder and thread count.
TEST(CrowdDeterminism, SameHashOnceTheRunsHaveParted) {
  expect_same_hashes(test::kSanitized ? 200 : 600, 16);
}

}  // namespace crowd_determinism_test
}  // namespace elan
