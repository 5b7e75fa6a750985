// SPDX-License-Identifier: MIT
// The shape types' names: the scene format's (spec/interface.md), one per type, both ways.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "elan/defs.hpp"

namespace elan::detail {
namespace shape_type_name_test {

TEST(ShapeTypeName, EveryTypeHasTheSceneFormatsNameAndBack) {
  const std::pair<ShapeType, const char*> spec[] = {{ShapeType::Sphere, "sphere"},
                                                    {ShapeType::Box, "box"},
                                                    {ShapeType::Capsule, "capsule"},
                                                    {ShapeType::Cylinder, "cylinder"},
                                                    {ShapeType::ConvexHull, "convex_hull"},
                                                    {ShapeType::Plane, "plane"},
                                                    {ShapeType::Mesh, "mesh"},
                                                    {ShapeType::Heightfield, "heightfield"},
                                                    {ShapeType::Compound, "compound"}};
  std::set<std::string> names;
  for (const auto& [type, name] : spec) {
    EXPECT_STREQ(shape_type_name(type), name);
    ASSERT_TRUE(shape_type_from_name(name).has_value()) << name;
    EXPECT_EQ(*shape_type_from_name(name), type) << name;
    names.insert(name);
  }
  EXPECT_EQ(names.size(), std::size(spec));
}

TEST(ShapeTypeName, OtherTextNamesNoType) {
  for (const char* text : {"", "Sphere", "convex hull", "hull", "sphere ", "compounds"}) {
    EXPECT_FALSE(shape_type_from_name(text).has_value()) << '"' << text << '"';
  }
  EXPECT_STREQ(shape_type_name(ShapeType(200)), "unknown");
}

}  // namespace shape_type_name_test
}  // namespace elan::detail
