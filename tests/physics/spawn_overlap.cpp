// SPDX-License-Identifier: MIT
// Bodies spawned on top of each other (issue 42's abuse scenes): the push-out that separates
// them is capped (SolveSettings::max_push_velocity, Box2D v3's contactPushMaxVelocity), and a
// body overlapping many others shares the cap among its deep contacts (color_contacts.hpp), so
// they part gently instead of flying apart.
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
  for (int n = 1; n <= 15; ++n) {
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

}  // namespace spawn_overlap_test
}  // namespace elan
