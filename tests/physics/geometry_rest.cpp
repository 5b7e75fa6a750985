// SPDX-License-Identifier: MIT
// Bodies of every shape dropped on a bumpy terrain, as a heightfield and as a mesh of the same
// surface, come to rest on it: none below it, all asleep or nearly still.
#include <gtest/gtest.h>

#include <cmath>
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

}  // namespace geometry_rest_test
}  // namespace elan
