// SPDX-License-Identifier: MIT
// The direct solve's depth rule (solver/direct_solve.hpp, kDirectDepth): a face pressed into a
// static body deeper than kDirectDepth is solved directly only while it sinks, its patch centre
// closing faster than kDirectGive a step and no point as fast as kDirectRestSpeed. A body that
// strikes the ground, one being pushed out after an impact and one held at rest are no load: a
// lone manifold of theirs is left to the passes, which settle it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/world/world_access.hpp"
#include "physics/physics_util.hpp"
#include "solver/direct_solve.hpp"

namespace elan {
namespace direct_sinking_test {

using test::add_body;
using test::at;
using test::kDt;

constexpr Real kHalf = Real(0.25);   // a cube of 0.5 m
constexpr Real kDepth = Real(0.01);  // twice kDirectDepth

struct Landing {
  bool direct = false;  // the first step solved a system directly
  Real rest_y = 0;      // the cube's centre after 2 s
};

// A cube pressed kDepth into the ground's top (y = 0), face down, moving at `vy`: whether the
// first step took its one manifold into the direct solve, and where it rests 2 s later.
Landing land(Real vy) {
  World world;
  test::add_ground(world);
  BodyDef d = at(Vec3(0, kHalf - kDepth, 0));
  d.linear_velocity = Vec3(0, vy, 0);
  const BodyId cube = add_body(world, test::box_shape(Vec3(kHalf, kHalf, kHalf)), d);
  world.step(kDt);
  Landing out;
  out.direct = !detail::state_of(world).solver.direct.systems.empty();
  for (int s = 1; s < int(std::lround(Real(2) / kDt)); ++s) {
    world.step(kDt);
    EXPECT_TRUE(test::all_finite(world)) << "vy " << vy << " step " << s;
  }
  out.rest_y = world.position(cube).y();
  std::printf("vy %+.2f m/s: direct %d, rests at %.5f m\n", double(vy), int(out.direct),
              double(out.rest_y));
  return out;
}

static_assert(kDepth > detail::kDirectDepth);

// Coming in at 5 m/s (an impact, faster than kDirectRestSpeed), going out at 0.5 m/s (pushed
// out), and still (held): none is sinking, so none is a direct system. Each settles in the passes
// on the ground within the soft rows' give (a single cube's is g / omega^2, 0.1 mm) and a
// millimetre for rounding and the speculative margin.
TEST(DirectSinking, DeepFaceThatIsNotSinkingIsLeftToThePasses) {
  for (const Real vy : {Real(-5), Real(0.5), Real(0)}) {
    const Landing l = land(vy);
    EXPECT_FALSE(l.direct) << "vy " << vy;
    EXPECT_NEAR(l.rest_y, kHalf, Real(0.001)) << "vy " << vy;
  }
}

// Coming in at 0.2 m/s, slower than an impact but faster than kDirectGive a step (0.03 m/s at
// 60 Hz): sinking, so its lone manifold is solved directly, and it rests as the others do.
TEST(DirectSinking, DeepFaceThatSinksIsSolvedDirectly) {
  const Landing l = land(Real(-0.2));
  EXPECT_TRUE(l.direct);
  EXPECT_NEAR(l.rest_y, kHalf, Real(0.001));
}

}  // namespace direct_sinking_test
}  // namespace elan
