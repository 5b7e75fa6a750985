// SPDX-License-Identifier: MIT
// Bit-for-bit determinism with meshes, heightfields and compounds: a pile of every convex shape
// and of compounds falling on a bumpy mesh and a bumpy heightfield gives the same state hash at
// every step under 1 and 2 threads and both broadphases.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics/physics_util.hpp"

namespace elan {
namespace geometry_determinism_test {

constexpr int kSteps = 150;

Real bump(Real x, Real z) {
  return Real(0.3) * std::sin(Real(0.9) * x) * std::cos(Real(0.7) * z);
}

World make_world(int threads, BroadphaseType broadphase) {
  WorldDef def;
  def.threads = threads;
  def.broadphase = broadphase;
  World world(def);
  // A bumpy mesh under x < 0 and a bumpy heightfield under x > 0: convex and concave edges,
  // active and not.
  ShapeDef mesh;
  mesh.type = ShapeType::Mesh;
  const int n = 24;
  const Real s = Real(0.5);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const Real x = Real(i) * s - 12, z = Real(j) * s - 6;
      mesh.vertices.emplace_back(x, bump(x, z), z);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      mesh.triangles.push_back({a, c, d});
      mesh.triangles.push_back({a, d, b});
    }
  }
  test::add_body(world, mesh, test::at(Vec3::Zero(), MotionType::Static));
  ShapeDef field;
  field.type = ShapeType::Heightfield;
  field.columns = uint32_t(n + 1);
  field.spacing_x = field.spacing_z = s;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) field.heights.push_back(bump(Real(i) * s, Real(j) * s - 6));
  }
  test::add_body(world, field, test::at(Vec3(0, 0, -6), MotionType::Static));
  ShapeDef dumbbell;
  dumbbell.type = ShapeType::Compound;
  CompoundChild bar, end;
  bar.shape = test::capsule_shape(Real(0.08), Real(0.3));
  bar.orientation = Quat(Eigen::AngleAxis<Real>(Real(1.5707963), Vec3::UnitZ()));
  end.shape = test::box_shape(Vec3::Constant(Real(0.15)));
  dumbbell.children = {bar, end, end};
  dumbbell.children[1].position = Vec3(Real(-0.4), 0, 0);
  dumbbell.children[2].position = Vec3(Real(0.4), 0, 0);
  const ShapeDef shapes[] = {test::sphere_shape(Real(0.25)),
                             test::box_shape(Vec3(0.3f, 0.2f, 0.25f)),
                             test::capsule_shape(Real(0.15), Real(0.25)), dumbbell};
  int k = 0;
  for (int y = 0; y < 3; ++y) {
    for (int z = 0; z < 8; ++z) {
      for (int x = 0; x < 16; ++x, ++k) {
        BodyDef d = test::at(Vec3(Real(x) * Real(1.3) - 10, Real(1) + Real(y) * Real(1.1),
                                  Real(z) * Real(1.2) - 4.5f));
        d.orientation =
            Quat(Eigen::AngleAxis<Real>(Real(0.37) * Real(k), Vec3(1, 2, 3).normalized()));
        test::add_body(world, shapes[k % 4], d);
      }
    }
  }
  return world;
}

std::vector<uint64_t> hashes(int threads, BroadphaseType broadphase) {
  World world = make_world(threads, broadphase);
  std::vector<uint64_t> out;
  for (int n = 0; n < kSteps; ++n) {
    world.step(test::kDt);
    out.push_back(world.state_hash());
  }
  EXPECT_TRUE(test::all_finite(world));
  // None fell through a surface: over the surfaces, every centre is above their lowest point
  // (-0.3 m) less the largest body's reach.
  for (std::size_t i = 2; i < world.body_count(); ++i) {
    const Vec3 p = world.position(world.body_at(i));
    if (std::abs(p.x()) < Real(11.5) && std::abs(p.z()) < Real(5.5)) {
      EXPECT_GT(p.y(), Real(-0.3) - Real(0.6)) << "body " << i;
    }
  }
  return out;
}

TEST(GeometryDeterminism, HashEqualEveryStepForOneAndTwoThreadsAndBothBroadphases) {
  const std::vector<uint64_t> reference = hashes(1, BroadphaseType::SweepAndPrune);
  EXPECT_EQ(reference, hashes(2, BroadphaseType::SweepAndPrune));
  EXPECT_EQ(reference, hashes(2, BroadphaseType::AllPairs));
  EXPECT_EQ(reference, hashes(2, BroadphaseType::Tree));
  // Sanitized, a rerun adds nothing the runs above do not (Determinism.SameHashesWhenRunTwice
  // InProcess reruns in every build).
  if (!test::kSanitized) {
    EXPECT_EQ(reference, hashes(1, BroadphaseType::SweepAndPrune)) << "rerun in process";
  }
}

}  // namespace geometry_determinism_test
}  // namespace elan
