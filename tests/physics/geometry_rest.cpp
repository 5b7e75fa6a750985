// SPDX-License-Identifier: MIT
// Bodies of every shape dropped on a bumpy terrain, as a heightfield and as a mesh of the same
// surface, come to rest on it: none below it, all asleep or nearly still.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "physics/geometry_util.hpp"

namespace elan {
namespace geometry_rest_test {

using test::at;
using test::kDt;

struct Dropped {
  BodyId id;
  Real reach;  // m: the least distance from the centre of mass to the shape's surface
  std::string what;
};

// Drops a 4 x 3 array of bodies of every shape (sphere, box, capsule, cylinder, hull, compounds),
// turned every which way, from 1.5 m above the surface, and lets them settle for 12 s.
void drop_and_settle(bool as_mesh) {
  const test::Terrain terrain;
  WorldDef def;
  def.threads = 2;
  World world(def);
  BodyDef ground = at(Vec3(terrain.x0, 0, terrain.z0), MotionType::Static);
  test::add_body(world, as_mesh ? test::mesh_shape(terrain) : test::heightfield_shape(terrain),
                 ground);
  struct Kind {
    ShapeDef shape;
    Real reach;
    const char* name;
  };
  const std::vector<Kind> kinds = {
      {test::sphere_shape(Real(0.25)), Real(0.25), "sphere"},
      {test::box_shape(Vec3(Real(0.3), Real(0.2), Real(0.25))), Real(0.2), "box"},
      {test::capsule_shape(Real(0.15), Real(0.25)), Real(0.15), "capsule"},
      {test::cylinder_shape(Real(0.2), Real(0.2)), Real(0.2), "cylinder"},
      {test::hull_shape(Real(0.35)), Real(0.1), "hull"},
      {test::table_shape(), Real(0.02), "table"},
      {test::l_shape(), Real(0.04), "L"},
      {test::dumbbell_shape(), Real(0.05), "dumbbell"},
  };
  std::vector<Dropped> dropped;
  int k = 0;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col, ++k) {
      const Kind& kind = kinds[std::size_t(k) % kinds.size()];
      const Real x = Real(-4.5) + Real(3) * Real(col), z = Real(-3) + Real(3) * Real(row);
      BodyDef d = at(Vec3(x, terrain.surface(x, z) + Real(1.5), z));
      d.orientation = Quat(Eigen::AngleAxis<Real>(Real(0.4) * Real(k + 1),
                                                  Vec3(Real(k % 3), 1, Real(k % 2)).normalized()));
      // Nothing resists rolling: a ball or a dumbbell in a valley of the hills would rock for
      // ever (a rolling ball's motion decays only at 2/7 of the angular damping). Damping stands
      // in for rolling resistance and air, so that every body can settle within the run.
      d.angular_damping = 3;
      d.linear_damping = Real(0.5);
      dropped.push_back({test::add_body(world, kind.shape, d), kind.reach, kind.name});
    }
  }
  for (int n = 0; n < 720; ++n) world.step(kDt);
  for (const Dropped& b : dropped) {
    SCOPED_TRACE(b.what);
    const Vec3 c = world.center_of_mass(b.id);
    // On the surface, not in it: the centre stands at least its reach above the surface under
    // it (less 2 cm: the resting penetration is millimetres, and on a slope the nearest surface
    // point is not straight below, which only makes the vertical gap larger).
    EXPECT_GT(c.y() - terrain.surface(c.x(), c.z()), b.reach - Real(0.02));
    // Not far above it either: it landed (no body is taller than 1 m).
    EXPECT_LT(c.y() - terrain.surface(c.x(), c.z()), Real(1));
    // At rest: asleep, or still to within what the sleep threshold lets through.
    EXPECT_TRUE(!world.is_awake(b.id) || world.linear_velocity(b.id).norm() < Real(0.05))
        << "speed " << world.linear_velocity(b.id).norm();
  }
  EXPECT_TRUE(test::all_finite(world));
}

TEST(GeometryRest, EveryShapeRestsOnAHeightfield) {
  drop_and_settle(false);
}

TEST(GeometryRest, EveryShapeRestsOnAMeshTerrain) {
  drop_and_settle(true);
}

// A flat heightfield (10 x 10 samples 1 m apart, at y = 0) with a hole at sample (4, 4): the six
// triangles around it are gone, a hexagon from (3, 3) to (5, 5). Bodies over the hole fall
// through it freely; bodies beside it, one on the triangle its cell keeps, rest on the surface.
TEST(GeometryRest, BodiesOverAHoleFallThroughItAndBesideItRest) {
  WorldDef def;
  def.threads = 2;
  World world(def);
  ShapeDef field;
  field.type = ShapeType::Heightfield;
  field.columns = 10;
  field.heights.assign(100, 0);
  field.heights[4 * 10 + 4] = std::numeric_limits<Real>::quiet_NaN();
  const BodyId ground = test::add_body(world, field, at(Vec3::Zero(), MotionType::Static));
  const Real r = Real(0.1), y0 = 1;
  const ShapeDef ball = test::sphere_shape(r);
  // Over the hole: cell (3, 3), which lost both triangles; the centroid of the triangle cell
  // (4, 3) lost (corners (4, 3), (4, 4), (5, 4)); a box smaller than the hole, 0.2 m inside its
  // rim.
  const Vec3 falling_at[] = {Vec3(Real(3.6), y0, Real(3.7)), Vec3(Real(13) / 3, y0, Real(11) / 3),
                             Vec3(Real(4.1), y0, Real(4.4))};
  std::vector<BodyId> falling = {
      test::add_body(world, ball, at(falling_at[0])),
      test::add_body(world, ball, at(falling_at[1])),
      test::add_body(world, test::box_shape(Vec3::Constant(Real(0.2))), at(falling_at[2]))};
  // Beside it: the centroid of the triangle cell (4, 3) keeps (corners (4, 3), (5, 4), (5, 3)),
  // 0.24 m from the hole's rim; a box well clear of it.
  const BodyId kept = test::add_body(world, ball, at(Vec3(Real(14) / 3, y0, Real(10) / 3)));
  const BodyId box = test::add_body(world, test::box_shape(Vec3::Constant(Real(0.2))),
                                    at(Vec3(Real(1.5), y0, Real(1.5))));
  const int steps = 60;
  for (int n = 0; n < steps; ++n) world.step(kDt);
  // Free fall, y0 - g t^2 / 2 at t = 1 s: 4.905 m. The substeps' semi-implicit Euler drops
  // g h^2 N (N + 1) / 2 over N substeps of h, (N + 1) / N times that: 0.4 % more at 240 substeps.
  // 1 % of the drop holds it; a body that touched the surface on the way would be metres off.
  const Real t = Real(steps) * kDt, drop = Real(0.5) * Real(9.81) * t * t;
  for (std::size_t k = 0; k < falling.size(); ++k) {
    SCOPED_TRACE("falling body " + std::to_string(k));
    const Vec3 p = world.center_of_mass(falling[k]);
    EXPECT_NEAR(y0 - p.y(), drop, Real(0.01) * drop);
    // Straight down: nothing pushed it sideways or turned it.
    EXPECT_NEAR(p.x(), falling_at[k].x(), Real(1e-4));
    EXPECT_NEAR(p.z(), falling_at[k].z(), Real(1e-4));
    EXPECT_LT(world.angular_velocity(falling[k]).norm(), Real(1e-4));
  }
  // Resting: the centre its reach above the plane, less the resting penetration (millimetres).
  EXPECT_NEAR(world.center_of_mass(kept).y(), r, Real(0.005));
  EXPECT_NEAR(world.center_of_mass(box).y(), Real(0.2), Real(0.005));
  for (const BodyId b : {kept, box}) {
    EXPECT_TRUE(!world.is_awake(b) || world.linear_velocity(b).norm() < Real(0.05));
  }
  // A ray down through the hole finds nothing (the fallen bodies are below its reach); one beside
  // it hits the surface.
  EXPECT_FALSE(world.cast_ray(Vec3(Real(13) / 3, 5, Real(11) / 3), Vec3(0, -1, 0), Real(5.5)));
  const auto hit = world.cast_ray(Vec3(Real(2.5), 5, Real(2.5)), Vec3(0, -1, 0), Real(5.5));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->body, ground);
  EXPECT_NEAR(hit->distance, 5, Real(1e-5));
  EXPECT_TRUE(test::all_finite(world));
}

}  // namespace geometry_rest_test
}  // namespace elan
