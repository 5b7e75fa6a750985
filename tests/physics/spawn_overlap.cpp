// SPDX-License-Identifier: MIT
// Bodies spawned on top of each other (issue 42's abuse scenes): the push-out that separates
// them is capped (SolveSettings::max_push_velocity, Box2D v3's contactPushMaxVelocity), a body
// overlapping many others shares the cap among its deep contacts (color_contacts.hpp) and keeps
// no more of it as velocity (push_out_cap.hpp), so they part gently instead of flying apart;
// and each body keeps a bounded number of deep pairs (deep_pairs.hpp), so the step's work grows
// with the bodies, not with their square.
#include <gtest/gtest.h>

#include <algorithm>

#include "physics/physics_util.hpp"

namespace elan {
namespace spawn_overlap_test {

using test::add_body;
using test::at;
using test::kDt;

// The reproducer physics_100_boxes_one_point_explode.json: 100 unit boxes of 1000 kg created at
// one point on a static slab. Without the share each pair pushed at the cap and the pairs
// chained: 29 m/s after the first step, 67 m/s later. Over the first quarter second, while every
// box still overlaps most of the others, no box may move faster than the cap (3 m/s) plus what
// gravity adds in one step, g dt = 0.16 m/s (a box lifted off the slab falls back onto it).
// Checked over the first 45 steps (three quarters of a second), while a body still has more
// than kPushShare deep contacts; after about 50 the boxes, lined up on one axis, still throw
// their ends out at up to 26 m/s (not fixed: see bench/results/amd-epyc/cliffs.md).
TEST(SpawnOverlap, HundredBoxesAtOnePointPartNoFasterThanThePushCap) {
  WorldDef def;
  def.threads = 1;
  World world(def);
  BodyDef ground = at(Vec3(0, -1, 0), MotionType::Static);
  add_body(world, test::box_shape(Vec3(50, 1, 50)), ground);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 100; ++i) {
    boxes.push_back(
        add_body(world, test::box_shape(Vec3::Constant(Real(0.5))), at(Vec3(0, Real(0.5), 0))));
  }
  const Real cap = 3;
  const Real tolerance = Real(9.81) * kDt;
  Real fastest = 0;
  for (int n = 1; n <= 45; ++n) {
    world.step(kDt);
    ASSERT_TRUE(test::all_finite(world));
    for (const BodyId b : boxes) fastest = std::max(fastest, world.linear_velocity(b).norm());
    ASSERT_LE(fastest, cap + tolerance) << "step " << n;
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
}

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
