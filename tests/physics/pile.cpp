// SPDX-License-Identifier: MIT
// A pile of mixed bodies (boxes, spheres, capsules, hulls) dropped into a walled container
// settles: no non-finite state, nothing leaves the container, kinetic energy near zero by 15 s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "physics/physics_util.hpp"

namespace elan {
namespace pile_test {

using test::add_body;
using test::at;

struct Container {
  Real inner_half = 0;  ///< m: the walls' inner faces are at |x|, |z| = inner_half
  Real height = 0;      ///< m: wall height above the ground y = 0
};

// A deterministic mixed pile of nx * ny * nz bodies on a grid above a ground inside four walls.
Container build_mixed_pile(World& world, int nx, int ny, int nz) {
  const Real spacing = Real(1.1);
  const Container c{Real(0.5) * spacing * Real(std::max(nx, nz)) + Real(0.3),
                    spacing * Real(ny) + 2};
  const Real wall = Real(0.5);
  add_body(world, test::box_shape(Vec3(c.inner_half + 2 * wall, 1, c.inner_half + 2 * wall)),
           at(Vec3(0, -1, 0), MotionType::Static));
  const Real h = Real(0.5) * c.height;
  for (int side = -1; side <= 1; side += 2) {
    const Real off = Real(side) * (c.inner_half + wall);
    add_body(world, test::box_shape(Vec3(wall, h, c.inner_half + 2 * wall)),
             at(Vec3(off, h, 0), MotionType::Static));
    add_body(world, test::box_shape(Vec3(c.inner_half, h, wall)),
             at(Vec3(0, h, off), MotionType::Static));
  }
  uint32_t seed = 12345;
  auto uniform = [&](Real lo, Real hi) {
    seed = seed * 1664525u + 1013904223u;  // Numerical Recipes LCG: same pile on every platform
    return lo + (hi - lo) * Real(seed >> 8) / Real(1u << 24);
  };
  std::vector<ShapeId> shapes;
  for (int k = 0; k < 16; ++k) {
    ShapeDef s;
    switch (k % 4) {
      case 0:
        s = test::box_shape(Vec3(uniform(Real(0.2), Real(0.45)), uniform(Real(0.2), Real(0.45)),
                                 uniform(Real(0.2), Real(0.45))));
        break;
      case 1:
        s = test::sphere_shape(uniform(Real(0.25), Real(0.45)));
        break;
      case 2:
        s = test::capsule_shape(uniform(Real(0.15), Real(0.25)), uniform(Real(0.1), Real(0.25)));
        break;
      default:
        s.type = ShapeType::ConvexHull;
        for (int p = 0; p < 12; ++p) {
          s.points.push_back(Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)).normalized() *
                             Real(0.42));
        }
        break;
    }
    shapes.push_back(world.create_shape(s));
  }
  const Real x0 = -Real(0.5) * spacing * Real(nx - 1), z0 = -Real(0.5) * spacing * Real(nz - 1);
  for (int y = 0; y < ny; ++y) {
    for (int z = 0; z < nz; ++z) {
      for (int x = 0; x < nx; ++x) {
        BodyDef d =
            at(Vec3(x0 + spacing * Real(x), Real(0.6) + spacing * Real(y), z0 + spacing * Real(z)));
        d.orientation = Quat(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
        d.shape = shapes[std::size_t(uniform(0, Real(15.99)))];
        world.create_body(d);
      }
    }
  }
  return c;
}

// Runs `seconds` and checks every step for non-finite state, then at the end that every
// dynamic body's centre of mass is inside the container (inner faces, above the ground) and that
// the pile has come to rest: the median over the last third of the run of its kinetic energy is
// below 2e-2 J per body, every body moving at about 1 cm/s (they weigh 60-950 kg). pile1k has
// 5e3 J per body at impact and a median of 0.1-0.15 J per body while it slides and rolls apart
// (2.5-7.5 s).
//
// Why a median over time and not the energy at the end: a settled pile of spheres and hulls
// still slumps now and then (a body slides off a rolling sphere; frictionless rolling has no
// damping), a few bodies move at up to 3 m/s for a fraction of a second, and the energy at one
// instant is a draw from that chaos. pile1k with every body nudged by up to 1 mm (12 draws) had
// 0-43 J at 15 s: 8 of the 12 over the former limit of 1e-3 J per body with the colour-by-colour
// solver, 6 with the one that solves the pile's two halves apart; their medians over 10-15 s
// were 0-16 and 0-8 J. A defect that keeps a few bodies moving slowly (the spinning spheres
// below: 5.26 J at 15 s) is not told apart from that here, and is checked where its physics is
// (Contact.SpinningSphereSlowsAtTorsionalFrictionRate).
void expect_settles(World& world, const Container& c, Real dt, Real seconds) {
  const int steps = int(std::lround(seconds / dt));
  std::vector<Real> tail_energy;
  for (int n = 1; n <= steps; ++n) {
    const uint32_t status = world.step(dt);
    ASSERT_EQ(status & kStepFrozeNonFinite, 0u) << "a body went non-finite at step " << n;
    if (3 * n > 2 * steps) tail_energy.push_back(world.kinetic_energy());
  }
  ASSERT_TRUE(test::all_finite(world));
  std::size_t dynamic = 0, outside = 0;
  for (std::size_t i = 0; i < world.body_count(); ++i) {
    const BodyId id = world.body_at(i);
    if (world.motion_type(id) != MotionType::Dynamic) continue;
    ++dynamic;
    const Vec3 x = world.center_of_mass(id);
    if (std::abs(x.x()) > c.inner_half || std::abs(x.z()) > c.inner_half || x.y() < 0) {
      ++outside;
      ADD_FAILURE() << "body " << i << " escaped to " << x.transpose();
      if (outside > 5) break;
    }
  }
  std::sort(tail_energy.begin(), tail_energy.end());
  const Real median = tail_energy[tail_energy.size() / 2];
  std::printf(
      "pile of %zu: median KE %.4g J over the last third, %.4g J at %.1f s, awake %zu, "
      "outside %zu\n",
      dynamic, double(median), double(world.kinetic_energy()), double(seconds),
      world.last_step().awake, outside);
  EXPECT_LT(median, Real(2e-2) * Real(dynamic))
      << "pile still moving after " << seconds << " s, awake " << world.last_step().awake;
}

// Regression: a one-point contact had no twist lever, hence no torsional friction, so spheres
// pinched between two bodies spun about the normal for ever (|w| r above the sleep threshold)
// and kept the pile's single island awake: 5.26 J and 994 of 1000 awake after 15 s. The solver
// now gives every manifold a 5 mm torsional patch. Settling of this pile is sensitive to solver
// changes. Two ways it has failed, when this fails look there first: a hull contact alternating
// between 2 and 1 points re-wakes its island; and a one-point edge-edge contact under a heavy
// load, exactly re-tested every step, falls into a two-step cycle (its normal turns by 0.1
// degree and its impulse swaps between 46 and 24 N s from one step to the next) that keeps
// its neighbours moving at 1 cm/s. The second once came with a change of rounding only
// (deriving B's contact arm from A's, as the engine now does) when this test read the kinetic
// energy at 15 s alone; the median over the last third is what tells a settled pile from one
// that is not (12 nudged copies of pile1k: medians 0-2.6 J, the limit 20 J). 10 to 12 of 30
// copies keep one body rocking on a sphere or capsule at up to 5 cm/s (0.01-0.4 J, the island
// awake) at 15 s: frictionless rolling has no damping.
TEST(Pile, Pile1kSettlesInItsContainer) {
  Real dt = 0;
  World world = test::load_world("pile1k.json", 2, dt);
  // scenes/pile1k.json: walls' inner faces at |x|, |z| = 4.75.
  expect_settles(world, Container{Real(4.75), 10}, dt, 15);
}

// About 2k bodies in Release; under the sanitizers (10x slower) a 500-body pile of the same
// mix, so the run stays minutes, not tens of minutes.
TEST(Pile, MixedPileSettlesInItsContainer) {
  WorldDef def;
  def.threads = 2;
  World world(def);
  const Container c =
      test::kSanitized ? build_mixed_pile(world, 8, 8, 8) : build_mixed_pile(world, 13, 12, 13);
  expect_settles(world, c, test::kDt, 15);
}

}  // namespace pile_test
}  // namespace elan
