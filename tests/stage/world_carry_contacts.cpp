// carry_sleeping_contacts: last step's manifolds between bodies that are all asleep or static
// are merged back by key, in place; the ones found again, the ones with an awake body and the
// empty ones are not.
#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "core/base/pair_key.hpp"
#include "core/world/step.hpp"

namespace elan::detail {
namespace {

// Body 0 static; 1, 2, 3 dynamic asleep; 4 dynamic awake; 5 dynamic asleep but frozen.
BodyStore make_bodies() {
  BodyStore b;
  for (int i = 0; i < 6; ++i) {
    const std::size_t k = b.push_back();
    b.motion[k] = uint8_t(k == 0 ? MotionType::Static : MotionType::Dynamic);
    b.flags[k] = k == 4 ? kAwake : k == 5 ? kFrozen : 0;
  }
  return b;
}

// `tag` marks where a manifold came from (its first point's separation).
Manifold manifold(uint32_t a, uint32_t b, Real tag, int points = 1) {
  Manifold m;
  m.key = make_pair_key(a, b);
  m.body_a = std::max(a, b);
  m.body_b = std::min(a, b);
  m.point_count = points;
  m.points[0].separation = tag;
  return m;
}

TEST(CarrySleepingContacts, MergesTheIdleOnesInKeyOrderInPlace) {
  const BodyStore bodies = make_bodies();
  // Both lists in key order, as the step keeps them.
  std::vector<Manifold> previous = {
      manifold(0, 1, 1),     // idle, not found again: carried
      manifold(0, 2, 2),     // idle, found again: the new one stays
      manifold(0, 4, 3),     // body 4 awake: dropped
      manifold(1, 3, 4),     // idle pair of sleepers: carried
      manifold(2, 3, 5, 0),  // no points: dropped
      manifold(3, 5, 6),     // body 5 frozen: dropped
      manifold(4, 5, 7),     // awake: dropped
  };
  std::vector<Manifold> contacts = {manifold(0, 2, -2), manifold(0, 3, -3), manifold(2, 4, -4)};
  carry_sleeping_contacts(bodies, previous, contacts);

  const std::vector<std::pair<uint64_t, Real>> expected = {
      {make_pair_key(0, 1), 1}, {make_pair_key(0, 2), -2}, {make_pair_key(0, 3), -3},
      {make_pair_key(1, 3), 4}, {make_pair_key(2, 4), -4},
  };
  ASSERT_EQ(contacts.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(contacts[i].key, expected[i].first) << i;
    EXPECT_EQ(contacts[i].points[0].separation, expected[i].second) << i;
  }
}

TEST(CarrySleepingContacts, CarriedBeforeAndAfterAllNewOnes) {
  // Carried keys below the first and above the last new key, and nothing new at all.
  const BodyStore bodies = make_bodies();
  std::vector<Manifold> previous = {manifold(0, 1, 1), manifold(2, 3, 2)};
  std::vector<Manifold> contacts = {manifold(1, 4, -1)};
  carry_sleeping_contacts(bodies, previous, contacts);
  ASSERT_EQ(contacts.size(), 3u);
  EXPECT_EQ(contacts[0].points[0].separation, 1);
  EXPECT_EQ(contacts[1].points[0].separation, -1);
  EXPECT_EQ(contacts[2].points[0].separation, 2);

  std::vector<Manifold> none;
  carry_sleeping_contacts(bodies, previous, none);
  ASSERT_EQ(none.size(), 2u);
  EXPECT_EQ(none[0].key, make_pair_key(0, 1));
  EXPECT_EQ(none[1].key, make_pair_key(2, 3));
}

}  // namespace
}  // namespace elan::detail
