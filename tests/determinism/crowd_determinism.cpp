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
std::vector<uint64_t> crowd_hashes(int threads, BroadphaseType broadphase) {
  WorldDef def;
  def.threads = threads;
  def.broadphase = broadphase;
  World world(def);
  add_body(world, test::box_shape(Vec3(50, 1, 50)), at(Vec3(0, -1, 0), MotionType::Static));
  // Under the sanitizers a step is about ten times slower: 1,000 boxes (999 deep partners each,
  // 125 times the 8 a body keeps) hold the test to a few seconds.
  const int boxes = test::kSanitized ? 1000 : 2000;
  for (int i = 0; i < boxes; ++i) {
    add_body(world, test::box_shape(Vec3::Constant(Real(0.5))), at(Vec3(0, Real(0.5), 0)));
  }
  std::vector<uint64_t> out;
  for (int n = 0; n < 3; ++n) {
    world.step(kDt);
    out.push_back(world.state_hash());
  }
  return out;
}

TEST(CrowdDeterminism, SameHashForOneAndTwoThreadsAndEveryBroadphase) {
  const std::vector<uint64_t> reference = crowd_hashes(1, BroadphaseType::SweepAndPrune);
  for (const BroadphaseType bp :
       {BroadphaseType::SweepAndPrune, BroadphaseType::AllPairs, BroadphaseType::Tree}) {
    for (int threads = 1; threads <= 2; ++threads) {
      if (threads == 1 && bp == BroadphaseType::SweepAndPrune) continue;
      EXPECT_EQ(crowd_hashes(threads, bp), reference)
          << threads << " threads, "
          << (bp == BroadphaseType::AllPairs ? "all-pairs"
              : bp == BroadphaseType::Tree   ? "tree"
                                             : "sap");
    }
  }
}

}  // namespace crowd_determinism_test
}  // namespace elan
