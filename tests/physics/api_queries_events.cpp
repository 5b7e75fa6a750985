// SPDX-License-Identifier: MIT
// Scene queries and contact events: ray casts against every shape type against closed forms,
// world ray and box queries in their documented order, and begin/end events of a bouncing ball.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/world/queries.hpp"
#include "elan/elan.hpp"

namespace elan {
namespace api_queries_events_test {

constexpr Real kDt = Real(1.0 / 60.0);
// Float closed forms with one sqrt and a frame change of O(1) values: a few ulps of 10 m.
constexpr Real kTol = Real(2e-5);

detail::ShapeRayHit cast(const ShapeDef& def, const Transform& pose, const Vec3& o, const Vec3& d) {
  detail::ShapeRayHit hit;
  hit.distance = -1;
  detail::ray_shape(detail::make_shape(def), pose, o, d.normalized(), 100, hit);
  return hit;
}

void expect_vec(const Vec3& a, const Vec3& b) {
  EXPECT_LT((a - b).norm(), kTol) << a.transpose() << " vs " << b.transpose();
}

TEST(RayCast, SphereAtAnAngleMatchesTheQuadratic) {
  ShapeDef s;
  s.type = ShapeType::Sphere;
  s.radius = 2;
  // Ray along +x at height 1 from x = -10: enters at x = -sqrt(4 - 1).
  const auto h = cast(s, Transform{}, Vec3(-10, 1, 0), Vec3::UnitX());
  EXPECT_NEAR(h.distance, 10 - std::sqrt(Real(3)), kTol);
  expect_vec(h.normal, Vec3(-std::sqrt(Real(3)), 1, 0) / 2);
  EXPECT_LT(cast(s, Transform{}, Vec3(0, 0, 0), Vec3::UnitX()).distance, 0);       // from inside
  EXPECT_LT(cast(s, Transform{}, Vec3(-10, 2.1f, 0), Vec3::UnitX()).distance, 0);  // passes by
}

TEST(RayCast, RotatedBoxHitsTheSlabFace) {
  ShapeDef s;
  s.type = ShapeType::Box;
  s.half_extents = Vec3(1, 2, 3);
  const Quat q(Eigen::AngleAxis<Real>(Real(M_PI / 2), Vec3::UnitZ()));  // local x -> world y
  const Transform pose{Vec3(5, 0, 0), q};
  // From above: the world-y extent is the local x half extent, 1.
  const auto h = cast(s, pose, Vec3(5, 10, 0), -Vec3::UnitY());
  EXPECT_NEAR(h.distance, 9, kTol);
  expect_vec(h.normal, Vec3::UnitY());
  const auto side = cast(s, pose, Vec3(0, 0, 0.5f), Vec3::UnitX());  // world-x extent is 2
  EXPECT_NEAR(side.distance, 3, kTol);
  expect_vec(side.normal, -Vec3::UnitX());
}

TEST(RayCast, CapsuleSideAndCap) {
  ShapeDef s;
  s.type = ShapeType::Capsule;
  s.radius = Real(0.5);
  s.half_height = 1;
  const auto side = cast(s, Transform{}, Vec3(-5, Real(0.3), 0), Vec3::UnitX());
  EXPECT_NEAR(side.distance, 4.5, kTol);
  expect_vec(side.normal, -Vec3::UnitX());
  const auto top = cast(s, Transform{}, Vec3(0, 5, 0), -Vec3::UnitY());
  EXPECT_NEAR(top.distance, 5 - 1.5, kTol);
  expect_vec(top.normal, Vec3::UnitY());
  // Off-axis into the cap sphere at x = 0.3: y = 1 + sqrt(0.25 - 0.09) = 1.4.
  const auto cap = cast(s, Transform{}, Vec3(0.3f, 5, 0), -Vec3::UnitY());
  EXPECT_NEAR(cap.distance, 5 - 1.4, kTol);
  expect_vec(cap.normal, Vec3(0.3f, 0.4f, 0) / 0.5f);
}

TEST(RayCast, CylinderSideAndFlatCap) {
  ShapeDef s;
  s.type = ShapeType::Cylinder;
  s.radius = 1;
  s.half_height = 2;
  const auto cap = cast(s, Transform{}, Vec3(0.5f, 10, 0.5f), -Vec3::UnitY());
  EXPECT_NEAR(cap.distance, 8, kTol);
  expect_vec(cap.normal, Vec3::UnitY());
  const auto side = cast(s, Transform{}, Vec3(0, 1, -7), Vec3::UnitZ());
  EXPECT_NEAR(side.distance, 6, kTol);
  expect_vec(side.normal, -Vec3::UnitZ());
  // Past the rim: at x = 1.2 the vertical ray misses the disc of radius 1.
  EXPECT_LT(cast(s, Transform{}, Vec3(1.2f, 10, 0), -Vec3::UnitY()).distance, 0);
}

TEST(RayCast, PlaneAndHullByFacePlanes) {
  ShapeDef plane;
  plane.type = ShapeType::Plane;
  plane.normal = Vec3(0, 1, 1);  // normalised on creation
  plane.offset = 0;
  const auto hp = cast(plane, Transform{}, Vec3(0, 3, 3), -Vec3::UnitY());
  EXPECT_NEAR(hp.distance, 6, kTol);  // y + z = 0 at y = -3
  expect_vec(hp.normal, Vec3(0, 1, 1).normalized());
  // A tetrahedron x, y, z >= 0, x + y + z <= 1, shifted by its centroid into the principal
  // frame by make_shape; pose identity keeps the user frame.
  ShapeDef hull;
  hull.type = ShapeType::ConvexHull;
  hull.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const detail::Shape shape = detail::make_shape(hull);
  const Transform pose{shape.frame_position, shape.frame_rotation};  // principal -> user = world
  detail::ShapeRayHit h;
  ASSERT_TRUE(detail::ray_shape(shape, pose, Vec3(0.2f, 0.2f, 5), -Vec3::UnitZ(), 100, h));
  EXPECT_NEAR(h.distance, 5 - 0.6, kTol);  // slanted face x + y + z = 1
  expect_vec(h.normal, Vec3(1, 1, 1).normalized());
  ASSERT_TRUE(detail::ray_shape(shape, pose, Vec3(0.2f, -3, 0.2f), Vec3::UnitY(), 100, h));
  EXPECT_NEAR(h.distance, 3, kTol);
  expect_vec(h.normal, -Vec3::UnitY());
}

TEST(WorldQueries, RaysAndBoxesFollowTheDocumentedOrder) {
  World w;
  ShapeDef ball;
  ball.type = ShapeType::Sphere;
  ball.radius = Real(0.5);
  BodyDef d;
  d.shape = w.create_shape(ball);
  d.motion = MotionType::Static;
  std::vector<BodyId> ids;
  for (int k = 0; k < 5; ++k) {
    d.position = Vec3(Real(4 - k) * 2, 0, 0);  // index 0 farthest along +x
    ids.push_back(w.create_body(d));
  }
  d.position = Vec3(2, 0, 0);  // same place as ids[3]: a tie broken by index
  ids.push_back(w.create_body(d));
  const auto closest = w.cast_ray(Vec3(-5, 0, 0), Vec3(3, 0, 0), 100);
  ASSERT_TRUE(closest);
  EXPECT_EQ(closest->body, ids[4]);
  EXPECT_NEAR(closest->distance, 4.5, kTol);
  std::vector<RayHit> all;
  w.cast_ray_all(Vec3(-5, 0, 0), Vec3::UnitX(), 100, all);
  ASSERT_EQ(all.size(), 6u);
  const BodyId expected[] = {ids[4], ids[3], ids[5], ids[2], ids[1], ids[0]};
  for (int k = 0; k < 6; ++k) EXPECT_EQ(all[k].body, expected[k]) << k;
  EXPECT_FALSE(w.cast_ray(Vec3(-5, 0, 0), Vec3::UnitX(), 4));  // too short
  std::vector<BodyId> over;
  w.overlap_box(Vec3(1.7f, -1, -1), Vec3(4.2f, 1, 1), over);
  ASSERT_EQ(over.size(), 3u);  // ids[2] (x 4), ids[3], ids[5] (x 2), in index order
  EXPECT_EQ(over[0], ids[2]);
  EXPECT_EQ(over[1], ids[3]);
  EXPECT_EQ(over[2], ids[5]);
  w.destroy_body(ids[3]);
  w.cast_ray_all(Vec3(-5, 0, 0), Vec3::UnitX(), 100, all);
  EXPECT_EQ(all.size(), 5u);  // the cached bounds follow the destroy
}

// A ball with restitution dropped on a floor: a begin event on every touch, an end event on
// every bounce-off, and the counts match the touches seen by polling the contact count.
TEST(ContactEvents, BouncingBallBeginsOnceAndEndsOnEachBounce) {
  World w;
  ShapeDef ground;
  ground.type = ShapeType::Box;
  ground.half_extents = Vec3(5, 1, 5);
  ShapeDef ball;
  ball.type = ShapeType::Sphere;
  ball.radius = Real(0.5);
  BodyDef floor;
  floor.motion = MotionType::Static;
  floor.shape = w.create_shape(ground);
  floor.position = Vec3(0, -1, 0);
  floor.restitution = Real(0.5);
  const BodyId floor_id = w.create_body(floor);
  BodyDef drop;
  drop.shape = w.create_shape(ball);
  drop.position = Vec3(0, 3, 0);
  drop.restitution = Real(0.5);
  const BodyId ball_id = w.create_body(drop);
  int begins = 0, ends = 0, touch_runs = 0, separations = 0;
  bool touching = false;
  for (int k = 0; k < 300; ++k) {
    w.step(kDt);
    for (const ContactBeginEvent& e : w.contact_begin_events()) {
      ++begins;
      EXPECT_EQ(e.body_a, ball_id);  // the static body is B
      EXPECT_EQ(e.body_b, floor_id);
      EXPECT_NEAR(e.normal.y(), -1, 1e-4);  // from the ball towards the floor
      EXPECT_NEAR(e.point.y(), 0, 0.1);
    }
    ends += int(w.contact_end_events().size());
    const bool now = w.last_step().manifolds > 0;
    if (now && !touching) ++touch_runs;
    if (!now && touching) ++separations;
    touching = now;
  }
  // Impact speeds 7, 3.5, 1.75 m/s bounce (e = 0.5, above the 1 m/s threshold), 0.9 m/s stays.
  EXPECT_GE(begins, 3);
  EXPECT_EQ(begins, touch_runs);
  EXPECT_EQ(ends, separations);
  EXPECT_EQ(begins, ends + (touching ? 1 : 0));
  EXPECT_TRUE(touching);  // at rest on the floor at the end
}

}  // namespace api_queries_events_test
}  // namespace elan
