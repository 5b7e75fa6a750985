// SPDX-License-Identifier: MIT
// The collide stage: bit-identical results under 1 and 2 threads on a pile of mixed shapes,
// A/B choice (static as B), and warm-start impulses carried by key and feature id.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <random>

#include "core/base/pair_key.hpp"
#include "narrowphase_test_shapes.hpp"

namespace elan::detail {
namespace narrowphase_collide_pairs_test {

struct Pile {
  BodyStore bodies;
  std::vector<Shape> shapes;
  std::vector<uint64_t> pairs;
};

// Mixed shapes at random poses in a small volume on a static ground box (body 0), pairs from
// overlapping bounding spheres (a brute-force broadphase), sorted by key.
Pile make_pile(int n, uint32_t seed) {
  Pile p;
  p.shapes = {test::box(20, Real(0.5), 20),
              test::box(Real(0.4), Real(0.3), Real(0.5)),
              test::sphere(Real(0.4)),
              test::capsule(Real(0.25), Real(0.4)),
              test::cylinder(Real(0.35), Real(0.3)),
              test::round_hull(16, Real(0.45)),
              test::box_hull(Real(0.3), Real(0.5), Real(0.4))};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  const uint32_t g = uint32_t(p.bodies.push_back());
  p.bodies.shape[g] = 0;
  p.bodies.motion[g] = uint8_t(MotionType::Static);
  p.bodies.set_position(g, Vec3(0, Real(-0.5), 0));
  for (int i = 0; i < n; ++i) {
    const uint32_t b = uint32_t(p.bodies.push_back());
    p.bodies.shape[b] = 1 + uint32_t(i % 6);
    p.bodies.motion[b] = uint8_t(MotionType::Dynamic);
    p.bodies.set_position(b,
                          Vec3{Real(2.5 * u(rng)), Real(1.2 + 1.2 * u(rng)), Real(2.5 * u(rng))});
    p.bodies.set_orientation(b, test::random_turn(rng, u));
    p.bodies.set_linear_velocity(b, test::draw3(rng, u));
  }
  for (uint32_t i = 0; i < p.bodies.size(); ++i) {
    for (uint32_t j = i + 1; j < p.bodies.size(); ++j) {
      const Real r = p.shapes[p.bodies.shape[i]].bounding_radius +
                     p.shapes[p.bodies.shape[j]].bounding_radius + Real(0.1);
      if (i == 0) {
        if (p.bodies.position(j).y() - r < Real(0.1)) p.pairs.push_back(make_pair_key(i, j));
      } else if ((p.bodies.position(i) - p.bodies.position(j)).norm() < r) {
        p.pairs.push_back(make_pair_key(i, j));
      }
    }
  }
  return p;
}

// The separation cache's two lists, held by a test between calls.
struct ApartPairs {
  std::vector<SeparatedPair> separated;
  std::vector<uint64_t> keys;

  void clear() {
    separated.clear();
    keys.clear();
  }
};

// collide_pairs on a list of whole manifolds, their poses and the separation cache: the store
// rebuilt from them, and they read back after.
void collide_list(std::span<const uint64_t> pairs, const Pile& p, const CollideSettings& settings,
                  std::span<const uint8_t> idle, ContactStore& store, std::vector<Manifold>& list,
                  ApartPairs& apart, std::vector<PairCache>& poses) {
  store.restore(list, poses, apart.separated, apart.keys);
  collide_pairs(pairs, p.bodies, p.shapes, settings, idle, store);
  list = store.manifolds();
  poses.assign(store.pair_cache().begin(), store.pair_cache().end());
  const ApartCandidates apart_now = store.continuous_candidates();
  apart.separated.assign(apart_now.separated.begin(), apart_now.separated.end());
  apart.keys.assign(apart_now.keys.begin(), apart_now.keys.end());
}

void expect_identical(const std::vector<Manifold>& x, const std::vector<Manifold>& y) {
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    ASSERT_EQ(x[i].key(), y[i].key());
    ASSERT_EQ(x[i].body_a, y[i].body_a);
    ASSERT_EQ(x[i].point_count, y[i].point_count);
    ASSERT_EQ(std::memcmp(x[i].normal.data(), y[i].normal.data(), sizeof(Vec3)), 0);
    for (int k = 0; k < x[i].point_count; ++k) {
      const ContactPoint &a = x[i].points[k], &b = y[i].points[k];
      ASSERT_EQ(std::memcmp(a.anchor_a.data(), b.anchor_a.data(), sizeof(Vec3)), 0);
      ASSERT_EQ(std::memcmp(&a.separation, &b.separation, sizeof(Real)), 0);
      ASSERT_EQ(a.feature_id, b.feature_id);
      ASSERT_EQ(std::memcmp(&a.normal_impulse, &b.normal_impulse, sizeof(Real)), 0);
    }
  }
}

TEST(CollidePairs, BitIdenticalUnderOneAndTwoThreads) {
  const Pile p = make_pile(300, 7);
  ASSERT_GT(p.pairs.size(), 256u) << "enough pairs for several blocks";
  CollideSettings settings;
  ContactStore slots1, slots2;
  ApartPairs apart1, apart2;
  std::vector<PairCache> poses1, poses2;
  std::vector<Manifold> out1, out2;
  tbb::task_arena(1).execute(
      [&] { collide_list(p.pairs, p, settings, {}, slots1, out1, apart1, poses1); });
  tbb::task_arena(2).execute(
      [&] { collide_list(p.pairs, p, settings, {}, slots2, out2, apart2, poses2); });
  ASSERT_GT(out1.size(), 50u);
  expect_identical(out1, out2);
  // Keys sorted and unique; static ground is always B; the normal is unit.
  for (std::size_t i = 0; i < out1.size(); ++i) {
    if (i > 0) {
      EXPECT_LT(out1[i - 1].key(), out1[i].key());
    }
    EXPECT_EQ(out1[i].key(), make_pair_key(out1[i].body_a, out1[i].body_b));
    EXPECT_NE(out1[i].body_a, 0u);
    EXPECT_NEAR(out1[i].normal.norm(), 1, 1e-4);
  }
  // Warm start under both thread counts gives the same bits too.
  for (Manifold& m : out1) {
    for (int k = 0; k < m.point_count; ++k)
      m.points[k].normal_impulse = Real(m.points[k].feature_id % 97);
  }
  out2 = out1;
  tbb::task_arena(1).execute(
      [&] { collide_list(p.pairs, p, settings, {}, slots1, out1, apart1, poses1); });
  tbb::task_arena(2).execute(
      [&] { collide_list(p.pairs, p, settings, {}, slots2, out2, apart2, poses2); });
  expect_identical(out1, out2);
}

// Deepest point of a manifold (m).
Real deepest(const Manifold& m) {
  Real s = std::numeric_limits<Real>::max();
  for (int k = 0; k < m.point_count; ++k) s = std::min(s, m.points[k].separation);
  return s;
}

// Regression: a manifold carried by the pair cache step after step added the whole motion since
// its exact test again at every step, so after k equal moves its separation was off by about
// k(k-1)/2 moves along the normal. Carried four times, it must still agree with a fresh exact
// test of the same poses: within one move's length (4.7e-5 m), against the six moves along the
// normal the old error reached. Not closer: a carried point stays fixed to the bodies, while a
// fresh clip slides a point where an incident edge crosses a side plane along that edge, and the
// pile's deep, tilted overlaps (0.2 m and more) make that 2e-5 m over these four moves.
TEST(CollidePairs, CarriedManifoldsAgreeWithTheExactTest) {
  Pile p = make_pile(200, 5);
  CollideSettings settings;
  ContactStore slots;
  ApartPairs apart;
  std::vector<PairCache> carried_poses, exact_poses;
  std::vector<Manifold> carried, exact;
  collide_list(p.pairs, p, settings, {}, slots, carried, apart, carried_poses);
  // 0.047 mm per move for every other body: four moves stay inside the cache's 1 mm.
  const Vec3 move(Real(3e-5), Real(-3e-5), Real(2e-5));
  for (int k = 0; k < 4; ++k) {
    for (uint32_t b = 1; b < p.bodies.size(); b += 2) {
      p.bodies.set_position(b, p.bodies.position(b) + move);
    }
    collide_list(p.pairs, p, settings, {}, slots, carried, apart, carried_poses);
  }
  collide_list(p.pairs, p, settings, {}, slots, exact, apart, exact_poses);
  std::size_t j = 0;
  int compared = 0;
  for (const Manifold& m : carried) {
    while (j < exact.size() && exact[j].key() < m.key()) ++j;
    if (j == exact.size() || exact[j].key() != m.key()) continue;
    EXPECT_NEAR(deepest(m), deepest(exact[j]), move.norm())
        << "pair " << m.body_a << "-" << m.body_b;
    ++compared;
  }
  EXPECT_GT(compared, 50);
}

TEST(CollidePairs, WarmStartCopiesImpulsesByFeatureId) {
  Pile p = make_pile(200, 11);
  CollideSettings settings;
  ContactStore slots;
  ApartPairs apart;
  std::vector<PairCache> poses;
  std::vector<Manifold> first, second;
  collide_list(p.pairs, p, settings, {}, slots, first, apart, poses);
  int points = 0;
  for (Manifold& m : first) {
    for (int k = 0; k < m.point_count; ++k) {
      EXPECT_EQ(m.points[k].normal_impulse, 0);
      m.points[k].normal_impulse = Real(1 + m.points[k].feature_id % 1000);
      ++points;
    }
    m.tangent_impulse[0] = Real(m.key() % 13);
    m.tangent_impulse[1] = -Real(m.key() % 7);
    m.twist_impulse = Real(m.key() % 5);
  }
  ASSERT_GT(points, 100);
  // Nudge every dynamic body by 1e-4 m: the same features touch, so every impulse arrives.
  for (uint32_t b = 1; b < p.bodies.size(); ++b) {
    p.bodies.set_position(b, p.bodies.position(b) + Vec3(Real(1e-4), 0, Real(-1e-4)));
  }
  second = first;
  collide_list(p.pairs, p, settings, {}, slots, second, apart, poses);
  std::size_t j = 0;
  int matched = 0, total = 0;
  for (const Manifold& m : second) {
    while (j < first.size() && first[j].key() < m.key()) ++j;
    if (j < first.size() && first[j].key() == m.key() &&
        first[j].normal.dot(m.normal) > Real(0.95)) {
      // Friction is per manifold: it follows the pair whatever its points are called, as a
      // world impulse projected onto the new tangent plane (the basis of a slightly turned
      // normal may be built from another axis).
      Vec3 a1, a2, b1, b2;
      tangent_basis(first[j].normal, a1, a2);
      tangent_basis(m.normal, b1, b2);
      const Vec3 before = first[j].tangent_impulse[0] * a1 + first[j].tangent_impulse[1] * a2;
      const Vec3 after = m.tangent_impulse[0] * b1 + m.tangent_impulse[1] * b2;
      const Vec3 expected = before - before.dot(m.normal) * m.normal;
      EXPECT_LT((after - expected).norm(), Real(1e-4) * (1 + before.norm()));
      EXPECT_EQ(m.twist_impulse, first[j].twist_impulse);
    }
    for (int k = 0; k < m.point_count; ++k) {
      ++total;
      const ContactPoint& c = m.points[k];
      const ContactPoint* old = nullptr;
      if (j < first.size() && first[j].key() == m.key()) {
        for (int i = 0; i < first[j].point_count; ++i) {
          if (first[j].points[i].feature_id == c.feature_id) old = &first[j].points[i];
        }
      }
      if (old) {
        ++matched;
        EXPECT_EQ(c.normal_impulse, old->normal_impulse);
      } else if (c.normal_impulse != 0) {
        // No id match: the impulse may only come from a previous point within 2 cm.
        bool near = false;
        for (int i = 0; j < first.size() && i < first[j].point_count; ++i) {
          near = near || (first[j].points[i].normal_impulse == c.normal_impulse &&
                          (first[j].points[i].anchor_a - c.anchor_a).norm() < Real(0.02));
        }
        EXPECT_TRUE(near);
      }
    }
  }
  EXPECT_GT(matched, total * 9 / 10) << "small motion keeps almost every feature";
}

// The list is updated in place: manifolds that end leave gaps, new keys are merged in, and whole
// blocks move left or right. Starting from lists with long runs of both (last step's manifolds
// missing, and stale keys of pairs the broadphase no longer reports), the result must be exactly
// the touching pairs in key order, with the same bits under 1 and 2 threads.
TEST(CollidePairs, InPlaceUpdateGivesEveryTouchingPairWhateverTheListHeld) {
  const Pile p = make_pile(400, 3);
  CollideSettings settings;
  ContactStore slots;
  ApartPairs apart;
  std::vector<PairCache> poses;
  std::vector<Manifold> fresh;
  collide_list(p.pairs, p, settings, {}, slots, fresh, apart, poses);
  ASSERT_GT(p.pairs.size(), 8 * 64u) << "enough blocks of pairs to shift across";
  std::vector<uint64_t> stale;
  for (uint32_t i = 1; i < p.bodies.size(); ++i) {
    for (uint32_t j = i + 1; j < p.bodies.size(); ++j) {
      const uint64_t key = make_pair_key(i, j);
      if (!std::binary_search(p.pairs.begin(), p.pairs.end(), key)) stale.push_back(key);
    }
  }
  std::mt19937 rng(17);
  for (int trial = 0; trial < 12; ++trial) {
    // Runs of about 40 keys alternate between dropping and keeping last step's manifolds and
    // between few and many stale keys, so shifts grow and shrink along the list.
    std::vector<Manifold> start;
    std::size_t s = 0;
    for (std::size_t i = 0; i < fresh.size(); ++i) {
      const bool drop_run = ((i / 40 + trial) % 3) == 0;
      const int stale_here = ((i / 40 + trial) % 4) == 1 ? 3 : int(rng() % 2);
      for (int k = 0; k < stale_here && s < stale.size(); ++k, s += 1 + rng() % 5) {
        if (stale[s] > fresh[i].key()) break;
        Manifold m;
        m.body_a = pair_first(stale[s]);
        m.body_b = pair_second(stale[s]);
        m.point_count = 1;
        start.push_back(m);
      }
      while (s < stale.size() && stale[s] < fresh[i].key()) ++s;
      if (!drop_run || rng() % 8 == 0) start.push_back(fresh[i]);
    }
    // The poses of fresh's pairs, some now without a manifold, which collide_pairs must drop.
    std::vector<Manifold> one = start, two = start;
    std::vector<PairCache> poses_one = poses, poses_two = poses;
    tbb::task_arena(1).execute(
        [&] { collide_list(p.pairs, p, settings, {}, slots, one, apart, poses_one); });
    tbb::task_arena(2).execute(
        [&] { collide_list(p.pairs, p, settings, {}, slots, two, apart, poses_two); });
    ASSERT_EQ(one.size(), fresh.size()) << "trial " << trial;
    for (std::size_t i = 0; i < one.size(); ++i) {
      ASSERT_EQ(one[i].key(), fresh[i].key()) << "trial " << trial << ", manifold " << i;
      ASSERT_EQ(one[i].point_count, fresh[i].point_count);
    }
    expect_identical(one, two);
  }
}

// The separation cache skips a pair's exact test only while the test would reject it again, so
// a run with the cache gives the bits of a run without it. Bodies drift towards the middle and
// turn by up to 2 degrees a step (some by 25), so cached pairs close in and start touching.
TEST(CollidePairs, SeparationCacheGivesTheBitsOfTheExactTests) {
  Pile p = make_pile(300, 21);
  CollideSettings settings;
  ContactStore slots_cached, slots_exact;
  std::vector<Manifold> cached, exact;
  ApartPairs apart, none;
  std::vector<PairCache> cached_poses, exact_poses;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1, 1);
  int kept = 0, closed_in = 0, closed_form_pairs = 0, closed_form_apart = 0, edge_pairs = 0;
  std::vector<SeparatedPair> before;
  for (int step = 0; step < 24; ++step) {
    collide_list(p.pairs, p, settings, {}, slots_cached, cached, apart, cached_poses);
    none.clear();
    collide_list(p.pairs, p, settings, {}, slots_exact, exact, none, exact_poses);
    expect_identical(cached, exact);
    if (HasFatalFailure()) return;
    for (const Manifold& m : cached) {
      closed_in += std::any_of(before.begin(), before.end(),
                               [&](const SeparatedPair& s) { return s.key == m.key(); })
                       ? 1
                       : 0;
    }
    before = apart.separated;
    // Every pair is in exactly one of the lists: touching, or found apart (the continuous
    // stage's candidates), kept with its separation or by key alone; each list in key order.
    std::vector<uint64_t> listed;
    for (const Manifold& m : cached) listed.push_back(m.key());
    for (const SeparatedPair& s : apart.separated) listed.push_back(s.key);
    listed.insert(listed.end(), apart.keys.begin(), apart.keys.end());
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(listed, p.pairs);
    EXPECT_TRUE(std::is_sorted(apart.keys.begin(), apart.keys.end()));
    auto closed_form = [&](uint64_t key) {
      return exact_test_is_closed_form(p.shapes[p.bodies.shape[pair_first(key)]],
                                       p.shapes[p.bodies.shape[pair_second(key)]]);
    };
    // Pairs with a closed-form test are kept by key alone (checking a separation costs about
    // what the test does); most others with their separation.
    for (uint64_t key : apart.keys) closed_form_apart += closed_form(key) ? 1 : 0;
    for (const SeparatedPair& s : apart.separated) {
      EXPECT_FALSE(closed_form(s.key));
      if (s.kind() == Separation::Kind::EdgePair) {
        // An SAT rejection on an edge axis: the two edges, re-tested while they still separate.
        ++edge_pairs;
        EXPECT_GE(s.edge_a(), 0);
        EXPECT_GE(s.edge_b(), 0);
        continue;
      }
      EXPECT_GT(s.gap(), 0);
      uint32_t a = pair_first(s.key), b = pair_second(s.key);
      if (a == 0) std::swap(a, b);  // the static ground is B
      const Vec3 now =
          p.bodies.orientation(a).conjugate() * (p.bodies.position(b) - p.bodies.position(a));
      const Real step =
          SeparatedPair::position_step(p.shapes[p.bodies.shape[a]], p.shapes[p.bodies.shape[b]]);
      bool same = true;
      for (int k = 0; k < 3; ++k) same = same && std::lrint(now[k] / step) == s.position[k];
      kept += same ? 0 : 1;
    }
    for (uint32_t b = 1; b < p.bodies.size(); ++b) {
      const Vec3 x = p.bodies.position(b);
      const Vec3 inwards = Vec3(-x.x(), Real(1.2) - x.y(), -x.z()).normalized();
      p.bodies.set_position(b, x + Real(3e-3) * inwards + test::draw3(rng, u, Real(1e-3)));
      const Real degrees = (b + step) % 17 == 0 ? 25 : 2 * std::abs(u(rng));
      const Vec3 axis = Vec3{u(rng), u(rng), u(rng) + Real(1.1)}.normalized();
      const Quat turn(Eigen::AngleAxis<Real>(degrees * Real(3.14159265 / 180), axis));
      p.bodies.set_orientation(b, (turn * p.bodies.orientation(b)).normalized());
    }
  }
  for (uint64_t key : p.pairs) {
    closed_form_pairs += exact_test_is_closed_form(p.shapes[p.bodies.shape[pair_first(key)]],
                                                   p.shapes[p.bodies.shape[pair_second(key)]]);
  }
  EXPECT_GT(closed_form_pairs, 100) << "the pile has pairs the cache leaves out";
  EXPECT_GT(closed_form_apart, 100) << "closed-form pairs found apart, kept by key";
  EXPECT_GT(kept, 2000) << "pairs skipped: entries kept from an earlier pose";
  EXPECT_GT(edge_pairs, 50) << "SAT pairs apart along an edge axis, kept by their two edges";
  EXPECT_GT(closed_in, 20) << "cached pairs that went on to touch";
}

// An edge pair's entry holds its two edges and no gap; ended, it is of kind Unknown like any.
TEST(SeparatedPair, HoldsAnEdgePairByItsEdges) {
  Separation edges{Separation::Kind::EdgePair, Real(0.1), 37, 12};
  SeparatedPair s;
  ASSERT_TRUE(SeparatedPair::make(5, edges, Vec3::Zero(), Quat::Identity(), Real(1e-4), s));
  EXPECT_EQ(s.key, 5u);
  EXPECT_EQ(s.kind(), Separation::Kind::EdgePair);
  EXPECT_EQ(s.edge_a(), 37);
  EXPECT_EQ(s.edge_b(), 12);
  EXPECT_FALSE(s.gap() > 0) << "no gap for closing() to trust";
  s.end();
  EXPECT_EQ(s.kind(), Separation::Kind::Unknown);
  edges.edge_a = 40000;  // past int16
  EXPECT_FALSE(SeparatedPair::make(5, edges, Vec3::Zero(), Quat::Identity(), Real(1e-4), s));
  edges.edge_a = -1;
  EXPECT_FALSE(SeparatedPair::make(5, edges, Vec3::Zero(), Quat::Identity(), Real(1e-4), s));
}

// The separation cache's 24-byte entry: each code errs on the side closing() can account for.
// The gap comes back no larger and within 2^-18 of itself, the kind and the rotation's left-out
// component survive in the gap's low bits, the position within (sqrt 3 / 2) of its step, the
// rotation within PackedRotation's bound; what the codes cannot hold is refused, not rounded.
TEST(SeparatedPair, CodesErrOnTheSideClosingAccountsFor) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(-1, 1);
  std::normal_distribution<float> n(0, 1);
  Shape a, b;
  a.bounding_radius = Real(0.7);
  b.bounding_radius = Real(1.3);
  const Real step = SeparatedPair::position_step(a, b);
  const Real reach = 32767 * step;  // each coordinate's range
  EXPECT_NEAR(reach, 2 * (a.bounding_radius + b.bounding_radius), 1e-5);
  Real worst_position = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const auto kind = Separation::Kind(1 + trial % 3);
    const Real gap = std::exp(Real(9) * u(rng)) * Real(0.01);
    const Vec3 position = test::draw3(rng, u, reach);
    const Quat rotation = Quat{n(rng), n(rng), n(rng), n(rng)}.normalized();
    SeparatedPair s;
    ASSERT_TRUE(SeparatedPair::make(42, {kind, gap}, position, rotation, step, s));
    EXPECT_EQ(s.key, 42u);
    EXPECT_EQ(s.kind(), kind);
    EXPECT_LE(s.gap(), gap);
    EXPECT_GE(s.gap(), gap * (1 - std::ldexp(Real(1), -18)));
    const Real error = (s.position_at(step) - position).norm();
    worst_position = std::max(worst_position, error);
    EXPECT_LE(error, Real(0.8661) * step);
    const Vec3 point = test::draw3(rng, n);
    EXPECT_LE((s.rotation_value() * point - rotation * point).norm(),
              PackedRotation::kError * point.norm());
    s.end();
    EXPECT_EQ(s.kind(), Separation::Kind::Unknown);
    if (HasFailure()) return;
  }
  EXPECT_GT(worst_position, Real(0.5) * step) << "the position is rounded to its step, no finer";
  SeparatedPair s;
  const Vec3 inside(reach, -reach, 0);
  EXPECT_TRUE(
      SeparatedPair::make(1, {Separation::Kind::Distance, 1}, inside, Quat::Identity(), step, s));
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Real inf = std::numeric_limits<Real>::infinity();
  const Separation distance{Separation::Kind::Distance, 1};
  EXPECT_FALSE(
      SeparatedPair::make(1, {Separation::Kind::Unknown, 1}, inside, Quat::Identity(), step, s));
  for (const Real gap : {Real(0), Real(-1), nan, inf}) {
    EXPECT_FALSE(
        SeparatedPair::make(1, {Separation::Kind::FaceOfA, gap}, inside, Quat::Identity(), step, s))
        << gap;
  }
  EXPECT_FALSE(
      SeparatedPair::make(1, distance, Vec3(0, 0, Real(1.001) * reach), Quat::Identity(), step, s));
  EXPECT_FALSE(SeparatedPair::make(1, distance, Vec3(nan, 0, 0), Quat::Identity(), step, s));
  EXPECT_FALSE(SeparatedPair::make(1, distance, inside, Quat::Identity(), 0, s));
}

// The contact events come from what collide_pairs reports it changed in the list: exactly the
// keys that left it and the keys that joined it, each in key order, an ended manifold with A and
// B as it had them (an end event names them so).
TEST(CollidePairs, ReportsTheManifoldsThatEndedAndTheKeysThatBegan) {
  Pile p = make_pile(200, 17);
  CollideSettings settings;
  ContactStore slots;
  ApartPairs apart;
  std::vector<PairCache> poses;
  std::vector<Manifold> list;
  collide_list(p.pairs, p, settings, {}, slots, list, apart, poses);
  ASSERT_GT(list.size(), 100u);
  EXPECT_TRUE(slots.ended().empty());
  ASSERT_EQ(slots.began().size(), list.size());
  for (std::size_t i = 0; i < list.size(); ++i) EXPECT_EQ(slots.began()[i], list[i].key());

  // Every third pair dropped and every fourth body moved: some contacts end, others begin.
  const std::vector<Manifold> before = list;
  std::vector<uint64_t> kept;
  for (std::size_t i = 0; i < p.pairs.size(); ++i) {
    if (i % 3 != 0) kept.push_back(p.pairs[i]);
  }
  for (uint32_t b = 1; b < p.bodies.size(); b += 4) {
    p.bodies.set_position(b, p.bodies.position(b) + Vec3(Real(0.15), Real(-0.1), Real(0.1)));
  }
  tbb::task_arena arena(2);
  arena.execute([&] { collide_list(kept, p, settings, {}, slots, list, apart, poses); });
  std::vector<ContactRecord> ended;
  std::vector<uint64_t> began;
  std::size_t j = 0;
  for (const Manifold& m : before) {
    while (j < list.size() && list[j].key() < m.key()) began.push_back(list[j++].key());
    if (j < list.size() && list[j].key() == m.key()) {
      ++j;
    } else {
      ended.push_back({m.body_a, m.body_b});
    }
  }
  for (; j < list.size(); ++j) began.push_back(list[j].key());
  ASSERT_GT(ended.size(), 10u);
  ASSERT_GT(began.size(), 0u);
  ASSERT_EQ(slots.ended().size(), ended.size());
  for (std::size_t i = 0; i < ended.size(); ++i) {
    EXPECT_EQ(slots.ended()[i].body_a, ended[i].body_a);
    EXPECT_EQ(slots.ended()[i].body_b, ended[i].body_b);
  }
  EXPECT_EQ(std::vector<uint64_t>(slots.began().begin(), slots.began().end()), began);
}

// The lists beside the heads hold the tails of exactly the manifolds with more than one point
// and the poses of exactly those that may reuse their points (neither body round), in key order:
// new ones get them, ended ones lose them, and carried ones (two idle bodies, no pair this step)
// keep theirs unchanged. Small moves between steps make pairs reuse their points, so the poses
// are updated in place as well as replaced, and manifolds change their point counts.
TEST(CollidePairs, KeepsTheTailsAndPosesOfExactlyTheManifoldsThatHaveThem) {
  Pile p = make_pile(300, 23);
  CollideSettings settings;
  ContactStore slots;
  ApartPairs apart;
  std::vector<PairCache> poses;
  std::vector<ManifoldHead> list;
  std::vector<ManifoldTail> tails;
  auto round = [&](uint32_t body) {
    const ShapeType t = p.shapes[p.bodies.shape[body]].type;
    return t == ShapeType::Sphere || t == ShapeType::Capsule || t == ShapeType::Cylinder;
  };
  // Bodies 1-60 fall asleep after the first step: their pairs with each other and the ground
  // leave the pair list, as the broadphase leaves them out, and their manifolds are carried.
  std::vector<uint8_t> idle(p.bodies.size(), 0);
  idle[0] = 1;
  std::vector<PairCache> carried_before;
  std::vector<ManifoldTail> carried_tails;
  int reused = 0, carried = 0, carried_tail = 0, tails_replaced = 0;
  for (int step = 0; step < 6; ++step) {
    std::vector<uint64_t> pairs;
    for (uint64_t key : p.pairs) {
      if (!(step > 0 && idle[pair_first(key)] && idle[pair_second(key)])) pairs.push_back(key);
    }
    const std::size_t tails_before = tails.size();
    tbb::task_arena(2).execute(
        [&] { collide_pairs(pairs, p.bodies, p.shapes, settings, idle, slots); });
    list.assign(slots.heads().begin(), slots.heads().end());
    tails.assign(slots.tails().begin(), slots.tails().end());
    poses.assign(slots.pair_cache().begin(), slots.pair_cache().end());
    std::vector<uint64_t> expected, expected_tails;
    for (const ManifoldHead& m : list) {
      if (!round(m.body_a) && !round(m.body_b)) expected.push_back(m.key());
      if (m.point_count > 1) expected_tails.push_back(m.key());
    }
    std::vector<uint64_t> keys, tail_keys;
    for (const PairCache& c : poses) keys.push_back(c.key);
    for (const ManifoldTail& t : tails) tail_keys.push_back(t.key);
    ASSERT_EQ(keys, expected) << "step " << step;
    ASSERT_EQ(tail_keys, expected_tails) << "step " << step;
    tails_replaced += step > 0 && tails.size() != tails_before;
    for (const ManifoldTail& t : tails) {
      for (const ManifoldTail& b : carried_tails) {
        if (b.key != t.key) continue;
        EXPECT_EQ(std::memcmp(b.points, t.points, sizeof(t.points)), 0) << "carried tail changed";
        ++carried_tail;
      }
    }
    for (const PairCache& c : poses) {
      reused += std::memcmp(c.exact_position.data(), c.relative_position.data(), sizeof(Vec3)) != 0;
      for (const PairCache& b : carried_before) {
        if (b.key != c.key) continue;
        // Field by field: the padding byte need not be copied.
        const bool same =
            std::memcmp(b.orientation_a.coeffs().data(), c.orientation_a.coeffs().data(),
                        4 * sizeof(Real)) == 0 &&
            std::memcmp(b.orientation_b.coeffs().data(), c.orientation_b.coeffs().data(),
                        4 * sizeof(Real)) == 0 &&
            std::memcmp(b.relative_position.data(), c.relative_position.data(), sizeof(Vec3)) ==
                0 &&
            std::memcmp(b.exact_position.data(), c.exact_position.data(), sizeof(Vec3)) == 0 &&
            std::memcmp(b.exact_rotation.bytes, c.exact_rotation.bytes, 7) == 0;
        EXPECT_TRUE(same) << "carried poses changed";
        ++carried;
      }
    }
    if (step == 0) {
      for (uint32_t b = 1; b <= 60; ++b) idle[b] = 1;
      for (const PairCache& c : poses) {
        if (idle[pair_first(c.key)] && idle[pair_second(c.key)]) carried_before.push_back(c);
      }
      for (const ManifoldTail& t : tails) {
        if (idle[pair_first(t.key)] && idle[pair_second(t.key)]) carried_tails.push_back(t);
      }
    }
    // The awake bodies move 0.1 mm and turn 0.1 degree, inside the cache's tolerance; every
    // fourth moves 5 cm, outside it.
    for (uint32_t b = 61; b < p.bodies.size(); ++b) {
      const Real d = b % 4 == 0 ? Real(0.05) : Real(1e-4);
      p.bodies.set_position(b, p.bodies.position(b) + Vec3(d, -d, 0));
      const Quat turn(Eigen::AngleAxis<Real>(Real(0.1 * 3.14159265 / 180), Vec3::UnitY()));
      p.bodies.set_orientation(b, (turn * p.bodies.orientation(b)).normalized());
    }
  }
  EXPECT_GT(poses.size(), 50u);
  EXPECT_LT(poses.size(), list.size()) << "the pile has round bodies, which keep no poses";
  EXPECT_GT(reused, 100) << "poses updated by a reuse";
  EXPECT_GT(carried, 10) << "poses carried with their manifolds";
  EXPECT_GT(tails.size(), 20u);
  EXPECT_LT(tails.size(), list.size()) << "the pile has one-point manifolds, which keep no tail";
  EXPECT_GT(carried_tail, 10) << "tails carried with their manifolds";
  EXPECT_GT(tails_replaced, 0) << "manifolds that gained or lost their tail";
}

}  // namespace narrowphase_collide_pairs_test
}  // namespace elan::detail
