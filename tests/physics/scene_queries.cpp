// SPDX-License-Identifier: MIT
// The scene queries against brute-force references over random worlds of every shape kind (the
// query tree must find exactly what testing every body finds), closed forms of shape casts,
// exact overlap (not boxes), filters, and the tree kept in step by the API (concurrent queries:
// tests/stage/queries_threads.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/world/queries.hpp"
#include "core/world/shape_queries.hpp"
#include "core/world/world_access.hpp"
#include "core/world/world_state.hpp"
#include "elan/snapshot.hpp"
#include "elan/world.hpp"
#include "narrowphase/shape_cast.hpp"
#include "narrowphase/shape_point.hpp"
#include "physics/query_worlds.hpp"

namespace elan {
namespace scene_queries_test {

using namespace query_worlds;

const detail::WorldState& state(const World& w) {
  return detail::state_of(w);
}
Transform pose_of(const World& w, std::size_t i) {
  return {state(w).bodies.position(i), state(w).bodies.orientation(i)};
}
const detail::Shape& shape_of(const World& w, std::size_t i) {
  return state(w).shapes[state(w).bodies.shape[i]];
}
bool passes(const World& w, std::size_t i, const QueryFilter& f) {
  const auto& t = state(w).bodies.traits_of(i);
  return (t.category & f.mask_bits) && (t.mask & f.category_bits) &&
         (!(t.flags & detail::kTraitSensor) || f.include_sensors) &&
         (!f.accept || f.accept(w.body_at(i)));
}

// Every body's ray hit, by testing every body: (distance, index) sorted.
std::vector<std::pair<Real, std::size_t>> all_ray_hits(const World& w, const Vec3& o, const Vec3& d,
                                                       Real max_t, const QueryFilter& f = {}) {
  std::vector<std::pair<Real, std::size_t>> out;
  for (std::size_t i = 0; i < w.body_count(); ++i) {
    detail::ShapeRayHit h;
    if (passes(w, i, f) && detail::ray_shape(shape_of(w, i), pose_of(w, i), o, d, max_t, h)) {
      out.emplace_back(h.distance, i);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The tree's answers equal testing every body, ray by ray (closest: the least distance, ties to
// the lower index; all: every hit sorted by distance then index).
void expect_rays_match_brute_force(const World& w, uint32_t seed, int rays, const char* what) {
  std::mt19937 rng(seed);
  int hits = 0;
  for (int k = 0; k < rays; ++k) {
    const RandomRay r = random_ray(rng);
    // The direction as the query normalises it: the same bits.
    const auto want = all_ray_hits(w, r.origin, r.dir.normalized(), 40);
    const auto got = w.cast_ray(r.origin, r.dir, 40);
    ASSERT_EQ(bool(got), !want.empty()) << what << " ray " << k;
    std::vector<RayHit> all;
    w.cast_ray_all(r.origin, r.dir, 40, all);
    ASSERT_EQ(all.size(), want.size()) << what << " ray " << k;
    for (std::size_t h = 0; h < all.size(); ++h) {
      ASSERT_EQ(all[h].body, w.body_at(want[h].second));
      ASSERT_EQ(all[h].distance, want[h].first);
    }
    if (!got) continue;
    ++hits;
    EXPECT_EQ(got->body, w.body_at(want[0].second)) << what << " ray " << k;
    EXPECT_EQ(got->distance, want[0].first);
    const auto any = w.cast_ray_any(r.origin, r.dir, 40);
    ASSERT_TRUE(any);
    EXPECT_TRUE(std::any_of(all.begin(), all.end(), [&](const RayHit& h) {
      return h.body == any->body && h.distance == any->distance;
    }));
  }
  EXPECT_GT(hits, rays / 4) << what << ": the rays must hit something to test anything";
}

TEST(SceneQueries, RaysMatchBruteForceOverEveryShapeKind) {
  const World w = random_world(1, 400);
  expect_rays_match_brute_force(w, 2, 400, "random world");
  EXPECT_TRUE(state(w).query.tree.valid());
}

TEST(SceneQueries, BatchedRaysEqualSingleRaysAtOneAndTwoThreads) {
  for (int threads : {1, 2}) {
    const World w = random_world(3, 300, threads);
    std::mt19937 rng(4);
    std::vector<Ray> rays(1000);
    for (Ray& r : rays) {
      const RandomRay q = random_ray(rng);
      r = {q.origin, q.dir * Real(2.5), 30};
    }
    std::vector<RayHit> hits(rays.size());
    w.cast_rays(rays, hits);
    for (std::size_t k = 0; k < rays.size(); ++k) {
      const auto one = w.cast_ray(rays[k].origin, rays[k].direction, rays[k].max_distance);
      ASSERT_EQ(hits[k].body.is_null(), !one) << k;
      if (one) {
        EXPECT_EQ(hits[k].body, one->body);
        EXPECT_EQ(hits[k].distance, one->distance);
      }
    }
    std::vector<RayHit> short_hits(3);
    EXPECT_THROW(w.cast_rays(rays, short_hits), Error);
  }
}

// Sphere of radius r cast down onto the plane y <= 0 from height h: first touch at
// fraction (h - r) / |translation|, closed form (the plane's cast is exact).
TEST(SceneQueries, ShapeCastSpherePlaneClosedForm) {
  World w;
  ShapeDef plane;
  plane.type = ShapeType::Plane;
  BodyDef g;
  g.motion = MotionType::Static;
  g.shape = w.create_shape(plane);
  const BodyId ground = w.create_body(g);
  ShapeDef ball;
  ball.radius = 0.5f;
  const ShapeId s = w.create_shape(ball);
  const auto hit = w.cast_shape(s, {Vec3(1, 3, 2), Quat::Identity()}, Vec3(4, -10, 0));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->body, ground);
  EXPECT_NEAR(hit->fraction, 0.25f, 1e-6f);
  EXPECT_NEAR((hit->normal - Vec3::UnitY()).norm(), 0, 1e-6f);
  EXPECT_NEAR((hit->point - Vec3(2, 0, 2)).norm(), 0, 1e-5f);
  EXPECT_FALSE(w.cast_shape(s, {Vec3(1, 3, 2), Quat::Identity()}, Vec3(0, -2, 0)));  // short
  EXPECT_FALSE(w.cast_shape(s, {Vec3(1, 3, 2), Quat::Identity()}, Vec3(0, 2, 0)));   // away
  const auto start = w.cast_shape(s, {Vec3(0, 0.2f, 0), Quat::Identity()}, Vec3(1, 0, 0));
  ASSERT_TRUE(start);
  EXPECT_EQ(start->fraction, 0);  // overlapping at the start
}

// Sphere r1 from (-5, b, 0) along +10 x against sphere r2 at the origin: the centres come
// r1 + r2 apart at x = -sqrt((r1 + r2)^2 - b^2), fraction (5 + x) / 10. Conservative
// advancement stops before the touch, within 1e-4 of the larger radius (1 m): 1e-5 of the
// translation, more only by the approach's obliquity (cos = 0.99 here).
TEST(SceneQueries, ShapeCastSphereSphereClosedForm) {
  World w;
  ShapeDef big;
  big.radius = 1;
  BodyDef b;
  b.motion = MotionType::Static;
  b.shape = w.create_shape(big);
  const BodyId target = w.create_body(b);
  ShapeDef small;
  small.radius = 0.5f;
  const ShapeId s = w.create_shape(small);
  const Real off = 0.3f;
  const auto hit = w.cast_shape(s, {Vec3(-5, off, 0), Quat::Identity()}, Vec3(10, 0, 0));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->body, target);
  const Real x = -std::sqrt(Real(1.5 * 1.5) - off * off);
  const Real expected = (5 + x) / 10;
  EXPECT_LE(hit->fraction, expected + 1e-6f);
  EXPECT_NEAR(hit->fraction, expected, 2e-5f);
  const Vec3 centre = Vec3(-5 + 10 * hit->fraction, off, 0);
  EXPECT_NEAR((hit->normal - centre.normalized()).norm(), 0, 1e-3f);
  EXPECT_NEAR(hit->point.norm(), 1, 1e-3f);
}

TEST(SceneQueries, ShapeCastsMatchBruteForce) {
  const World w = random_world(5, 250);
  std::mt19937 rng(6);
  std::vector<bool> unused;
  World scratch;
  ShapeDef ball;
  ball.radius = 0.4f;
  ShapeDef box;
  box.type = ShapeType::Box;
  box.half_extents = Vec3(0.3f, 0.5f, 0.2f);
  // The query shapes are made in `w` itself: a const world cannot, so use the ids of its own
  // shapes (sphere: 0, box: 1, compound: 5).
  const ShapeId ids[3] = {ShapeId{0}, ShapeId{1}, ShapeId{5}};
  int hits = 0;
  for (int k = 0; k < 60; ++k) {
    const ShapeId id = ids[k % 3];
    const detail::Shape& a = state(w).shapes[id.index];
    const Transform start{Vec3{uniform(rng, -14, 14), uniform(rng, -14, 14), uniform(rng, -14, 14)},
                          random_rotation(rng)};
    const Vec3 move{uniform(rng, -8, 8), uniform(rng, -8, 8), uniform(rng, -8, 8)};
    std::vector<ShapeCastHit> all;
    w.cast_shape_all(id, start, move, all);
    // Reference: every body swept against alone.
    const Transform x = detail::principal_pose(a, start);
    std::vector<std::pair<Real, std::size_t>> want;
    for (std::size_t i = 0; i < w.body_count(); ++i) {
      detail::CastContact c;
      if (detail::shape_cast(a, x, move, shape_of(w, i), pose_of(w, i), 0, c)) {
        want.emplace_back(c.fraction, i);
      }
    }
    std::sort(want.begin(), want.end());
    ASSERT_EQ(all.size(), want.size()) << "cast " << k;
    for (std::size_t h = 0; h < all.size(); ++h) {
      EXPECT_EQ(all[h].body, w.body_at(want[h].second));
      EXPECT_EQ(all[h].fraction, want[h].first);
    }
    const auto first = w.cast_shape(id, start, move);
    ASSERT_EQ(bool(first), !want.empty());
    if (first) {
      ++hits;
      EXPECT_EQ(first->body, all[0].body);
      EXPECT_EQ(first->fraction, all[0].fraction);
    }
  }
  EXPECT_GT(hits, 10);
}

// Down through a packed pile, where the walk along the cast prunes most bodies: the first hit is
// still the least fraction over every body (ties: the lower index), for spheres, boxes and a
// compound cast at random tilts.
TEST(SceneQueries, FirstShapeCastIntoAPileMatchesBruteForce) {
  World w;
  ShapeDef ball;
  ball.radius = 0.25f;
  ShapeDef box;
  box.type = ShapeType::Box;
  box.half_extents = Vec3(0.24f, 0.2f, 0.22f);
  const ShapeId kinds[2] = {w.create_shape(ball), w.create_shape(box)};
  ShapeDef compound;
  compound.type = ShapeType::Compound;
  ShapeDef part;
  part.type = ShapeType::Box;
  part.half_extents = Vec3(0.3f, 0.1f, 0.1f);
  compound.children.push_back({part, Vec3(0.2f, 0, 0), Quat::Identity()});
  part.type = ShapeType::Sphere;
  part.radius = 0.2f;
  compound.children.push_back({part, Vec3(-0.3f, 0.1f, 0), Quat::Identity()});
  const ShapeId casts[3] = {kinds[0], kinds[1], w.create_shape(compound)};
  std::mt19937 rng(21);
  BodyDef b;
  b.awake = false;
  for (int layer = 0; layer < 6; ++layer) {
    for (int i = 0; i < 12; ++i) {
      for (int j = 0; j < 12; ++j) {
        b.shape = kinds[(i + j + layer) % 2];
        b.position = Vec3{Real(i) * 0.5f - 3 + uniform(rng, -0.03f, 0.03f),
                          Real(layer) * 0.5f + uniform(rng, -0.03f, 0.03f),
                          Real(j) * 0.5f - 3 + uniform(rng, -0.03f, 0.03f)};
        b.orientation = random_rotation(rng);
        w.create_body(b);
      }
    }
  }
  int hits = 0;
  for (int k = 0; k < 90; ++k) {
    const ShapeId id = casts[k % 3];
    const detail::Shape& a = state(w).shapes[id.index];
    const Transform start{Vec3{uniform(rng, -3.5f, 3.5f), 6, uniform(rng, -3.5f, 3.5f)},
                          random_rotation(rng)};
    const Vec3 move{uniform(rng, -2, 2), -10, uniform(rng, -2, 2)};
    const Transform x = detail::principal_pose(a, start);
    std::size_t want = SIZE_MAX;
    detail::CastContact best;
    for (std::size_t i = 0; i < w.body_count(); ++i) {
      detail::CastContact c;
      if (detail::shape_cast(a, x, move, shape_of(w, i), pose_of(w, i), 0, c) &&
          (want == SIZE_MAX || c.fraction < best.fraction)) {
        want = i;
        best = c;
      }
    }
    const auto first = w.cast_shape(id, start, move);
    ASSERT_EQ(bool(first), want != SIZE_MAX) << "cast " << k;
    if (!first) continue;
    ++hits;
    EXPECT_EQ(first->body, w.body_at(want)) << "cast " << k;
    EXPECT_EQ(first->fraction, best.fraction) << "cast " << k;
  }
  EXPECT_GT(hits, 45);
}

TEST(SceneQueries, OverlapIsExactNotBoxes) {
  World w;
  ShapeDef cube;
  cube.type = ShapeType::Box;
  cube.half_extents = Vec3::Ones();
  BodyDef b;
  b.motion = MotionType::Static;
  b.shape = w.create_shape(cube);
  const BodyId box = w.create_body(b);
  ShapeDef ball;
  ball.radius = 0.3f;
  const ShapeId s = w.create_shape(ball);
  // In the box's bounding-box corner region but 0.2 sqrt(3) = 0.35 m from the corner: apart.
  std::vector<BodyId> out;
  w.overlap_shape(s, {Vec3(1.2f, 1.2f, 1.2f), Quat::Identity()}, out);
  EXPECT_TRUE(out.empty());
  w.overlap_box(Vec3::Constant(0.9f), Vec3::Constant(1.5f), out);
  EXPECT_EQ(out, std::vector<BodyId>{box});                          // the boxes do overlap
  w.overlap_shape(s, {Vec3(1.1f, 1.1f, 0), Quat::Identity()}, out);  // 0.14 m from the edge
  EXPECT_EQ(out, std::vector<BodyId>{box});
  w.overlap_point(Vec3(0.99f, -0.99f, 0.5f), out);
  EXPECT_EQ(out, std::vector<BodyId>{box});
  w.overlap_point(Vec3(1.01f, 0, 0), out);
  EXPECT_TRUE(out.empty());
}

TEST(SceneQueries, OverlapsAndPointsMatchBruteForce) {
  const World w = random_world(7, 300);
  std::mt19937 rng(8);
  const ShapeId ids[3] = {ShapeId{0}, ShapeId{1}, ShapeId{5}};
  std::size_t found = 0;
  for (int k = 0; k < 200; ++k) {
    const ShapeId id = ids[k % 3];
    const detail::Shape& a = state(w).shapes[id.index];
    const Transform pose{Vec3{uniform(rng, -13, 13), uniform(rng, -13, 13), uniform(rng, -13, 13)},
                         random_rotation(rng)};
    const Transform x = detail::principal_pose(a, pose);
    std::vector<BodyId> got, want;
    w.overlap_shape(id, pose, got);
    for (std::size_t i = 0; i < w.body_count(); ++i) {
      if (detail::shapes_overlap(a, x, shape_of(w, i), pose_of(w, i))) want.push_back(w.body_at(i));
    }
    ASSERT_EQ(got, want) << "overlap " << k;
    found += got.size();

    const Vec3 p = pose.position;
    w.overlap_point(p, got);
    want.clear();
    for (std::size_t i = 0; i < w.body_count(); ++i) {
      if (detail::shape_contains(shape_of(w, i), pose_of(w, i), p)) want.push_back(w.body_at(i));
    }
    ASSERT_EQ(got, want) << "point " << k;
    found += got.size();

    // Closest point within 2 m: the least distance of every body's, ties to the lower index.
    const auto near = w.closest_point(p, 2);
    Real best = 2;
    std::size_t best_i = SIZE_MAX;
    for (std::size_t i = 0; i < w.body_count(); ++i) {
      detail::ShapePoint sp;
      if (!detail::closest_on_shape(shape_of(w, i), pose_of(w, i), p, sp, 2)) continue;
      if (sp.distance <= 2 && (best_i == SIZE_MAX || sp.distance < best)) {
        best = sp.distance;
        best_i = i;
      }
    }
    ASSERT_EQ(bool(near), best_i != SIZE_MAX) << "closest " << k;
    if (near) {
      EXPECT_EQ(near->body, w.body_at(best_i));
      EXPECT_EQ(near->distance, best);
    }
  }
  EXPECT_GT(found, 40u);
}

// Closed forms of closest_point on one body: a unit cube from outside (a corner region and a
// face region) and from inside (the nearest face, negative distance), a sphere.
TEST(SceneQueries, ClosestPointOnOneBody) {
  World w;
  ShapeDef cube;
  cube.type = ShapeType::Box;
  cube.half_extents = Vec3::Ones();
  BodyDef b;
  b.motion = MotionType::Static;
  b.shape = w.create_shape(cube);
  b.position = Vec3(10, 0, 0);
  const BodyId box = w.create_body(b);
  PointHit h = w.closest_point(box, Vec3(12, 2, 2));
  EXPECT_NEAR((h.point - Vec3(11, 1, 1)).norm(), 0, 1e-5f);
  EXPECT_NEAR(h.distance, std::sqrt(3.0f), 1e-5f);
  h = w.closest_point(box, Vec3(10.2f, 0.7f, 0));
  EXPECT_NEAR(h.distance, -0.3f, 1e-5f);
  EXPECT_NEAR((h.normal - Vec3::UnitY()).norm(), 0, 1e-6f);
  EXPECT_NEAR((h.point - Vec3(10.2f, 1, 0)).norm(), 0, 1e-5f);
  ShapeDef ball;
  ball.radius = 2;
  b.shape = w.create_shape(ball);
  b.position = Vec3(-10, 0, 0);
  const BodyId sphere = w.create_body(b);
  h = w.closest_point(sphere, Vec3(-10, 0, 5));
  EXPECT_NEAR(h.distance, 3, 1e-5f);
  EXPECT_NEAR((h.point - Vec3(-10, 0, 2)).norm(), 0, 1e-5f);
}

TEST(SceneQueries, FiltersAreHonoured) {
  World w = random_world(9, 200);
  // A third of the bodies become sensors.
  detail::WorldState& s = detail::state_of(w);
  for (std::size_t i = 0; i < s.bodies.size(); i += 3) {
    detail::BodyTraits t = s.bodies.traits_of(i);
    t.flags |= detail::kTraitSensor;
    s.bodies.set_traits(i, t);
  }
  std::mt19937 rng(10);
  QueryFilter only_two;
  only_two.mask_bits = 2;
  QueryFilter sensors;
  sensors.include_sensors = true;
  QueryFilter odd;
  odd.include_sensors = true;
  odd.accept = [](BodyId id) { return id.slot % 2 == 1; };
  QueryFilter not_one;
  not_one.category_bits = 4;  // bodies' masks are all bits: passes; their category 1 or 2
  not_one.mask_bits = ~1u;
  int checked = 0;
  for (int k = 0; k < 300; ++k) {
    const RandomRay r = random_ray(rng);
    for (const QueryFilter* f : {&only_two, &sensors, &odd, &not_one}) {
      const auto want = all_ray_hits(w, r.origin, r.dir.normalized(), 40, *f);
      std::vector<RayHit> all;
      w.cast_ray_all(r.origin, r.dir, 40, all, *f);
      ASSERT_EQ(all.size(), want.size());
      for (std::size_t h = 0; h < all.size(); ++h) {
        ASSERT_EQ(all[h].body, w.body_at(want[h].second));
        ASSERT_TRUE(passes(w, want[h].second, *f));
      }
      checked += int(all.size());
    }
    // No filter: sensors unseen.
    std::vector<RayHit> plain;
    w.cast_ray_all(r.origin, r.dir, 40, plain);
    for (const RayHit& h : plain) {
      EXPECT_FALSE(s.bodies.traits_of(detail::index_of(s, h.body)).flags & detail::kTraitSensor);
    }
  }
  EXPECT_GT(checked, 100);
}

// The tree stays right through every change between steps: moves, creates, destroys (the last
// body takes the hole), bulk moves, snapshot restores and steps.
TEST(SceneQueries, TreeKeptInStepByEveryChange) {
  World w = random_world(13, 200);
  std::mt19937 rng(14);
  const auto check = [&](const char* what) {
    ASSERT_TRUE(state(w).query.tree.valid()) << what;
    expect_rays_match_brute_force(w, uint32_t(rng()), 60, what);
  };
  check("start");
  for (int k = 0; k < 40; ++k) {
    const BodyId id = w.body_at(rng() % (w.body_count() - 1));
    if (w.motion_type(id) == MotionType::Static) continue;
    w.set_position(id, Vec3{uniform(rng, -12, 12), uniform(rng, -12, 12), uniform(rng, -12, 12)});
    w.set_orientation(id, random_rotation(rng));
  }
  check("set_position");
  for (int k = 0; k < 30; ++k) w.destroy_body(w.body_at(rng() % w.body_count()));
  check("destroy_body");
  ShapeDef ball;
  BodyDef b;
  b.shape = w.create_shape(ball);
  for (int k = 0; k < 30; ++k) {
    b.position = Vec3{uniform(rng, -12, 12), uniform(rng, -12, 12), uniform(rng, -12, 12)};
    w.create_body(b);
  }
  check("create_body");
  const std::vector<uint8_t> saved = save_snapshot(w);
  for (int k = 0; k < 30; ++k) w.step(Real(1.0 / 60));
  check("step");
  restore_snapshot(w, saved);
  check("restore_snapshot");
  std::vector<Real> x(w.body_count()), y(w.body_count()), z(w.body_count());
  for (std::size_t i = 0; i < w.body_count(); ++i) {
    const Vec3 p = state(w).bodies.position(i) + Vec3(0, 3, 0);
    x[i] = p.x();
    y[i] = p.y();
    z[i] = p.z();
  }
  w.set_center_of_mass_positions(x, y, z);
  check("bulk positions");
}

}  // namespace scene_queries_test
}  // namespace elan
