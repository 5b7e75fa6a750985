// SPDX-License-Identifier: MIT
// collide_pairs' carrying: last step's manifolds between two idle (static or sleeping) bodies
// whose key found no touching manifold this step are kept, merged by key into the new list; the
// ones found again, the ones with a body not idle and the empty ones are not. The join is split
// at the first key of each block of pairs, so the merge is checked across block boundaries too.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "core/base/pair_key.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_collide_carry_test {

constexpr Real kRadius = Real(0.4);

// Body 0: a static ground box with its top at y = 0. Then spheres of radius kRadius resting on
// it at the given x (so each touches the ground), with the given flags.
struct Scene {
  BodyStore bodies;
  std::vector<Shape> shapes = {test::box(1000, Real(0.5), 5), test::sphere(kRadius)};
  std::vector<uint8_t> idle;
};

Scene make_scene(const std::vector<std::pair<Real, uint8_t>>& spheres) {
  Scene s;
  const std::size_t g = s.bodies.push_back();
  s.bodies.shape[g] = 0;
  s.bodies.motion[g] = uint8_t(MotionType::Static);
  s.bodies.set_position(g, Vec3(0, Real(-0.5), 0));
  for (const auto& [x, flags] : spheres) {
    const std::size_t b = s.bodies.push_back();
    s.bodies.shape[b] = 1;
    s.bodies.motion[b] = uint8_t(MotionType::Dynamic);
    s.bodies.flags[b] = flags;
    s.bodies.set_position(b, Vec3(x, kRadius, 0));
  }
  // As the world flags them: static, or asleep and not frozen.
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    s.idle.push_back(i == 0 || !(s.bodies.flags[i] & (kAwake | kFrozen)));
  }
  return s;
}

// A manifold of last step, marked by `tag` (its first point's separation, far from any real one).
Manifold old_manifold(const Scene& s, uint32_t a, uint32_t b, Real tag, int points = 1) {
  Manifold m;
  // The static body as B, as collide_pairs orders them.
  m.body_a = s.bodies.is_dynamic(a) ? a : b;
  m.body_b = s.bodies.is_dynamic(a) ? b : a;
  m.point_count = points;
  m.points[0].separation = tag;
  return m;
}

std::vector<Manifold> run(const Scene& s, std::vector<uint64_t> pairs,
                          const std::vector<Manifold>& previous, int threads = 1) {
  std::sort(pairs.begin(), pairs.end());
  ContactStore store;
  store.restore(previous, {});
  tbb::task_arena(threads).execute(
      [&] { collide_pairs(pairs, s.bodies, s.shapes, CollideSettings{}, s.idle, store); });
  return store.manifolds();
}

TEST(CollideCarry, MergesTheIdleOnesInKeyOrder) {
  // 1, 2, 3 asleep; 4 awake, touching 2; 5 asleep but frozen.
  const Scene s =
      make_scene({{0, 0}, {3, 0}, {6, 0}, {Real(3) + 2 * kRadius, kAwake}, {9, kFrozen}});
  const std::vector<Manifold> previous = {
      old_manifold(s, 0, 1, 1),     // idle, not found again: carried
      old_manifold(s, 0, 2, 2),     // idle, found again: the new one stays
      old_manifold(s, 0, 4, 3),     // body 4 awake: dropped
      old_manifold(s, 1, 3, 4),     // idle pair of sleepers: carried
      old_manifold(s, 2, 3, 5, 0),  // no points: dropped
      old_manifold(s, 3, 5, 6),     // body 5 frozen: dropped
      old_manifold(s, 4, 5, 7),     // awake: dropped
  };
  const std::vector<Manifold> out =
      run(s, {make_pair_key(0, 2), make_pair_key(0, 3), make_pair_key(2, 4)}, previous);

  // Tag 0 marks a manifold made this step: its sphere rests on what it touches.
  const std::vector<std::pair<uint64_t, Real>> expected = {
      {make_pair_key(0, 1), 1}, {make_pair_key(0, 2), 0}, {make_pair_key(0, 3), 0},
      {make_pair_key(1, 3), 4}, {make_pair_key(2, 4), 0},
  };
  ASSERT_EQ(out.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(out[i].key(), expected[i].first) << i;
    EXPECT_NEAR(out[i].points[0].separation, expected[i].second, Real(1e-3)) << i;
  }
}

TEST(CollideCarry, CarriedBeforeAndAfterAllNewOnesAndWithoutPairs) {
  const Scene s = make_scene({{0, 0}, {3, kAwake}, {6, 0}, {9, 0}});
  const std::vector<Manifold> previous = {old_manifold(s, 0, 1, 1), old_manifold(s, 3, 4, 2)};
  const std::vector<Manifold> out = run(s, {make_pair_key(0, 2)}, previous);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].points[0].separation, 1);
  EXPECT_EQ(out[1].key(), make_pair_key(0, 2));
  EXPECT_EQ(out[2].points[0].separation, 2);

  const std::vector<Manifold> none = run(s, {}, previous);
  ASSERT_EQ(none.size(), 2u);
  EXPECT_EQ(none[0].key(), make_pair_key(0, 1));
  EXPECT_EQ(none[1].key(), make_pair_key(3, 4));
}

TEST(CollideCarry, MergesAcrossBlocksOfPairsUnderOneAndTwoThreads) {
  // 300 spheres on the ground, every third one awake: the awake ones' ground pairs are tested
  // (several blocks of pairs), the sleeping ones' manifolds are carried in between.
  std::vector<std::pair<Real, uint8_t>> spheres;
  for (int i = 0; i < 300; ++i) spheres.push_back({Real(2 * i), uint8_t(i % 3 == 0 ? kAwake : 0)});
  const Scene s = make_scene(spheres);
  std::vector<uint64_t> pairs;
  std::vector<Manifold> previous;
  for (uint32_t b = 1; b <= 300; ++b) {
    if (s.idle[b]) {
      previous.push_back(old_manifold(s, 0, b, Real(b)));
    } else {
      pairs.push_back(make_pair_key(0, b));
    }
  }
  std::sort(previous.begin(), previous.end(),
            [](const Manifold& x, const Manifold& y) { return x.key() < y.key(); });
  for (int threads : {1, 2}) {
    const std::vector<Manifold> out = run(s, pairs, previous, threads);
    ASSERT_EQ(out.size(), 300u) << threads;
    for (std::size_t i = 0; i < out.size(); ++i) {
      if (i > 0) {
        EXPECT_LT(out[i - 1].key(), out[i].key()) << i;
      }
      const uint32_t b = out[i].body_a;
      EXPECT_EQ(out[i].key(), make_pair_key(0, b));
      EXPECT_NEAR(out[i].points[0].separation, s.idle[b] ? Real(b) : Real(0), Real(1e-3)) << b;
    }
  }
}

}  // namespace narrowphase_collide_carry_test
}  // namespace elan::detail
