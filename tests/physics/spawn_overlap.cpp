// SPDX-License-Identifier: MIT
// Bodies spawned on top of each other (issue 42's abuse scenes): the push-out that separates
// them is capped (SolveSettings::max_push_velocity, Box2D v3's contactPushMaxVelocity), a body
// overlapping many others shares the cap among its deep contacts (color_contacts.hpp) and keeps
// no more of it as velocity (push_out_cap.hpp), so they part gently instead of flying apart;
// and each body keeps a bounded number of deep pairs (deep_pairs.hpp), so the step's work grows
// with the bodies, not with their square.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "physics/physics_util.hpp"

namespace elan {
namespace spawn_overlap_test {

using test::add_body;
using test::at;
using test::kDt;

// The reproducer physics_100_boxes_one_point_explode.json: 100 unit boxes of 1000 kg created at
// one point, on a static slab (height 0.5) or above it (height 2, scenes/abuse/spawn100.json).
// Without the share each pair pushed at the cap and the pairs chained: 29 m/s after the first
// step, 67 m/s later; with the share but the cap only in steps with a clique of deep overlaps,
// the chains of shallow overlaps left from step 50 on threw their end boxes out at 36 m/s. Over
// 300 steps (5 s, the cloud spread out and come to rest), no box may end a step faster than what
// the cap and gravity give: a box pushed out at the cap and then falling from the highest point
// it reached keeps at most |v|^2 = cap^2 + 2 g (y_max - y) (push_out_cap.hpp's bound, summed
// over the steps). Tolerance 2 m/s: boxes out of the overlap, no longer marked, still tumble off
// and strike one another, turning the spin the cap allows (cap / r, 1 J/kg for a unit box) and
// the soft push of overlaps shallower than kSeparatingDepth into speed; measured 0.4 m/s at most
// (1.1 from height 2), against 33 m/s without the kept mark and 1.5 (1.8) with the mark but no
// cap on its unmarked neighbours.
class SpawnHeight : public ::testing::TestWithParam<Real> {};

TEST_P(SpawnHeight, HundredBoxesAtOnePointPartNoFasterThanThePushCapAndGravity) {
  WorldDef def;
  def.threads = 1;
  World world(def);
  BodyDef ground = at(Vec3(0, -1, 0), MotionType::Static);
  add_body(world, test::box_shape(Vec3(50, 1, 50)), ground);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 100; ++i) {
    boxes.push_back(
        add_body(world, test::box_shape(Vec3::Constant(Real(0.5))), at(Vec3(0, GetParam(), 0))));
  }
  const Real cap = 3, g = Real(9.81);
  const Real tolerance = 2;
  std::vector<Real> highest(boxes.size(), GetParam());
  for (int n = 1; n <= 300; ++n) {
    world.step(kDt);
    ASSERT_TRUE(test::all_finite(world));
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      const Real y = world.position(boxes[k]).y();
      highest[k] = std::max(highest[k], y);
      const Real bound = std::sqrt(cap * cap + 2 * g * (highest[k] - y));
      ASSERT_LE(world.linear_velocity(boxes[k]).norm(), bound + tolerance)
          << "step " << n << ", box " << k;
    }
    if (n == 45 && GetParam() < 1) {
      // While the boxes spawned on the slab still overlap, the cap itself plus a step of gravity
      // (g dt = 0.16 m/s: a box lifted off the slab falls back onto it) bounds them.
      for (const BodyId b : boxes) EXPECT_LE(world.linear_velocity(b).norm(), cap + g * kDt);
    }
  }
  // They do part: along some horizontal axis the boxes have spread by more than a box's width.
  Real spread = 0;
  for (int axis : {0, 2}) {
    Real lo = 1e9, hi = -1e9;
    for (const BodyId b : boxes) {
      lo = std::min(lo, world.position(b)[axis]);
      hi = std::max(hi, world.position(b)[axis]);
    }
    spread = std::max(spread, hi - lo);
  }
  EXPECT_GT(spread, Real(1));
  // And none was thrown off the slab (50 m each way): they stay on it, above it.
  for (const BodyId b : boxes) EXPECT_GT(world.position(b).y(), Real(0));
}

INSTANTIATE_TEST_SUITE_P(SpawnOverlap, SpawnHeight, ::testing::Values(Real(0.5), Real(2)));

// The deep-pair budget: 100 boxes at one point are 4,950 pairs, each 0.0 m from centre to
// centre. Each box keeps at most kDeepPairBudget = 8 of them, so at most 100 * 8 / 2 = 400
// pairs between boxes reach the collide stage, plus one with the slab each: 500 (without the
// budget, 5,050 pairs and as many manifolds).
TEST(SpawnOverlap, HundredBoxesAtOnePointKeepABoundedNumberOfContacts) {
  WorldDef def;
  def.threads = 1;
  World world(def);
  add_body(world, test::box_shape(Vec3(50, 1, 50)), at(Vec3(0, -1, 0), MotionType::Static));
  for (int i = 0; i < 100; ++i) {
    add_body(world, test::box_shape(Vec3::Constant(Real(0.5))), at(Vec3(0, Real(0.5), 0)));
  }
  world.step(kDt);
  EXPECT_LE(world.last_step().pairs, 500u);
  EXPECT_LE(world.last_step().manifolds, 500u);
  EXPECT_GT(world.last_step().manifolds, 100u);  // the boxes do touch each other
}

// The deep sieve in the broadphase (broadphase/deep_sieve.hpp): 2,000 boxes at one point are
// 2 million deep pairs, which the broadphase no longer stores; each box keeps at most
// kDeepPairBudget = 8 of them, so at most 2,000 * 8 / 2 = 8,000 pairs between boxes reach the
// collide stage, plus one with the slab each: 10,000. The second step starts from centres at most
// 5 cm apart (the push-out cap, 3 m/s, over 1/60 s), all pairs still deep.
TEST(SpawnOverlap, TwoThousandBoxesAtOnePointKeepABoundedNumberOfPairs) {
  WorldDef def;
  def.threads = 2;
  World world(def);
  add_body(world, test::box_shape(Vec3(50, 1, 50)), at(Vec3(0, -1, 0), MotionType::Static));
  for (int i = 0; i < 2000; ++i) {
    add_body(world, test::box_shape(Vec3::Constant(Real(0.5))), at(Vec3(0, Real(0.5), 0)));
  }
  for (int n = 1; n <= 2; ++n) {
    world.step(kDt);
    ASSERT_TRUE(test::all_finite(world));
    EXPECT_LE(world.last_step().pairs, 10000u) << "step " << n;
    // The budget is used, not starved: the sieve keeps each box the partners of its run of 9
    // consecutive indices, which keep all their 36 pairs (2,000 / 9 runs: about 8,000 pairs).
    // Were each box's candidates the same few lowest indices, most boxes would keep none.
    EXPECT_GT(world.last_step().pairs, 2000u + 2000u * 2) << "step " << n;
  }
}

}  // namespace spawn_overlap_test
}  // namespace elan
