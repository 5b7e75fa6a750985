// SPDX-License-Identifier: MIT
// Mass ratios in contact: a heavy box resting on a light one, and stacks of mixed masses. A soft
// contact row is a spring on its effective mass, which a light body makes small, so under a heavy
// load it gives F / (m_eff omega^2); the loaded rows are solved directly (solver/direct_solve.hpp)
// and must hold whatever the ratio.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/world/world_access.hpp"
#include "physics/physics_util.hpp"

namespace elan {
namespace mass_ratio_test {

using test::add_body;
using test::at;
using test::kDt;

constexpr Real kHalf = Real(0.25);  // the boxes are cubes of 0.5 m

World make_world(int threads = 2) {
  WorldDef def;
  def.threads = threads;
  World world(def);
  test::add_ground(world);
  return world;
}

// A cube of 0.5 m of `mass` kg resting on the ground (bottom face at y = base).
BodyId add_cube(World& world, Real mass, Real base) {
  BodyDef d = at(Vec3(0, base + kHalf, 0));
  d.mass = mass;
  return add_body(world, test::box_shape(Vec3(kHalf, kHalf, kHalf)), d);
}

struct Press {
  Real worst = 0;     // m: the most the top box sank below its resting height over the run
  Real sideways = 0;  // m: the most the bottom box moved sideways
  bool stacked = true;
};

// A box of `heavy` kg on a 1 kg box on the ground, both placed touching, stepped for `seconds`.
Press heavy_on_light(Real heavy, Real seconds) {
  World world = make_world();
  const BodyId light = add_cube(world, 1, 0);
  const BodyId top = add_cube(world, heavy, 2 * kHalf);
  const Real rest = 3 * kHalf;  // the top box's centre height with rigid contacts
  Press out;
  const int steps = int(std::lround(seconds / kDt));
  for (int s = 0; s < steps; ++s) {
    world.step(kDt);
    EXPECT_TRUE(test::all_finite(world));
    out.worst = std::max(out.worst, rest - world.position(top).y());
    const Vec3 p = world.position(light);
    out.sideways = std::max(out.sideways, Vec3(p.x(), 0, p.z()).norm());
    out.stacked = out.stacked && world.position(top).y() > p.y() + Real(1.5) * kHalf;
  }
  std::printf("%g kg on 1 kg: top sank at most %.5f m, light box moved %.5f m sideways\n",
              double(heavy), double(out.worst), double(out.sideways));
  return out;
}

// 500 kg on 1 kg: the top box's sink is both contacts' penetration, the light box's pressing
// into the ground and the heavy one's into it. Soft rows give 2.4 cm; the bound is 5 mm.
TEST(MassRatio, HeavyBoxPressesLightBoxLittle) {
  const Press p = heavy_on_light(500, 5);
  EXPECT_LT(p.worst, Real(0.005));
  EXPECT_LT(p.sideways, Real(0.005));
  EXPECT_TRUE(p.stacked);
}

// 1e6 kg on 1 kg: with soft rows the light box is squeezed out sideways. It must stay under the
// heavy one (within 1 cm of where it was) and the heavy one on it. The direct rows keep a
// compliance of 1e-6 of their diagonal (direct_solve.cpp), a give of about 4 cm at this load on
// the light box's effective mass: 5 cm bounds the sink.
TEST(MassRatio, MillionToOneDoesNotSqueezeTheLightBoxOut) {
  const Press p = heavy_on_light(Real(1e6), 5);
  EXPECT_TRUE(p.stacked);
  EXPECT_LT(p.sideways, Real(0.01));
  EXPECT_LT(p.worst, Real(0.05));
}

// A column of ten cubes with the given masses, bottom first, placed touching: it must stand
// (the top within 2 cm of its start, 2 cm being a twenty-fifth of a cube) and fall asleep.
void expect_column_stands_and_sleeps(const std::vector<Real>& masses, const char* name) {
  World world = make_world();
  std::vector<BodyId> cubes;
  for (std::size_t k = 0; k < masses.size(); ++k) {
    cubes.push_back(add_cube(world, masses[k], 2 * kHalf * Real(k)));
  }
  const BodyId top = cubes.back();
  const Vec3 start = world.position(top);
  Real moved = 0;
  const int steps = int(std::lround(Real(10) / kDt));
  for (int s = 0; s < steps; ++s) {
    world.step(kDt);
    ASSERT_TRUE(test::all_finite(world)) << name << " step " << s;
    moved = std::max(moved, (world.position(top) - start).norm());
  }
  std::printf("%s: top moved at most %.5f m; awake at 10 s: %zu\n", name, double(moved),
              world.last_step().awake);
  EXPECT_LT(moved, Real(0.02)) << name;
  EXPECT_EQ(world.last_step().awake, 0u) << name;
}

TEST(MassRatio, MixedMassColumnsStandAndSleep) {
  std::vector<Real> up, down, alternating;
  for (int k = 0; k < 10; ++k) {
    up.push_back(std::pow(Real(2), Real(k)));        // heavy on light: 1 kg to 512 kg
    down.push_back(std::pow(Real(2), Real(9 - k)));  // light on heavy
    alternating.push_back(k % 2 == 0 ? Real(1) : Real(100));
  }
  expect_column_stands_and_sleeps(up, "heavy on light");
  expect_column_stands_and_sleeps(down, "light on heavy");
  expect_column_stands_and_sleeps(alternating, "alternating 1 and 100 kg");
}

// A column of four 0.5 m cubes of the given masses (bottom first), placed touching, stepped for
// 3 s: the most the top sank below its rigid height over the last second, and whether any step
// solved a system directly.
struct ShortColumn {
  Real settled_sink = 0;
  bool direct = false;
};
ShortColumn short_column(const std::vector<Real>& masses) {
  World world = make_world();
  std::vector<BodyId> cubes;
  for (std::size_t k = 0; k < masses.size(); ++k) {
    cubes.push_back(add_cube(world, masses[k], 2 * kHalf * Real(k)));
  }
  const Real rest = world.position(cubes.back()).y();
  ShortColumn out;
  const int steps = int(std::lround(Real(3) / kDt));
  for (int s = 0; s < steps; ++s) {
    world.step(kDt);
    EXPECT_TRUE(test::all_finite(world)) << "step " << s;
    if (s >= steps - int(std::lround(Real(1) / kDt))) {
      out.settled_sink = std::max(out.settled_sink, rest - world.position(cubes.back()).y());
    }
    out.direct = out.direct || !detail::state_of(world).solver.direct.systems.empty();
  }
  return out;
}

// Four even cubes on the ground are a short stack of even masses (detail::kDirectShortStack):
// left to the passes, their rows give as soft springs, F / (m_eff omega^2) each. The header's
// figure for one 0.5 m cube on another is 0.2 mm, so the contacts under three, two and one cube
// give about 0.6 + 0.4 + 0.2 mm, and the ground's under four, twice as stiff in frequency, a
// quarter of 0.8 mm: 1.4 mm in all. 2 mm bounds it; a load the passes did not carry would sink
// the top by a give per pass, far past it.
TEST(MassRatio, ShortEvenColumnIsLeftToThePassesAndHolds) {
  const ShortColumn even = short_column({1, 1, 1, 1});
  std::printf("four even cubes: top sank %.5f m, direct %d\n", double(even.settled_sink),
              int(even.direct));
  EXPECT_FALSE(even.direct);
  EXPECT_LT(even.settled_sink, Real(0.002));
  EXPECT_GT(even.settled_sink, Real(0));
}

// The same column with a top ten times heavier is past detail::kDirectEvenMass: its loaded rows
// are solved directly on some step, and the column holds within the even column's bound (a light
// body under a heavy one is what the passes cannot carry).
TEST(MassRatio, HeavyTopOnShortColumnIsSolvedDirectly) {
  const ShortColumn heavy = short_column({1, 1, 1, 10});
  std::printf("three cubes under a tenfold one: top sank %.5f m, direct %d\n",
              double(heavy.settled_sink), int(heavy.direct));
  EXPECT_TRUE(heavy.direct);
  EXPECT_LT(heavy.settled_sink, Real(0.002));
}

}  // namespace mass_ratio_test
}  // namespace elan
