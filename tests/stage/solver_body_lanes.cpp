// Loads and stores of a bundle's bodies: each lane gets exactly its body's values, and a store
// touches only v and w of the lanes flagged for writing. With AVX-512 these run as a transpose
// of whole rows, which must move the same bits as the lane-by-lane loop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

#include "solver/body_lanes.hpp"

namespace elan::detail {
namespace solver_body_lanes_test {

std::vector<SolverBody> random_bodies(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-100, 100);
  std::vector<SolverBody> bodies(n);
  for (SolverBody& b : bodies) {
    b.v = Vec3(u(rng), u(rng), u(rng));
    b.w = Vec3(u(rng), u(rng), u(rng));
    b.dp = Vec3(u(rng), u(rng), u(rng));
    b.dtheta = Vec3(u(rng), u(rng), u(rng));
    b.dq = Quat(u(rng), u(rng), u(rng), u(rng));
  }
  return bodies;
}

bool same_bits(const Vec3& a, const Vec3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(Vec3)) == 0;
}

TEST(BodyLanes, EachLaneGathersItsOwnBody) {
  std::mt19937 rng(5);
  const std::vector<SolverBody> bodies = random_bodies(200, rng);
  for (int trial = 0; trial < 50; ++trial) {
    uint32_t packets[kLanes];
    for (uint32_t& p : packets) p = uint32_t(rng() % bodies.size());
    WideBody velocity;
    WideVec3 dp, dtheta;
    gather_velocity(bodies.data(), packets, velocity);
    gather_pose(bodies.data(), packets, dp, dtheta);
    for (int l = 0; l < kLanes; ++l) {
      const SolverBody& b = bodies[packets[l]];
      ASSERT_TRUE(same_bits(lane(velocity.v, l), b.v)) << "lane " << l;
      ASSERT_TRUE(same_bits(lane(velocity.w, l), b.w)) << "lane " << l;
      ASSERT_TRUE(same_bits(lane(dp, l), b.dp)) << "lane " << l;
      ASSERT_TRUE(same_bits(lane(dtheta, l), b.dtheta)) << "lane " << l;
    }
  }
}

TEST(BodyLanes, ScatterWritesOnlyTheFlaggedLanesVelocities) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 50; ++trial) {
    const std::vector<SolverBody> before = random_bodies(64, rng);
    std::vector<SolverBody> after = before;
    // Written lanes hold distinct bodies, as within a colour; read-only lanes may repeat any
    // body, written or not, as the static dummy does.
    std::vector<uint32_t> order(before.size());
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), rng);
    uint32_t packets[kLanes];
    uint8_t write[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      write[l] = uint8_t(rng() % 3 != 0);
      packets[l] = write[l] ? order[std::size_t(l)] : order[rng() % order.size()];
    }
    for (int l = 0; l < kLanes; ++l) {
      if (write[l]) continue;
      for (int k = 0; k < kLanes; ++k) {
        if (write[k] && packets[k] == packets[l]) packets[l] = order[kLanes + std::size_t(l)];
      }
    }
    WideBody in;
    std::uniform_real_distribution<float> u(-5, 5);
    for (int l = 0; l < kLanes; ++l) {
      set_lane(in.v, l, Vec3(u(rng), u(rng), u(rng)));
      set_lane(in.w, l, Vec3(u(rng), u(rng), u(rng)));
    }
    scatter_velocity(after.data(), packets, write, in);
    std::vector<SolverBody> expected = before;
    for (int l = 0; l < kLanes; ++l) {
      if (!write[l]) continue;
      expected[packets[l]].v = lane(in.v, l);
      expected[packets[l]].w = lane(in.w, l);
    }
    for (std::size_t i = 0; i < before.size(); ++i) {
      ASSERT_EQ(std::memcmp(&after[i], &expected[i], sizeof(SolverBody)), 0)
          << "trial " << trial << ", body " << i;
    }
  }
}

}  // namespace solver_body_lanes_test
}  // namespace elan::detail
