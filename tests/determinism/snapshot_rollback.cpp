// SPDX-License-Identifier: MIT
// Compact rollback states: save at step k, run on, roll back, run again: the same hashes every
// step; the state's size per body is what the format says; another world's state is refused.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/world/world_access.hpp"
#include "determinism/snapshot_scene.hpp"
#include "elan/snapshot.hpp"

namespace elan {
namespace snapshot_rollback_test {

constexpr int kSaveAt = 100;
constexpr int kEnd = 130;

std::vector<uint64_t> run_to_end(World& world) {
  std::vector<uint64_t> hashes;
  for (int s = kSaveAt; s < kEnd; ++s) {
    world.step(test::kSnapshotDt);
    hashes.push_back(world.state_hash());
  }
  return hashes;
}

World& world_at_save() {
  static World world = [] {
    World w = test::make_snapshot_world(2);
    for (int s = 0; s < kSaveAt; ++s) w.step(test::kSnapshotDt);
    return w;
  }();
  return world;
}

TEST(Rollback, RollingBackAndRunningAgainGivesTheSameHashes) {
  World& world = world_at_save();
  const std::vector<uint8_t> saved = save_rollback(world);
  const uint64_t hash_at_save = world.state_hash();
  const std::vector<uint64_t> first = run_to_end(world);
  for (int threads : {1, 2}) {
    SCOPED_TRACE(threads);
    world.set_threads(threads);
    restore_rollback(world, saved);
    EXPECT_EQ(world.state_hash(), hash_at_save);
    EXPECT_EQ(detail::state_of(world).step_count, uint64_t(kSaveAt));
    EXPECT_EQ(run_to_end(world), first);
  }
  restore_rollback(world, saved);
}

TEST(Rollback, SizeIsEightyOneBytesPerMovingBodyPlusContacts) {
  const World& world = world_at_save();
  const std::vector<uint8_t> saved = save_rollback(world);
  const detail::WorldState& s = detail::state_of(world);
  std::size_t moving = 0;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) moving += !s.bodies.is_static(i);
  std::size_t contact_bytes = 4;
  for (const detail::ManifoldHead& m : s.contacts.heads()) {
    contact_bytes += 8 + 1 + 6 * sizeof(Real) + 1 + m.point_count * (5 * sizeof(Real) + 4) + 1;
  }
  // The pair cache's rotations and offsets, for the manifolds that have them.
  contact_bytes += s.contacts.pair_cache().size() * (14 * sizeof(Real) + 7);
  ASSERT_GT(s.contacts.pair_cache().size(), 0u);
  const std::size_t per_body = 20 * sizeof(Real) + 1;
  // The joint section: counts of joints, slots and free slots, none of them here.
  ASSERT_TRUE(s.joints.empty());
  const std::size_t joint_bytes = 12;
  // The sensor overlaps: a count, none here.
  ASSERT_TRUE(s.api.sensor_overlaps.empty());
  const std::size_t sensor_bytes = 4;
  // Header 16, body count 4, fingerprint 8, step count 8, checksum 8.
  EXPECT_EQ(saved.size(), 44 + moving * per_body + contact_bytes + joint_bytes + sensor_bytes);
  if constexpr (sizeof(Real) == 4) {
    EXPECT_LE(per_body, 128u);
  }
}

TEST(Rollback, SavingIntoAWarmBufferKeepsItsStorage) {
  const World& world = world_at_save();
  std::vector<uint8_t> buffer;
  save_rollback(world, buffer);
  const uint8_t* storage = buffer.data();
  save_rollback(world, buffer);
  EXPECT_EQ(buffer.data(), storage);
  EXPECT_EQ(buffer, save_rollback(world));
}

TEST(Rollback, AnotherWorldsStateIsRefusedAndNothingChanges) {
  World& world = world_at_save();
  World other = test::make_snapshot_world(1);
  BodyDef extra;
  extra.shape = ShapeId{0};
  extra.position = Vec3(0, 30, 0);
  other.create_body(extra);
  const uint64_t before = world.state_hash();
  try {
    restore_rollback(world, save_rollback(other));
    FAIL() << "restored another world's state";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "rollback");
    EXPECT_NE(std::string(e.what()).find("different number of bodies"), std::string::npos);
  }
  EXPECT_EQ(world.state_hash(), before);
}

TEST(Rollback, CorruptOrTruncatedStateIsRefusedAndNothingChanges) {
  World& world = world_at_save();
  const std::vector<uint8_t> saved = save_rollback(world);
  const uint64_t before = world.state_hash();
  const std::size_t contacts = detail::state_of(world).contacts.size();
  for (std::size_t at : {std::size_t(0), std::size_t(9), saved.size() / 2, saved.size() - 1}) {
    std::vector<uint8_t> bad = saved;
    bad[at] ^= 0x10;
    EXPECT_THROW(restore_rollback(world, bad), Error) << "flipped byte " << at;
  }
  for (std::size_t n : {std::size_t(0), std::size_t(20), saved.size() - 1}) {
    EXPECT_THROW(restore_rollback(world, std::span(saved).first(n)), Error) << "length " << n;
  }
  EXPECT_EQ(world.state_hash(), before);
  EXPECT_EQ(detail::state_of(world).contacts.size(), contacts);
}

}  // namespace snapshot_rollback_test
}  // namespace elan
