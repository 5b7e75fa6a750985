// SPDX-License-Identifier: MIT
// Ids key unordered containers: std::hash of BodyId and ShapeId, consistent with ==.
#include <gtest/gtest.h>

#include <unordered_map>
#include <unordered_set>

#include "elan/ids.hpp"

namespace elan {
namespace ids_hash_test {

TEST(IdHash, BodyIdsKeyAnUnorderedMap) {
  std::unordered_map<BodyId, int> names;
  for (uint32_t slot = 0; slot < 100; ++slot) {
    names[BodyId{slot, 0}] = int(slot);
    names[BodyId{slot, 1}] = int(slot) + 1000;  // the same slot reused: another body
  }
  EXPECT_EQ(names.size(), 200u);
  EXPECT_EQ(names.at(BodyId{7, 0}), 7);
  EXPECT_EQ(names.at(BodyId{7, 1}), 1007);
  EXPECT_EQ(names.count(BodyId{7, 2}), 0u);
  EXPECT_EQ(names.count(BodyId{}), 0u);
}

TEST(IdHash, ShapeIdsKeyAnUnorderedSet) {
  std::unordered_set<ShapeId> shapes;
  for (uint32_t i = 0; i < 50; ++i) shapes.insert(ShapeId{i % 10});
  EXPECT_EQ(shapes.size(), 10u);
  EXPECT_TRUE(shapes.contains(ShapeId{3}));
  EXPECT_FALSE(shapes.contains(ShapeId{}));
}

TEST(IdHash, EqualIdsHashEqualAndGenerationsDiffer) {
  const std::hash<BodyId> h;
  EXPECT_EQ(h(BodyId{5, 2}), h(BodyId{5, 2}));
  EXPECT_NE(h(BodyId{5, 2}), h(BodyId{5, 3}));
  EXPECT_NE(h(BodyId{5, 2}), h(BodyId{2, 5}));
  EXPECT_EQ(std::hash<ShapeId>{}(ShapeId{4}), std::hash<ShapeId>{}(ShapeId{4}));
}

}  // namespace ids_hash_test
}  // namespace elan
