// SPDX-License-Identifier: MIT
// The query tree after steps with no query between them: a step only marks the bodies it moved,
// and the first query refits their leaves (core/world/query_tree.hpp). Each test finds bodies at
// their current poses, where a leaf left where the body was created would miss them.
#include <gtest/gtest.h>

#include <vector>

#include "core/world/world_access.hpp"
#include "elan/world.hpp"
#include "physics/physics_util.hpp"

namespace elan {
namespace queries_refit_test {

constexpr Real kRadius = Real(0.25);
constexpr Real kTol = Real(1e-4);  // m: a ray-sphere hit rounds to about 1e-6 at these sizes

// Adds a row of spheres 2 m apart at rest 20 m up (no ground): after t seconds of steps each has
// fallen about g t^2 / 2, soon past its leaf's 5 cm margin.
std::vector<BodyId> add_falling_row(World& w, int count) {
  BodyDef b;
  b.shape = w.create_shape(test::sphere_shape(kRadius));
  std::vector<BodyId> ids;
  for (int k = 0; k < count; ++k) {
    b.position = Vec3(Real(2 * k), 20, 0);
    ids.push_back(w.create_body(b));
  }
  return ids;
}

// A ray straight down from 1 m above the body's centre hits it first, 1 m - r away.
void expect_found_from_above(const World& w, BodyId id) {
  const Vec3 c = w.position(id);
  const auto hit = w.cast_ray(c + Vec3(0, 1, 0), Vec3(0, -1, 0), 5);
  ASSERT_TRUE(hit.has_value()) << "body " << id.slot << " at y = " << c.y();
  EXPECT_EQ(hit->body, id);
  EXPECT_NEAR(hit->distance, 1 - kRadius, kTol);
  std::vector<BodyId> at;
  w.overlap_point(c, at);
  EXPECT_EQ(at, std::vector<BodyId>{id});
}

TEST(QueryRefit, FallingBodiesAreFoundWhereTheyAreAfterStepsWithoutAQuery) {
  World w;
  const std::vector<BodyId> ids = add_falling_row(w, 20);
  for (int n = 0; n < 60; ++n) w.step(Real(1) / 60);
  // Fallen about g/2 = 4.9 m (the solver's damping aside): far outside the leaves they had.
  EXPECT_LT(w.position(ids[0]).y(), 16);
  for (const BodyId id : ids) expect_found_from_above(w, id);
  // Stepped again after that query, and queried again: the marks of the second run are refitted.
  for (int n = 0; n < 30; ++n) w.step(Real(1) / 60);
  for (const BodyId id : ids) expect_found_from_above(w, id);
}

// A destroy swap-removes: the last body takes the destroyed one's index, and its mark (moved by
// the steps, not yet refitted) must go with it. The destroyed body is static (never marked), so
// without that the last body's leaf would stay where it was created.
TEST(QueryRefit, TheLastBodyKeepsItsMarkWhenItTakesADestroyedBodysIndex) {
  World w;
  const BodyId fixed = test::add_body(w, test::box_shape(Vec3::Constant(Real(0.5))),
                                      test::at(Vec3(-50, 0, 0), MotionType::Static));
  const std::vector<BodyId> ids = add_falling_row(w, 3);
  for (int n = 0; n < 60; ++n) w.step(Real(1) / 60);
  w.destroy_body(fixed);
  for (const BodyId id : ids) expect_found_from_above(w, id);
}

// A body moved by the API after the steps (its leaf placed at once, its mark cleared) is found at
// its new pose and nowhere along its fall; the others, refitted at the query, at theirs.
TEST(QueryRefit, ABodyMovedByTheApiAfterAStepIsFoundWhereItWasPut) {
  World w;
  const std::vector<BodyId> ids = add_falling_row(w, 4);
  for (int n = 0; n < 60; ++n) w.step(Real(1) / 60);
  w.set_position(ids[1], Vec3(2, 40, 0));
  for (const BodyId id : ids) expect_found_from_above(w, id);
  std::vector<BodyId> below;
  w.overlap_box(Vec3(1.5, -100, -1), Vec3(2.5, 30, 1), below);
  EXPECT_TRUE(below.empty()) << "body 1 is found where the step left it";
}

// determinism: the continuous stage picks a fast body's static candidates by their leaves during
// the step, so a static body's leaf must not depend on when the world was queried. Two twin worlds
// step a falling sphere alike, one queried after every step (its leaf refitted each time) and one
// never; made static, the sphere has the same leaf in both: its box grown by the margin.
TEST(QueryRefit, ABodyMadeStaticGetsTheSameLeafWhetherOrNotTheWorldWasQueried) {
  World queried, plain;
  const std::vector<BodyId> queried_ids = add_falling_row(queried, 1);
  const std::vector<BodyId> plain_ids = add_falling_row(plain, 1);
  std::vector<BodyId> out;
  // 15 steps: 2.5 m/s, so the queried world's leaf, stretched by four steps' fall (16 cm), is
  // within the slack that update_moving keeps a leaf in; the plain world's leaf, made at rest,
  // no longer holds the sphere 28 cm lower.
  for (int n = 0; n < 15; ++n) {
    queried.step(Real(1) / 60);
    plain.step(Real(1) / 60);
    queried.overlap_point(Vec3::Zero(), out);  // any query refits the moved leaves
  }
  queried.set_motion_type(queried_ids[0], MotionType::Static);
  plain.set_motion_type(plain_ids[0], MotionType::Static);
  ASSERT_EQ(queried.position(queried_ids[0]), plain.position(plain_ids[0]));
  const auto leaf = [](const World& w, BodyId id) {
    const detail::WorldState& s = detail::state_of(w);
    return s.query.tree.fat_box(uint32_t(detail::index_of(s, id)));
  };
  const detail::TreeBox a = leaf(queried, queried_ids[0]);
  const detail::TreeBox b = leaf(plain, plain_ids[0]);
  EXPECT_EQ(a.lo, b.lo);
  EXPECT_EQ(a.hi, b.hi);
  const Vec3 c = plain.position(plain_ids[0]);
  const Vec3 reach = Vec3::Constant(kRadius + detail::kQueryFatMargin);
  EXPECT_TRUE((b.lo - (c - reach)).cwiseAbs().maxCoeff() < kTol) << "leaf " << b.lo.transpose();
  EXPECT_TRUE((b.hi - (c + reach)).cwiseAbs().maxCoeff() < kTol) << "leaf " << b.hi.transpose();
}

}  // namespace queries_refit_test
}  // namespace elan
