// SPDX-License-Identifier: MIT
// The continuous stage: a fast body whose step's motion passes through a thin wall is put back
// where it first comes within kContinuousTarget of it; slow bodies, bodies already touching, planes
// and pairs the collide stage did not find apart (the contact solver had them) are left alone.
#include <gtest/gtest.h>

#include "broadphase/bounds.hpp"
#include "core/base/pair_key.hpp"
#include "core/world/continuous.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace world_continuous_test {

// Body 0: a static wall 4 cm thick, faces at x = 0.98 and 1.02. Bodies 1..: spheres of 5 cm
// radius at the origin, each in its own packet with the given step motion.
struct Scene {
  BodyStore bodies;
  std::vector<Shape> shapes = {test::box(Real(0.02), 1, 1), test::sphere(Real(0.05))};
  // The collide stage's apart keys (a sphere and a box: a closed form), each pair found apart.
  std::vector<uint64_t> apart;
  // The collide stage's manifolds (none unless a test adds one) and the query tree (empty unless
  // a test files the wall in it: a static body off the pair list).
  std::vector<ManifoldHead> touching;
  DynamicTree tree;
  SolverState state;

  explicit Scene(std::initializer_list<Vec3> motions) {
    const uint32_t wall = uint32_t(bodies.push_back());
    bodies.shape[wall] = 0;
    bodies.motion[wall] = uint8_t(MotionType::Static);
    bodies.set_position(wall, Vec3(1, 0, 0));
    state.packets.resize(1);
    state.masses.resize(1);
    for (const Vec3& dp : motions) {
      const uint32_t b = uint32_t(bodies.push_back());
      bodies.shape[b] = 1;
      bodies.motion[b] = uint8_t(MotionType::Dynamic);
      bodies.set_position(b, Vec3(0, Real(0.3) * Real(b), 0));
      SolverBody p;
      p.dp = dp;
      state.packets.push_back(p);
      SolverBodyMass mass;
      mass.body = b;
      state.masses.push_back(mass);
      apart.push_back(make_pair_key(wall, b));
    }
    state.packet_of.assign(bodies.size(), 0);
    for (uint32_t k = 1; k < state.masses.size(); ++k) state.packet_of[state.masses[k].body] = k;
  }
};

TEST(Continuous, FastBodyStopsAtTheWall) {
  // 2 m in one step: the sphere ends past the wall, its step's line crosses it.
  Scene s({Vec3(2, 0, 0)});
  EXPECT_EQ(solve_continuous(s.bodies, s.shapes, {}, s.apart, s.touching, s.tree, s.state), 1u);
  // Surface within the target of the face x = 0.98 (time of impact stops within a quarter of the
  // target of it, on the near side).
  const Real front = s.state.packets[1].dp.x() + Real(0.05);
  EXPECT_LE(front, Real(0.98) - Real(0.75) * kContinuousTarget);
  EXPECT_GE(front, Real(0.98) - Real(1.25) * kContinuousTarget);
  EXPECT_NEAR(s.state.packets[1].dp.y(), 0, 1e-6);
}

TEST(Continuous, SlowBodiesAndMissesAreLeftAlone) {
  // 2 cm is less than half the radius: not fast. 2 m along y is fast but runs 0.93 m from the
  // wall's face.
  Scene s({Vec3(Real(0.02), 0, 0), Vec3(0, 2, 0)});
  EXPECT_EQ(solve_continuous(s.bodies, s.shapes, {}, s.apart, s.touching, s.tree, s.state), 0u);
  EXPECT_EQ(s.state.packets[1].dp, Vec3(Real(0.02), 0, 0));
  EXPECT_EQ(s.state.packets[2].dp, Vec3(0, 2, 0));
}

TEST(Continuous, BodyAlreadyTouchingIsLeftToItsContact) {
  // Sliding fast along the wall's face, 2 mm from it: the contact solver owns this one.
  Scene s({Vec3(0, 0, 1)});
  s.bodies.set_position(1, Vec3(Real(0.98) - Real(0.05) - Real(0.002), 0, 0));
  EXPECT_EQ(solve_continuous(s.bodies, s.shapes, {}, s.apart, s.touching, s.tree, s.state), 0u);
  EXPECT_EQ(s.state.packets[1].dp, Vec3(0, 0, 1));
}

TEST(Continuous, OnlyPairsFoundApartAreCandidates) {
  // The same crossing, but the collide stage gave the pair a manifold (so no separation entry):
  // its speculative contact was in the solve.
  Scene s({Vec3(2, 0, 0)});
  EXPECT_EQ(solve_continuous(s.bodies, s.shapes, {}, {}, s.touching, s.tree, s.state), 0u);
  EXPECT_EQ(s.state.packets[1].dp, Vec3(2, 0, 0));
  EXPECT_EQ(solve_continuous(s.bodies, s.shapes, {}, s.apart, s.touching, s.tree, s.state), 1u);
}

// A pair kept with its separation (the collide stage's other list of pairs found apart).
SeparatedPair separated_entry(const Scene& s, uint32_t a, uint32_t b) {
  const Real step =
      SeparatedPair::position_step(s.shapes[s.bodies.shape[a]], s.shapes[s.bodies.shape[b]]);
  SeparatedPair entry;
  EXPECT_TRUE(SeparatedPair::make(make_pair_key(a, b), {Separation::Kind::Distance, Real(0.5)},
                                  s.bodies.position(b) - s.bodies.position(a), Quat::Identity(),
                                  step, entry));
  return entry;
}

TEST(Continuous, PairsOfBothListsAreCandidates) {
  Scene s({Vec3(2, 0, 0)});
  const std::vector<SeparatedPair> separated = {separated_entry(s, 0, 1)};
  EXPECT_EQ(solve_continuous(s.bodies, s.shapes, separated, {}, s.touching, s.tree, s.state), 1u);
}

TEST(Continuous, EarliestWallWins) {
  // A second wall nearer (x = 0.5): the sphere stops at the first one it meets.
  Scene s({Vec3(2, 0, 0)});
  const uint32_t near_wall = uint32_t(s.bodies.push_back());
  s.bodies.shape[near_wall] = 0;
  s.bodies.motion[near_wall] = uint8_t(MotionType::Static);
  s.bodies.set_position(near_wall, Vec3(Real(0.5), 0, 0));
  s.state.packet_of.push_back(0);
  // The near wall's pair in the other list: the earliest impact over both lists.
  const std::vector<SeparatedPair> separated = {separated_entry(s, 1, near_wall)};
  ASSERT_EQ(solve_continuous(s.bodies, s.shapes, separated, s.apart, s.touching, s.tree, s.state),
            1u);
  EXPECT_NEAR(s.state.packets[1].dp.x() + Real(0.05), Real(0.48) - kContinuousTarget,
              Real(0.25) * kContinuousTarget);
}

// Files body i's box in the scene's query tree, as the world keeps its static bodies there.
void file_in_tree(Scene& s, uint32_t i) {
  Vec3 lo, hi;
  const Shape& shape = s.shapes[s.bodies.shape[i]];
  shape_bounds(shape, s.bodies.position(i), s.bodies.orientation(i), lo, hi);
  if (s.tree.item_count() < s.bodies.size()) s.tree.resize_items(s.bodies.size());
  s.tree.insert(i, {lo, hi});
}

TEST(Continuous, StaticBodyOffThePairListIsFoundAlongThePathTaken) {
  // The wall was no pair of the sphere this step (its box was swept along another velocity), but
  // the step's motion crosses it: the query tree finds it, and the sphere stops at its face.
  Scene s({Vec3(2, 0, 0)});
  file_in_tree(s, 0);
  EXPECT_EQ(solve_continuous(s.bodies, s.shapes, {}, {}, s.touching, s.tree, s.state), 1u);
  const Real front = s.state.packets[1].dp.x() + Real(0.05);
  EXPECT_LE(front, Real(0.98) - Real(0.75) * kContinuousTarget);
  EXPECT_GE(front, Real(0.98) - Real(1.25) * kContinuousTarget);
}

TEST(Continuous, StaticBodyWithAManifoldIsLeftToTheSolveThoughInTheTree) {
  Scene s({Vec3(2, 0, 0)});
  file_in_tree(s, 0);
  ManifoldHead head;
  head.body_a = 0;
  head.body_b = 1;
  s.touching.push_back(head);
  EXPECT_EQ(solve_continuous(s.bodies, s.shapes, {}, {}, s.touching, s.tree, s.state), 0u);
  EXPECT_EQ(s.state.packets[1].dp, Vec3(2, 0, 0));
}

// A few static bodies are tested one by one, many through the tree: the same stop either way,
// with dynamic leaves in the tree too (the world files every body there).
TEST(Continuous, FewAndManyStaticBodiesGiveTheSameStop) {
  const auto stop_with = [](int extra_walls) {
    Scene s({Vec3(2, 0, 0)});
    for (int k = 0; k < extra_walls; ++k) {
      const uint32_t wall = uint32_t(s.bodies.push_back());
      s.bodies.shape[wall] = 0;
      s.bodies.motion[wall] = uint8_t(MotionType::Static);
      // Beside the path (z from 3 m), and one more across it behind the first wall.
      s.bodies.set_position(wall, k == 0 ? Vec3(Real(1.5), 0, 0) : Vec3(1, 0, Real(2 + k)));
      s.state.packet_of.push_back(0);
    }
    for (uint32_t i = 0; i < s.bodies.size(); ++i) file_in_tree(s, i);
    EXPECT_EQ(solve_continuous(s.bodies, s.shapes, {}, {}, s.touching, s.tree, s.state), 1u);
    return s.state.packets[1].dp;
  };
  const Vec3 few = stop_with(3), many = stop_with(40);
  EXPECT_EQ(few, many);
  EXPECT_NEAR(few.x() + Real(0.05), Real(0.98) - kContinuousTarget, Real(0.25) * kContinuousTarget);
}

}  // namespace world_continuous_test
}  // namespace elan::detail
