// SPDX-License-Identifier: MIT
// The abuse scenes of scenes/abuse/ (bench/make_abuse_scenes.py): what users do build at the
// edges of the supported ranges. Each runs a few hundred steps and stays finite and bounded: no
// body frozen for a non-finite state, every body inside the supported positions, and no speed
// beyond what the scene's own energy allows. Their step times are benchmarks
// (bench/abuse_scenes.cpp), not asserted here.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "elan/limits.hpp"
#include "physics/physics_util.hpp"

namespace elan {
namespace abuse_scenes_test {

class AbuseScenes : public testing::TestWithParam<std::string> {};

TEST_P(AbuseScenes, StayFiniteAndBounded) {
  Real dt = 0;
  World world = test::load_world("abuse/" + GetParam() + ".json", 2, dt);
  Real v0 = 0, w0 = 0;
  for (std::size_t i = 0; i < world.body_count(); ++i) {
    const BodyId b = world.body_at(i);
    v0 = std::max(v0, world.linear_velocity(b).norm());
    w0 = std::max(w0, world.angular_velocity(b).norm());
  }
  const Real g = world.settings().gravity.norm();
  const int steps = test::kSanitized ? 120 : 300;
  for (int k = 1; k <= steps; ++k) {
    const uint32_t status = world.step(dt);
    ASSERT_EQ(status & kStepFrozeNonFinite, 0u) << "step " << k;
    ASSERT_TRUE(test::all_finite(world)) << "step " << k;
    // Bounds: a body's speed comes from its start, gravity's work and the push-out of
    // overlapping spawns (limited to a few tens of m/s, the solver's maximum push-out speed,
    // with the rest as margin): 100 m/s over v0 + g t. A torque-free spin keeps its angular
    // momentum, so its rate changes by at most the ratio of the principal inertias (at most
    // 10 for these shapes); contacts only take energy away.
    const Real v_max = v0 + g * dt * Real(k) + 100;
    const Real w_max = 10 * std::max(w0, Real(100));
    for (std::size_t i = 0; i < world.body_count(); ++i) {
      const BodyId b = world.body_at(i);
      ASSERT_LE(world.position(b).cwiseAbs().maxCoeff(), Real(limits::kMaxPosition))
          << "body " << i << " step " << k;
      ASSERT_LE(world.linear_velocity(b).norm(), v_max) << "body " << i << " step " << k;
      ASSERT_LE(world.angular_velocity(b).norm(), w_max) << "body " << i << " step " << k;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, AbuseScenes,
                         testing::Values("spawn100", "tiny_on_huge", "heavy_on_light",
                                         "fast_bodies", "high_gravity", "reference_pile100"));

}  // namespace abuse_scenes_test
}  // namespace elan
