// SPDX-License-Identifier: MIT
// The contact store alone on hand-made lists: a step's merge (entries rewritten, added, ended, the
// changes reported in key order), remove_body's renaming and re-sort, and save/restore.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/base/pair_key.hpp"
#include "narrowphase/contact_store.hpp"

namespace elan::detail {
namespace narrowphase_contact_store_test {

// A manifold of bodies a and b (A first) with `points` points, each tagged by `tag`.
Manifold manifold(uint32_t a, uint32_t b, int points, Real tag) {
  Manifold m;
  m.body_a = a;
  m.body_b = b;
  m.point_count = uint32_t(points);
  m.normal = Vec3(0, 1, 0);
  for (int k = 0; k < points; ++k) {
    m.points[k].anchor_a = Vec3(tag, Real(k), 0);
    m.points[k].separation = -tag;
    m.points[k].feature_id = uint32_t(k + 1);
    m.points[k].normal_impulse = tag + Real(k);
  }
  m.tangent_impulse[0] = tag;
  m.twist_impulse = -tag;
  return m;
}

PairCache cache_of(uint32_t a, uint32_t b, Real tag) {
  PairCache c;
  c.key = make_pair_key(a, b);
  c.relative_position = Vec3(tag, 0, 0);
  c.exact_position = Vec3(0, tag, 0);
  return c;
}

std::vector<uint64_t> keys_of(std::span<const ManifoldHead> heads) {
  std::vector<uint64_t> keys;
  for (const ManifoldHead& h : heads) keys.push_back(h.key());
  return keys;
}

bool same_bits(const Manifold& x, const Manifold& y) {
  if (x.body_a != y.body_a || x.body_b != y.body_b || x.point_count != y.point_count) return false;
  bool same = std::memcmp(x.normal.data(), y.normal.data(), sizeof(Vec3)) == 0 &&
              std::memcmp(x.tangent_impulse, y.tangent_impulse, sizeof(x.tangent_impulse)) == 0 &&
              std::memcmp(&x.twist_impulse, &y.twist_impulse, sizeof(Real)) == 0;
  for (uint32_t k = 0; k < x.point_count; ++k) {
    const ContactPoint &p = x.points[k], &q = y.points[k];
    same = same && std::memcmp(p.anchor_a.data(), q.anchor_a.data(), sizeof(Vec3)) == 0 &&
           std::memcmp(&p.separation, &q.separation, sizeof(Real)) == 0 &&
           p.feature_id == q.feature_id &&
           std::memcmp(&p.normal_impulse, &q.normal_impulse, sizeof(Real)) == 0;
  }
  return same;
}

bool same_bits(const PairCache& x, const PairCache& y) {
  return x.key == y.key &&
         std::memcmp(x.relative_position.data(), y.relative_position.data(), sizeof(Vec3)) == 0 &&
         std::memcmp(x.exact_position.data(), y.exact_position.data(), sizeof(Vec3)) == 0 &&
         std::memcmp(x.exact_rotation.bytes, y.exact_rotation.bytes, 7) == 0;
}

// One step by hand: each pair of `pairs` (sorted) either touches (its manifold is `touching`'s
// entry of the same key, with a new tag) or is found apart; two pairs a block.
void step(ContactStore& store, const std::vector<uint64_t>& pairs,
          const std::vector<Manifold>& touching) {
  constexpr std::size_t kGrain = 2;
  const std::size_t parts = std::max<std::size_t>((pairs.size() + kGrain - 1) / kGrain, 1);
  store.begin_step(pairs, kGrain, parts, nullptr);
  for (std::size_t part = 0; part < parts; ++part) {
    ContactStore::Block block(store, part, {});
    for (std::size_t i = part * kGrain; i < std::min(pairs.size(), (part + 1) * kGrain); ++i) {
      const uint64_t key = pairs[i];
      const ContactStore::Touching last = block.look_up(key);
      const ContactStore::Apart apart = block.look_up_apart(key);
      const Manifold* m = nullptr;
      for (const Manifold& t : touching) m = t.key() == key ? &t : m;
      if (m == nullptr) {
        block.let_go(last);
        block.file_apart(key, nullptr, apart);
        continue;
      }
      const PairCache c = cache_of(m->body_a, m->body_b, 9);
      block.file_cache(m->point_count > 1 ? &c : nullptr, last, apart);
      block.file_manifold(*m, last);
    }
    block.close();
  }
  store.finish_step();
}

TEST(ContactStore, MergeRewritesAddsAndEndsInKeyOrder) {
  ContactStore store;
  store.restore(
      std::vector<Manifold>{manifold(1, 2, 1, 1), manifold(1, 5, 2, 2), manifold(3, 4, 1, 3),
                            manifold(4, 9, 3, 4), manifold(6, 7, 1, 5)},
      std::vector<PairCache>{cache_of(1, 5, 2), cache_of(4, 9, 4)});
  // (1,2) touches again with two points; (1,3) begins; (3,4) is found apart; (4,9) touches with
  // one point (its tail and poses end); (1,5) and (6,7) have no pair: they end.
  const std::vector<uint64_t> pairs = {make_pair_key(1, 2), make_pair_key(1, 3),
                                       make_pair_key(3, 4), make_pair_key(4, 8),
                                       make_pair_key(4, 9)};
  const std::vector<Manifold> touching = {manifold(1, 2, 2, 10), manifold(3, 1, 4, 11),
                                          manifold(9, 4, 1, 12)};
  step(store, pairs, touching);

  EXPECT_EQ(keys_of(store.heads()),
            (std::vector<uint64_t>{make_pair_key(1, 2), make_pair_key(1, 3), make_pair_key(4, 9)}));
  const std::vector<Manifold> now = store.manifolds();
  ASSERT_EQ(now.size(), 3u);
  EXPECT_TRUE(same_bits(now[0], touching[0]));
  EXPECT_TRUE(same_bits(now[1], touching[1]));
  EXPECT_TRUE(same_bits(now[2], touching[2]));
  ASSERT_EQ(store.tails().size(), 2u);
  EXPECT_EQ(store.tails()[0].key, make_pair_key(1, 2));
  EXPECT_EQ(store.tails()[1].key, make_pair_key(1, 3));
  ASSERT_EQ(store.pair_cache().size(), 2u) << "the poses of the manifolds with more than one point";
  EXPECT_EQ(store.pair_cache()[0].key, make_pair_key(1, 2));
  EXPECT_EQ(store.pair_cache()[1].key, make_pair_key(1, 3));

  EXPECT_EQ(std::vector<uint64_t>(store.began().begin(), store.began().end()),
            std::vector<uint64_t>{make_pair_key(1, 3)});
  ASSERT_EQ(store.ended().size(), 3u);
  EXPECT_EQ(store.ended()[0].key(), make_pair_key(1, 5));
  EXPECT_EQ(store.ended()[1].key(), make_pair_key(3, 4));
  EXPECT_EQ(store.ended()[2].key(), make_pair_key(6, 7));
  const ApartCandidates apart = store.continuous_candidates();
  EXPECT_TRUE(apart.separated.empty());
  EXPECT_EQ(std::vector<uint64_t>(apart.keys.begin(), apart.keys.end()),
            (std::vector<uint64_t>{make_pair_key(3, 4), make_pair_key(4, 8)}));

  // The next step: (3,4) touches again (its apart key ends), the rest apart.
  step(store, pairs, {manifold(3, 4, 1, 20)});
  EXPECT_EQ(keys_of(store.heads()), std::vector<uint64_t>{make_pair_key(3, 4)});
  EXPECT_EQ(std::vector<uint64_t>(store.began().begin(), store.began().end()),
            std::vector<uint64_t>{make_pair_key(3, 4)});
  EXPECT_EQ(store.ended().size(), 3u);
  EXPECT_TRUE(store.tails().empty());
  EXPECT_TRUE(store.pair_cache().empty());
  const ApartCandidates apart2 = store.continuous_candidates();
  EXPECT_EQ(std::vector<uint64_t>(apart2.keys.begin(), apart2.keys.end()),
            (std::vector<uint64_t>{make_pair_key(1, 2), make_pair_key(1, 3), make_pair_key(4, 8),
                                   make_pair_key(4, 9)}));
}

// Body 1 of 0..5 is destroyed and body 5 takes its index: 1's manifolds go (each reported), 5's
// are renamed to 1 with A and B kept as they were, and every list is in key order again.
TEST(ContactStore, RemoveBodyDropsItsManifoldsAndRenamesTheLastBody) {
  ContactStore store;
  const std::vector<Manifold> before = {manifold(1, 0, 1, 1), manifold(5, 0, 2, 2),
                                        manifold(2, 1, 3, 3), manifold(3, 4, 2, 4),
                                        manifold(2, 5, 1, 5)};
  std::vector<Manifold> sorted = before;
  std::sort(sorted.begin(), sorted.end(),
            [](const Manifold& x, const Manifold& y) { return x.key() < y.key(); });
  store.restore(sorted,
                std::vector<PairCache>{cache_of(0, 5, 2), cache_of(1, 2, 3), cache_of(3, 4, 4)}, {},
                std::vector<uint64_t>{make_pair_key(0, 3)});
  std::vector<uint64_t> dropped;
  store.remove_body(1, 5, [&](const ManifoldHead& h) { dropped.push_back(h.key()); });
  EXPECT_EQ(dropped, (std::vector<uint64_t>{make_pair_key(0, 1), make_pair_key(1, 2)}));
  const std::vector<Manifold> now = store.manifolds();
  ASSERT_EQ(now.size(), 3u);
  EXPECT_EQ(now[0].key(), make_pair_key(0, 1));
  EXPECT_EQ(now[0].body_a, 1u) << "5 was A: its new index is A";
  EXPECT_EQ(now[0].body_b, 0u);
  EXPECT_EQ(now[0].point_count, 2u);
  EXPECT_EQ(now[0].points[1].normal_impulse, Real(3)) << "its tail went with it";
  EXPECT_EQ(now[1].key(), make_pair_key(1, 2));
  EXPECT_EQ(now[1].body_a, 2u);
  EXPECT_EQ(now[1].body_b, 1u);
  EXPECT_EQ(now[1].points[0].separation, Real(-5));
  EXPECT_EQ(now[2].key(), make_pair_key(3, 4));
  ASSERT_EQ(store.tails().size(), 2u);
  EXPECT_EQ(store.tails()[0].key, make_pair_key(0, 1));
  EXPECT_EQ(store.tails()[1].key, make_pair_key(3, 4));
  ASSERT_EQ(store.pair_cache().size(), 2u);
  EXPECT_EQ(store.pair_cache()[0].key, make_pair_key(0, 1));
  EXPECT_EQ(store.pair_cache()[0].relative_position.x(), Real(2)) << "(0,5)'s poses, renamed";
  EXPECT_EQ(store.pair_cache()[1].key, make_pair_key(3, 4));
  EXPECT_TRUE(store.continuous_candidates().keys.empty()) << "the separation cache starts over";
}

// What for_each_manifold gives back rebuilds the same store, whole (restore) or one manifold at a
// time (begin_restore, restore_manifold), bit for bit.
TEST(ContactStore, SaveAndRestoreRoundTrip) {
  ContactStore store;
  store.restore(std::vector<Manifold>{manifold(0, 1, 4, 1), manifold(0, 2, 1, 2),
                                      manifold(3, 1, 2, 3), manifold(2, 7, 3, 4)},
                std::vector<PairCache>{cache_of(0, 1, 1), cache_of(2, 7, 4)});
  std::vector<Manifold> saved;
  std::vector<PairCache> saved_cache;
  std::vector<bool> has_cache;
  store.for_each_manifold([&](const Manifold& m, const PairCache* c) {
    saved.push_back(m);
    has_cache.push_back(c != nullptr);
    if (c != nullptr) saved_cache.push_back(*c);
  });
  EXPECT_EQ(has_cache, (std::vector<bool>{true, false, false, true}));

  ContactStore whole;
  whole.restore(saved, saved_cache);
  ContactStore one_by_one;
  one_by_one.begin_restore(saved.size());
  std::size_t c = 0;
  for (std::size_t k = 0; k < saved.size(); ++k) {
    one_by_one.restore_manifold(k, saved[k], has_cache[k] ? &saved_cache[c++] : nullptr);
  }
  for (const ContactStore* s : {&whole, &one_by_one}) {
    const std::vector<Manifold> back = s->manifolds();
    ASSERT_EQ(back.size(), saved.size());
    for (std::size_t k = 0; k < back.size(); ++k) EXPECT_TRUE(same_bits(back[k], saved[k])) << k;
    ASSERT_EQ(s->pair_cache().size(), saved_cache.size());
    for (std::size_t k = 0; k < saved_cache.size(); ++k) {
      EXPECT_TRUE(same_bits(s->pair_cache()[k], saved_cache[k])) << k;
    }
    EXPECT_EQ(s->tails().size(), store.tails().size());
  }
}

}  // namespace narrowphase_contact_store_test
}  // namespace elan::detail
