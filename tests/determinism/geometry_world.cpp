// SPDX-License-Identifier: MIT
// A world with a mesh terrain, a heightfield beside it (with a hole) and bodies of every shape
// (compounds among them) raining on both: the same state hash every step at 1 to 4 threads and with
// both broadphases (geometry_determinism.cpp checks a denser pile at 1 and 2); a snapshot restored
// and a rollback state rolled back to continue bit for bit, and a rollback frame holds no mesh.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <vector>

#include "elan/snapshot.hpp"
#include "physics/geometry_util.hpp"

namespace elan {
namespace geometry_world_test {

using test::at;
using test::kDt;

constexpr int kSteps = 120;

World geometry_world(int threads, BroadphaseType broadphase) {
  WorldDef def;
  def.threads = threads;
  def.broadphase = broadphase;
  World world(def);
  test::Terrain mesh_terrain;  // x and z in [-8, 8]
  test::add_body(world, test::mesh_shape(mesh_terrain),
                 at(Vec3(mesh_terrain.x0, 0, mesh_terrain.z0), MotionType::Static));
  test::Terrain field_terrain;  // beside it, x in [8, 24]
  field_terrain.x0 = 8;
  ShapeDef field = test::heightfield_shape(field_terrain);
  // A hole in it under the rain, samples x in [14, 15] and z in [-1, 0]: some bodies fall through.
  for (int j = 14; j <= 16; ++j) {
    for (int i = 12; i <= 14; ++i) {
      field.heights[std::size_t(j * (field_terrain.cells + 1) + i)] =
          std::numeric_limits<Real>::quiet_NaN();
    }
  }
  test::add_body(world, field, at(Vec3(field_terrain.x0, 0, field_terrain.z0), MotionType::Static));
  const ShapeId shapes[] = {
      world.create_shape(test::sphere_shape(Real(0.2))),
      world.create_shape(test::box_shape(Vec3(Real(0.25), Real(0.15), Real(0.2)))),
      world.create_shape(test::capsule_shape(Real(0.12), Real(0.2))),
      world.create_shape(test::cylinder_shape(Real(0.18), Real(0.15))),
      world.create_shape(test::hull_shape(Real(0.3))),
      world.create_shape(test::table_shape()),
      world.create_shape(test::l_shape()),
      world.create_shape(test::dumbbell_shape()),
  };
  // 8 x 2 x 8 bodies over each surface, close enough to pile on one another.
  int k = 0;
  for (int surface = 0; surface < 2; ++surface) {
    for (int y = 0; y < 2; ++y) {
      for (int z = 0; z < 8; ++z) {
        for (int x = 0; x < 8; ++x, ++k) {
          const Vec3 p(Real(surface * 16 - 5) + Real(x) * Real(1.2), Real(1.5) + Real(y),
                       Real(-5) + Real(z) * Real(1.2));
          BodyDef d = at(p);
          d.shape = shapes[k % 8];
          d.orientation =
              Quat(Eigen::AngleAxis<Real>(Real(0.3) * Real(k % 11), Vec3(1, 1, 0).normalized()));
          d.angular_velocity = Vec3(0, Real(k % 5) - 2, 0);
          world.create_body(d);
        }
      }
    }
  }
  return world;
}

std::vector<uint64_t> run(World& world, int steps) {
  std::vector<uint64_t> out;
  for (int s = 0; s < steps; ++s) {
    world.step(kDt);
    out.push_back(world.state_hash());
  }
  return out;
}

TEST(GeometryWorld, SameHashesForAnyThreadCountAndBroadphase) {
  World reference_world = geometry_world(1, BroadphaseType::SweepAndPrune);
  const std::vector<uint64_t> reference = run(reference_world, kSteps);
  EXPECT_TRUE(test::all_finite(reference_world));
  EXPECT_GT(reference_world.last_step().contacts, 200u) << "the bodies landed and touch";
  int fell = 0;  // through the heightfield's hole
  for (std::size_t i = 2; i < reference_world.body_count(); ++i) {
    fell += reference_world.position(reference_world.body_at(i)).y() < -5;
  }
  EXPECT_GT(fell, 0);
  for (BroadphaseType broadphase : {BroadphaseType::SweepAndPrune, BroadphaseType::AllPairs}) {
    for (int threads = 1; threads <= 4; ++threads) {
      // The sanitized runs check 2 threads (the code under 3 and 4 is the same, with other block
      // boundaries, and one thread runs no task a sanitizer could catch racing); the optimised
      // build checks all four.
      if (test::kSanitized && threads != 2) continue;
      SCOPED_TRACE(testing::Message() << threads << " threads, broadphase " << int(broadphase));
      World world = geometry_world(threads, broadphase);
      EXPECT_EQ(run(world, kSteps), reference);
    }
  }
}

TEST(GeometryWorld, SnapshotAndRollbackContinueBitForBit) {
  World world = geometry_world(2, BroadphaseType::SweepAndPrune);
  run(world, 40);
  const std::vector<uint8_t> snapshot = save_snapshot(world);
  const std::vector<uint8_t> rollback = save_rollback(world);
  const std::vector<uint64_t> expected = run(world, 50);

  World loaded = load_snapshot(snapshot);
  EXPECT_EQ(run(loaded, 50), expected);

  restore_rollback(world, rollback);
  world.set_threads(1);
  EXPECT_EQ(run(world, 50), expected);
}

// A rollback frame holds the bodies' state and contacts, never the shapes: a world with a mesh of
// 100k triangles saves a frame no larger than the same world without it (but for the bodies'
// manifolds).
TEST(GeometryWorld, RollbackFramesDoNotCopyTheMesh) {
  WorldDef def;
  def.threads = 1;
  World with_mesh(def), without(def);
  test::Terrain big;
  big.cells = 224;  // 100,352 triangles
  big.spacing = Real(0.25);
  big.x0 = big.z0 = -28;
  test::add_body(with_mesh, test::mesh_shape(big),
                 at(Vec3(big.x0, -5, big.z0), MotionType::Static));
  for (World* w : {&with_mesh, &without}) {
    test::add_body(*w, test::sphere_shape(Real(0.3)), at(Vec3(0, 5, 0)));
  }
  const std::size_t bytes = save_rollback(with_mesh).size();
  EXPECT_LT(bytes, save_rollback(without).size() + 64);
  EXPECT_GT(save_snapshot(with_mesh).size(), std::size_t(100352) * 12) << "a snapshot keeps it";
}

}  // namespace geometry_world_test
}  // namespace elan
