// SPDX-License-Identifier: MIT
// The table of body traits: bodies made in runs share one entry, an entry no body uses is reused,
// values are compared bit for bit, and a snapshot's table is refused when it disagrees with the
// bodies' entries.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/base/body_store.hpp"

namespace elan::detail {
namespace body_traits_test {

BodyTraits with_friction(Real f) {
  BodyTraits t;
  t.friction = f;
  t.category = 1;
  t.mask = ~0u;
  return t;
}

TEST(TraitTable, BodiesMadeInRunsOrInTurnShareEntries) {
  BodyStore store;
  // A store's bodies start with zero traits and then get their own, one after another: a pile.
  for (int i = 0; i < 1000; ++i) store.set_traits(store.push_back(), with_friction(Real(0.5)));
  // Then five materials in turn.
  for (int i = 0; i < 1000; ++i) {
    store.set_traits(store.push_back(), with_friction(Real(0.1) * Real(i % 5)));
  }
  // The zero traits (free now), 0.5, and the five (0 among them, distinct from zero traits by the
  // filter bits).
  EXPECT_LE(store.trait_table.entries().size(), 7u);
  for (std::size_t i = 0; i < store.size(); ++i) {
    const Real expected = i < 1000 ? Real(0.5) : Real(0.1) * Real((i - 1000) % 5);
    ASSERT_EQ(store.traits_of(i).friction, expected) << "body " << i;
  }
}

TEST(TraitTable, ChangingOneBodyLeavesTheOthersAndTheTableDoesNotGrow) {
  BodyStore store;
  for (int i = 0; i < 10; ++i) store.set_traits(store.push_back(), with_friction(Real(0.5)));
  const std::size_t entries = store.trait_table.entries().size();
  for (int k = 0; k < 1000; ++k) store.set_traits(3, with_friction(Real(k)));
  EXPECT_EQ(store.traits_of(3).friction, Real(999));
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (i != 3) {
      EXPECT_EQ(store.traits_of(i).friction, Real(0.5));
    }
  }
  // The changed body's old entry is freed and reused at each change.
  EXPECT_LE(store.trait_table.entries().size(), entries + 1);
  // Removing bodies gives their entries back: a new body then reuses one.
  while (store.size() > 0) store.swap_remove(store.size() - 1);
  EXPECT_EQ(store.trait_table.free_entries().size(), store.trait_table.entries().size());
  EXPECT_FALSE(store.trait_table.any_restitution());
}

TEST(TraitTable, ValuesAreComparedBitForBit) {
  BodyStore store;
  store.set_traits(store.push_back(), with_friction(Real(0)));
  store.set_traits(store.push_back(), with_friction(-Real(0)));
  EXPECT_NE(store.traits[0], store.traits[1]);
  EXPECT_TRUE(std::signbit(store.traits_of(1).friction));
  EXPECT_FALSE(std::signbit(store.traits_of(0).friction));
  BodyTraits bouncy = with_friction(Real(0.5));
  bouncy.restitution = Real(0.25);
  store.set_traits(1, bouncy);
  EXPECT_TRUE(store.trait_table.any_restitution());
  store.set_traits(1, with_friction(Real(0.5)));
  EXPECT_FALSE(store.trait_table.any_restitution()) << "only entries in use count";
}

TEST(TraitTable, RestoreRefusesATableTheBodiesDisagreeWith) {
  const std::vector<BodyTraits> two = {with_friction(1), with_friction(2)};
  TraitTable table;
  EXPECT_TRUE(table.restore(two, {}, std::vector<uint32_t>{0, 1, 1}));
  EXPECT_EQ(table[1].friction, Real(2));
  EXPECT_TRUE(table.restore(two, {0}, std::vector<uint32_t>{1, 1}));
  EXPECT_FALSE(table.restore(two, {}, std::vector<uint32_t>{0, 2})) << "an entry past the table";
  EXPECT_FALSE(table.restore(two, {}, std::vector<uint32_t>{1})) << "an unused entry not free";
  EXPECT_FALSE(table.restore(two, {0}, std::vector<uint32_t>{0, 1})) << "a used entry listed free";
  EXPECT_FALSE(table.restore(two, {0, 0}, std::vector<uint32_t>{1})) << "listed twice";
  EXPECT_TRUE(table.entries().empty()) << "left empty when refused";
}

}  // namespace body_traits_test
}  // namespace elan::detail
