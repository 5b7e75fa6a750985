// SPDX-License-Identifier: MIT
// Loads and stores of a bundle's bodies: each lane gets exactly its body's values, and a store
// touches only v and w of the lanes whose packet is written. The substep integration's loads and
// stores of consecutive packets: all sixteen floats of each, and only the first `count`. With
// AVX-512 these run as a transpose of whole rows, which must move the same bits as the lane-by-lane
// loop.
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
    b.v = Vec3{u(rng), u(rng), u(rng)};
    b.w = Vec3{u(rng), u(rng), u(rng)};
    b.dp = Vec3{u(rng), u(rng), u(rng)};
    b.dtheta = Vec3{u(rng), u(rng), u(rng)};
    b.dq = Quat{u(rng), u(rng), u(rng), u(rng)};
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

TEST(BodyLanes, WrittenPacketsAreTheAwakeDynamicOnes) {
  EXPECT_FALSE(written_packet(0, 10));  // the static dummy
  EXPECT_TRUE(written_packet(1, 10));
  EXPECT_TRUE(written_packet(9, 10));
  EXPECT_FALSE(written_packet(10, 10));  // the first kinematic packet
  EXPECT_FALSE(written_packet(0, 1));    // no awake dynamic body
  EXPECT_FALSE(written_packet(1, 1));
}

// A store writes v and w of the lanes whose packet is below written_end, except the static dummy
// (packet 0), and nothing else of any packet.
TEST(BodyLanes, ScatterWritesOnlyTheWrittenPacketsVelocities) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 50; ++trial) {
    const std::vector<SolverBody> before = random_bodies(64, rng);
    std::vector<SolverBody> after = before;
    const uint32_t written_end = 20 + uint32_t(rng() % 24);
    // Written lanes hold distinct dynamic packets, as within a colour; read-only lanes may
    // repeat the static dummy or a kinematic packet (at or past written_end).
    std::vector<uint32_t> dynamic(written_end - 1);
    std::iota(dynamic.begin(), dynamic.end(), 1u);
    std::shuffle(dynamic.begin(), dynamic.end(), rng);
    uint32_t packets[kLanes];
    bool write[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      const uint32_t kind = rng() % 3;
      write[l] = kind != 0;
      const uint32_t kinematic = written_end + uint32_t(rng() % (before.size() - written_end));
      packets[l] = write[l] ? dynamic[std::size_t(l)] : (rng() % 2 == 0 ? 0 : kinematic);
    }
    WideBody in;
    std::uniform_real_distribution<float> u(-5, 5);
    for (int l = 0; l < kLanes; ++l) {
      set_lane(in.v, l, Vec3{u(rng), u(rng), u(rng)});
      set_lane(in.w, l, Vec3{u(rng), u(rng), u(rng)});
    }
    scatter_velocity(after.data(), packets, written_end, in);
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

// gather_packets: lane l holds every float of packet first + l, and lanes past `count` repeat the
// last packet (never one past the range).
TEST(BodyLanes, ConsecutivePacketsGatherWholeAndRepeatTheLast) {
  std::mt19937 rng(13);
  const std::vector<SolverBody> bodies = random_bodies(3 * kLanes, rng);
  for (int count = 1; count <= kLanes; ++count) {
    const std::size_t first = rng() % (bodies.size() - std::size_t(count) + 1);
    Wide cols[16];
    gather_packets(bodies.data() + first, count, cols);
    for (int l = 0; l < kLanes; ++l) {
      const Real* expected = floats_of(bodies[first + std::size_t(std::min(l, count - 1))]);
      for (int j = 0; j < 16; ++j) {
        // A copy of the lane: clang takes no address of a vector element.
        const Real lane = cols[j][l];
        ASSERT_EQ(std::memcmp(&lane, &expected[j], sizeof(Real)), 0)
            << "count " << count << ", lane " << l << ", float " << j;
      }
    }
  }
}

// gather_rows: lane l holds the sixteen floats at row[l], wherever the rows are and in whatever
// order (prepare_bundle's manifold heads are scattered over the contact list); two lanes may
// share a row.
TEST(BodyLanes, RowsGatherFromAnyAddresses) {
  std::mt19937 rng(19);
  const std::vector<SolverBody> bodies = random_bodies(4 * kLanes, rng);
  for (int trial = 0; trial < 20; ++trial) {
    const Real* row[kLanes];
    std::size_t picked[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      picked[l] = rng() % bodies.size();
      row[l] = floats_of(bodies[picked[l]]);
    }
    Wide cols[16];
    gather_rows(row, cols);
    for (int l = 0; l < kLanes; ++l) {
      for (int j = 0; j < 16; ++j) {
        const Real lane = cols[j][l];
        ASSERT_EQ(std::memcmp(&lane, &floats_of(bodies[picked[l]])[j], sizeof(Real)), 0)
            << "trial " << trial << ", lane " << l << ", float " << j;
      }
    }
  }
}

// scatter_packets writes all sixteen floats of the first `count` packets and nothing else.
TEST(BodyLanes, ConsecutivePacketsScatterOnlyTheirCount) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-5, 5);
  for (int count = 1; count <= kLanes; ++count) {
    const std::vector<SolverBody> before = random_bodies(3 * kLanes, rng);
    std::vector<SolverBody> after = before;
    const std::size_t first = rng() % (before.size() - std::size_t(count) + 1);
    Wide cols[16];
    for (Wide& c : cols) {
      for (int l = 0; l < kLanes; ++l) c[l] = u(rng);
    }
    scatter_packets(after.data() + first, count, cols);
    for (std::size_t i = 0; i < before.size(); ++i) {
      const bool stored = i >= first && i < first + std::size_t(count);
      for (int j = 0; j < 16; ++j) {
        const Real expected = stored ? cols[j][int(i - first)] : floats_of(before[i])[j];
        ASSERT_EQ(std::memcmp(&floats_of(after[i])[j], &expected, sizeof(Real)), 0)
            << "count " << count << ", packet " << i << ", float " << j;
      }
    }
  }
}

}  // namespace solver_body_lanes_test
}  // namespace elan::detail
