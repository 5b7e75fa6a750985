// SPDX-License-Identifier: MIT
// Ray casts against meshes, heightfields and compounds in the world at their closed-form points
// and normals, and the static-only rule of meshes and heightfields.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "elan/elan.hpp"

namespace elan {
namespace api_surface_queries_test {

// Float frame changes of O(10) values and one division: a few ulps of 10 m.
constexpr Real kTol = Real(2e-5);

void expect_vec(const Vec3& a, const Vec3& b) {
  EXPECT_LT((a - b).norm(), kTol) << a.transpose() << " vs " << b.transpose();
}

ShapeId square_mesh(World& w) {
  // Two triangles making the square |x|, |z| <= 2 of the plane y = 0 (shape frame).
  ShapeDef mesh;
  mesh.type = ShapeType::Mesh;
  mesh.vertices = {Vec3(-2, 0, -2), Vec3(2, 0, -2), Vec3(2, 0, 2), Vec3(-2, 0, 2)};
  mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
  return w.create_shape(mesh);
}

TEST(SurfaceRayCast, MeshHitsItsPlaneFromEitherSide) {
  World w;
  BodyDef d;
  d.motion = MotionType::Static;
  d.shape = square_mesh(w);
  d.position = Vec3(1, 2, 3);
  d.orientation = Quat(Eigen::AngleAxis<Real>(Real(std::numbers::pi / 6), Vec3::UnitX()));
  w.create_body(d);
  const Vec3 n = d.orientation * Vec3::UnitY();
  // The ray meets the plane n . (x - p) = 0 at t = n . (p - o) / n . dir.
  const Vec3 o = d.position + d.orientation * Vec3(0.5f, 5, -0.3f);
  const Vec3 dir = (d.orientation * Vec3(0.1f, -1, 0.2f)).normalized();
  const Real t = n.dot(d.position - o) / n.dot(dir);
  const auto hit = w.cast_ray(o, dir, 100);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, t, kTol);
  expect_vec(hit->point, o + t * dir);
  expect_vec(hit->normal, n);
  // From below the normal faces the ray: -n.
  const Vec3 below = d.position + d.orientation * Vec3(-1, -3, 1);
  const auto back = w.cast_ray(below, n, 100);
  ASSERT_TRUE(back);
  EXPECT_NEAR(back->distance, 3, kTol);
  expect_vec(back->normal, -n);
  // Past the square's edge: nothing.
  EXPECT_FALSE(w.cast_ray(d.position + d.orientation * Vec3(2.5f, 3, 0), -n, 100));
}

TEST(SurfaceRayCast, HeightfieldOfAPlaneHitsTheClosedForm) {
  // Heights 0.5 x + 0.25 z on 5 x 4 samples 1 m apart: the plane y = 0.5 x + 0.25 z, whose
  // upward normal is (-0.5, 1, -0.25) normalised.
  World w;
  ShapeDef f;
  f.type = ShapeType::Heightfield;
  f.columns = 5;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 5; ++i) f.heights.push_back(Real(0.5 * i + 0.25 * j));
  }
  BodyDef d;
  d.motion = MotionType::Static;
  d.shape = w.create_shape(f);
  d.position = Vec3(10, 0, 0);
  w.create_body(d);
  const Vec3 n = Vec3(-0.5f, 1, -0.25f).normalized();
  const auto down = w.cast_ray(Vec3(12.3f, 10, 1.7f), -Vec3::UnitY(), 100);
  ASSERT_TRUE(down);
  EXPECT_NEAR(down->distance, 10 - (0.5 * 2.3 + 0.25 * 1.7), kTol);
  expect_vec(down->normal, n);
  // A slanted ray crossing several cells: t = n . (p - o) / n . dir with p on the plane.
  const Vec3 o(9.5f, 6, 0.5f);
  const Vec3 dir = Vec3(1, -1, 0.4f).normalized();
  const Real t = n.dot(Vec3(10, 0, 0) - o) / n.dot(dir);
  const auto slant = w.cast_ray(o, dir, 100);
  ASSERT_TRUE(slant);
  EXPECT_NEAR(slant->distance, t, kTol);
  expect_vec(slant->normal, n);
  // Beside the grid: nothing.
  EXPECT_FALSE(w.cast_ray(Vec3(15.5f, 10, 1), -Vec3::UnitY(), 100));
}

TEST(SurfaceRayCast, CompoundHitsItsNearestChild) {
  World w;
  ShapeDef box;
  box.type = ShapeType::Box;
  box.half_extents = Vec3(1, 1, 1);
  ShapeDef ball;
  ball.type = ShapeType::Sphere;
  ball.radius = 1;
  ShapeDef c;
  c.type = ShapeType::Compound;
  c.children.resize(2);
  c.children[0].shape = box;
  c.children[0].position = Vec3(-3, 0, 0);
  c.children[1].shape = ball;
  c.children[1].position = Vec3(3, 0, 0);
  BodyDef d;
  d.shape = w.create_shape(c);
  d.position = Vec3(0, 5, 0);
  const BodyId id = w.create_body(d);
  // Along +x: the box's face x = -4, 6 m away.
  const auto left = w.cast_ray(Vec3(-10, 5, 0), Vec3::UnitX(), 100);
  ASSERT_TRUE(left);
  EXPECT_EQ(left->body, id);
  EXPECT_NEAR(left->distance, 6, kTol);
  expect_vec(left->normal, -Vec3::UnitX());
  // Along -x at height 0.5 above the centres: the sphere at x = 3 + sqrt(1 - 0.25).
  const auto right = w.cast_ray(Vec3(10, 5.5f, 0), -Vec3::UnitX(), 100);
  ASSERT_TRUE(right);
  EXPECT_NEAR(right->distance, 7 - std::sqrt(Real(0.75)), kTol);
  expect_vec(right->normal, Vec3(std::sqrt(Real(0.75)), 0.5f, 0));
  // Between the children: nothing.
  EXPECT_FALSE(w.cast_ray(Vec3(0, 5, -10), Vec3::UnitZ(), 100));

  // Turned a quarter about y (x -> -z), the box child sits at z = +3: its face z = 4.
  World w2;
  d.shape = w2.create_shape(c);
  d.orientation = Quat(Eigen::AngleAxis<Real>(Real(std::numbers::pi / 2), Vec3::UnitY()));
  w2.create_body(d);
  const auto turned = w2.cast_ray(Vec3(0, 5, 10), -Vec3::UnitZ(), 100);
  ASSERT_TRUE(turned);
  EXPECT_NEAR(turned->distance, 6, kTol);
  expect_vec(turned->normal, Vec3::UnitZ());
}

TEST(SurfaceRayCast, MeshesAndHeightfieldsMustBeStatic) {
  World w;
  ShapeDef f;
  f.type = ShapeType::Heightfield;
  f.columns = 2;
  f.heights = {0, 0, 0, 0};
  for (const ShapeId shape : {square_mesh(w), w.create_shape(f)}) {
    for (const MotionType m : {MotionType::Dynamic, MotionType::Kinematic}) {
      BodyDef d;
      d.shape = shape;
      d.motion = m;
      try {
        w.create_body(d);
        ADD_FAILURE() << "a moving surface was created";
      } catch (const Error& e) {
        EXPECT_EQ(e.field(), "motion");
        EXPECT_NE(std::string(e.what()).find("must be static"), std::string::npos) << e.what();
      }
    }
    BodyDef d;
    d.shape = shape;
    d.motion = MotionType::Static;
    EXPECT_NO_THROW(w.create_body(d));
  }
}

}  // namespace api_surface_queries_test
}  // namespace elan
