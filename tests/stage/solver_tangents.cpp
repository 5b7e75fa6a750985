// SPDX-License-Identifier: MIT
// The contact passes' friction axes: tangents_of() across the lanes must give, bit for bit, the
// basis tangent_basis() gives each lane's normal, since a manifold's friction impulses are stored
// and carried (carry_tangent_impulse) in that scalar basis.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "solver/contact_solver.hpp"

namespace elan::detail {
namespace solver_tangents_test {

bool same_bits(const Vec3& a, const Vec3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(Vec3)) == 0;
}

TEST(SolverTangents, EachLaneIsTheScalarBasisOfItsNormal) {
  std::mt19937 rng(21);
  std::normal_distribution<float> g(0, 1);
  for (int trial = 0; trial < 500; ++trial) {
    WideVec3 normals;
    Vec3 n[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      n[l] = Vec3{g(rng), g(rng), g(rng)};
      if (l % 4 == 1) n[l].z() = Real(1e-7) * g(rng);         // beside the sign switch
      if (l % 4 == 2) n[l] = Vec3(0, trial % 2 ? 1 : -1, 0);  // a floor or a ceiling
      n[l].normalize();
      set_lane(normals, l, n[l]);
    }
    const WideTangents t = tangents_of(normals);
    for (int l = 0; l < kLanes; ++l) {
      Vec3 t1, t2;
      tangent_basis(n[l], t1, t2);
      ASSERT_TRUE(same_bits(lane(t.t0, l), t1)) << "trial " << trial << ", lane " << l;
      ASSERT_TRUE(same_bits(lane(t.t1, l), t2)) << "trial " << trial << ", lane " << l;
    }
  }
}

// Unused lanes have a zero normal: their axes must be finite, as the old basis's zero axes were,
// since the passes' any_lane tests read every lane.
TEST(SolverTangents, ZeroNormalGivesFiniteAxes) {
  const WideTangents t = tangents_of(WideVec3{});
  for (int l = 0; l < kLanes; ++l) {
    EXPECT_TRUE(lane(t.t0, l).allFinite());
    EXPECT_TRUE(lane(t.t1, l).allFinite());
  }
}

}  // namespace solver_tangents_test
}  // namespace elan::detail
