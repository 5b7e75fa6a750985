// SPDX-License-Identifier: MIT
// Snapshot format: refused cleanly (elan::Error naming the problem, world unchanged) when not a
// snapshot, of another version or Real size, truncated at any length or corrupt at any byte; and
// tripwires that fail when a body column or contact field is added that snapshots do not save.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/body_store.hpp"
#include "core/world/byte_io.hpp"
#include "core/world/world_access.hpp"
#include "elan/snapshot.hpp"

namespace elan {
namespace snapshot_format_test {

// Two boxes and a hull on a plane after a few steps: small enough to try every truncation.
World small_world() {
  World world;
  ShapeDef plane;
  plane.type = ShapeType::Plane;
  BodyDef ground;
  ground.motion = MotionType::Static;
  ground.shape = world.create_shape(plane);
  world.create_body(ground);
  ShapeDef box;
  box.type = ShapeType::Box;
  box.half_extents = Vec3(Real(0.5), Real(0.3), Real(0.2));
  ShapeDef hull;
  hull.type = ShapeType::ConvexHull;
  hull.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)};
  const ShapeId ids[] = {world.create_shape(box), world.create_shape(hull)};
  for (int k = 0; k < 3; ++k) {
    BodyDef b;
    b.shape = ids[k % 2];
    b.position = Vec3(Real(0.3 * k), Real(0.4 + 1.1 * k), 0);
    world.create_body(b);
  }
  for (int s = 0; s < 40; ++s) world.step(Real(1.0 / 60.0));
  return world;
}

std::string error_of(World& world, const std::vector<uint8_t>& bytes) {
  try {
    restore_snapshot(world, bytes);
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "snapshot");
    return e.what();
  }
  return "";
}

void reseal(std::vector<uint8_t>& bytes) {
  ASSERT_GE(bytes.size(), 8u);
  bytes.erase(bytes.end() - 8, bytes.end());
  const uint64_t sum = detail::checksum_words(bytes);
  detail::ByteWriter(bytes).u64(sum);
}

TEST(SnapshotFormat, EveryTruncationIsRefusedAndTheWorldIsUnchanged) {
  World source = small_world();
  ASSERT_GT(detail::state_of(source).contacts.size(), 0u);
  const std::vector<uint8_t> bytes = save_snapshot(source);
  World target = small_world();
  target.step(Real(1.0 / 60.0));
  const uint64_t before = target.state_hash();
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const std::string message = error_of(target, {bytes.begin(), bytes.begin() + n});
    EXPECT_FALSE(message.empty()) << "length " << n;
  }
  EXPECT_EQ(target.state_hash(), before);
}

TEST(SnapshotFormat, EveryFlippedByteIsRefused) {
  const std::vector<uint8_t> bytes = save_snapshot(small_world());
  World target;
  for (std::size_t at = 0; at < bytes.size(); ++at) {
    std::vector<uint8_t> bad = bytes;
    bad[at] ^= 0x01;
    EXPECT_FALSE(error_of(target, bad).empty()) << "byte " << at;
  }
  EXPECT_EQ(target.body_count(), 0u);
}

TEST(SnapshotFormat, OtherVersionAndRealSizeAreRefusedByName) {
  const std::vector<uint8_t> bytes = save_snapshot(small_world());
  World target;
  std::vector<uint8_t> version = bytes;
  version[8] = uint8_t(kSnapshotVersion + 1);
  reseal(version);
  EXPECT_NE(
      error_of(target, version)
          .find("unsupported snapshot format version " + std::to_string(kSnapshotVersion + 1)),
      std::string::npos);
  std::vector<uint8_t> real = bytes;
  real[12] = uint8_t(sizeof(Real) == 4 ? 8 : 4);
  reseal(real);
  EXPECT_NE(error_of(target, real)
                .find(sizeof(Real) == 4 ? "saved with 64-bit Real" : "saved with 32-bit Real"),
            std::string::npos);
  const std::string text = "{\"bodies\": []}";
  EXPECT_NE(error_of(target, {text.begin(), text.end()}).find("not an elan snapshot"),
            std::string::npos);
}

// The joint section's bytes (it follows the contacts).
std::size_t joint_bytes(const detail::WorldState& s) {
  return 4 + s.joints.size() * (22 + 64 * sizeof(Real)) + 4 + 8 * s.joints.slot_index.size() + 4 +
         4 * s.joints.free_slots.size();
}

// Version 10's section after the joints: per body user data, density and given mass; the hit
// threshold; the sensor overlaps.
std::size_t api_bytes(const detail::WorldState& s) {
  return s.bodies.size() * (8 + 2 * sizeof(Real)) + sizeof(Real) + 4 +
         8 * s.api.sensor_overlaps.size();
}

// The snapshot's bytes after the body columns: the applied forces, contacts, id slots, joints
// and the checksum, counted back from the end.
std::size_t bytes_after_columns(const detail::WorldState& s) {
  constexpr std::size_t kR = sizeof(Real);
  const std::size_t forces = 4 + s.bodies.applied_forces.size() * (4 + 6 * kR);
  const std::size_t traits = 4 + s.bodies.trait_table.entries().size() * (5 * kR + 12) + 4 +
                             4 * s.bodies.trait_table.free_entries().size();
  // Per manifold: key and bodies, normal, point count, points, friction, whether it has cache
  // poses; then the poses of those that have them.
  const std::size_t contacts = 4 + s.contacts.size() * (16 + 6 * kR + 1 + 4 * (5 * kR + 4) + 1) +
                               s.contacts.pair_cache().size() * (14 * kR + 7);
  const std::size_t slots = 4 + 8 * s.slot_index.size() + 4 + 4 * s.free_slots.size();
  return forces + traits + contacts + slots + joint_bytes(s) + api_bytes(s) + 8;
}

// The error a fresh world gives for `bytes` with the byte at `at` (which must hold `was`) set to
// `value` and resealed.
std::string error_with_byte(std::vector<uint8_t> bytes, std::size_t at, uint32_t was,
                            uint8_t value) {
  EXPECT_EQ(bytes[at], was);
  bytes[at] = value;
  reseal(bytes);
  World target;
  return error_of(target, bytes);
}

TEST(SnapshotFormat, ResealedInconsistentContentsAreRefused) {
  // A body pointing at a shape that does not exist passes the checksum once resealed; the
  // reader must still refuse it. The shape column's offset is counted back from the end: the
  // bytes after the columns, then the columns after `shape` (traits, slot and applied: 4 bytes
  // each, motion and flags: 1 byte each).
  World world = small_world();
  const std::vector<uint8_t> bytes = save_snapshot(world);
  const detail::WorldState& s = detail::state_of(world);
  const std::size_t n = s.bodies.size();
  const std::size_t last_shape = bytes.size() - bytes_after_columns(s) - 14 * n - 4;
  const std::string error = error_with_byte(bytes, last_shape, s.bodies.shape[n - 1], 200);
  EXPECT_NE(error.find("body 3: bad shape index"), std::string::npos) << error;
}

TEST(SnapshotFormat, ResealedTraitsEntryPastTheTableIsRefused) {
  // The last body's `traits` entry (followed by the slot and applied columns, then motion and
  // flags) made to point past the table of traits.
  World world = small_world();
  const std::vector<uint8_t> bytes = save_snapshot(world);
  const detail::WorldState& s = detail::state_of(world);
  const std::size_t n = s.bodies.size();
  const std::size_t last_traits = bytes.size() - bytes_after_columns(s) - 10 * n - 4;
  const std::string error = error_with_byte(bytes, last_traits, s.bodies.traits[n - 1], 200);
  EXPECT_NE(error.find("body traits: a body's entry"), std::string::npos) << error;
}

TEST(SnapshotFormat, ResealedForceSlotWithoutItsForceIsRefused) {
  // The last body's `applied` slot (no force: all bits set) made to point at entry 0 of an empty
  // list of applied forces.
  World world = small_world();
  std::vector<uint8_t> bytes = save_snapshot(world);
  const detail::WorldState& s = detail::state_of(world);
  const std::size_t n = s.bodies.size();
  ASSERT_TRUE(s.bodies.applied_forces.empty());
  const std::size_t last_applied = bytes.size() - bytes_after_columns(s) - 2 * n - 4;
  for (std::size_t k = 0; k < 4; ++k) {
    ASSERT_EQ(bytes[last_applied + k], 0xFF);
    bytes[last_applied + k] = 0;
  }
  reseal(bytes);
  World target;
  EXPECT_NE(error_of(target, bytes).find("body 3: applied force slot does not point back at it"),
            std::string::npos)
      << error_of(target, bytes);
}

TEST(SnapshotFormat, ResealedBadPackedRotationIsRefused) {
  // The last manifold ends the contacts and, with its pair cache poses, its packed exact rotation
  // ends them: the byte before the joints says which component was left out, 0..3. Before the
  // poses, a byte says whether they follow.
  World world = small_world();
  const detail::WorldState& s = detail::state_of(world);
  ASSERT_GT(s.contacts.size(), 0u);
  ASSERT_FALSE(s.contacts.pair_cache().empty());
  ASSERT_EQ(s.contacts.pair_cache().back().key, s.contacts.heads().back().key())
      << "the last manifold has poses";
  const std::vector<uint8_t> saved = save_snapshot(world);
  std::vector<uint8_t> bytes = saved;
  const std::size_t tail = 8 + joint_bytes(s) + api_bytes(s);  // joints, API values, checksum
  uint8_t& dropped = bytes[bytes.size() - tail - 1];
  ASSERT_LE(dropped, 3);
  dropped = 4;
  reseal(bytes);
  World target;
  EXPECT_NE(error_of(target, bytes).find("manifold exact rotation is not a packed rotation"),
            std::string::npos)
      << error_of(target, bytes);
  bytes = saved;
  uint8_t& has_poses = bytes[bytes.size() - tail - (14 * sizeof(Real) + 7) - 1];
  ASSERT_EQ(has_poses, 1);
  has_poses = 2;
  reseal(bytes);
  EXPECT_NE(error_of(target, bytes).find("bad manifold pair cache flag"), std::string::npos)
      << error_of(target, bytes);
}

TEST(SnapshotFormat, SavesEveryColumnOfTheBodyStore) {
  // Tripwire: a column added to BodyStore must be added to for_each_column, the list that
  // snapshots (and push_back, swap_remove, reserve) walk.
  std::size_t columns = 0;
  detail::BodyStore probe;
  detail::for_each_column(probe, [&columns](auto&) { ++columns; });
  // The members that are not columns, saved on their own: the applied forces, the traits table.
  EXPECT_EQ(columns * sizeof(detail::Column<Real>) + sizeof(std::vector<detail::AppliedForce>) +
                sizeof(detail::TraitTable),
            sizeof(detail::BodyStore));
}

TEST(SnapshotFormat, SavesEveryFieldOfAManifold) {
  // Tripwire: a field added to ContactPoint, Manifold (and the list's ManifoldHead and
  // ManifoldTail) or PairCache must be saved in snapshot.cpp (and in rollback states); these
  // sizes are those of the fields saved today, padded as the compiler pads them.
  constexpr auto padded = [](std::size_t bytes, std::size_t align) {
    return (bytes + align - 1) / align * align;
  };
  constexpr std::size_t kR = sizeof(Real);
  using detail::ContactPoint;
  using detail::Manifold;
  using detail::PairCache;
  EXPECT_EQ(sizeof(ContactPoint), padded(5 * kR + 4, alignof(ContactPoint)));
  // The bodies and point count (one word with body b), the normal, the points, the friction
  // impulses.
  EXPECT_EQ(sizeof(Manifold),
            padded(4 + 4 + 3 * kR + detail::kMaxManifoldPoints * sizeof(ContactPoint) + 3 * kR,
                   alignof(Manifold)));
  // A head: the same but for the points past the first, and the solver's index of its tail.
  EXPECT_EQ(sizeof(detail::ManifoldHead), padded(4 + 4 + 3 * kR + sizeof(ContactPoint) + 3 * kR + 4,
                                                 alignof(detail::ManifoldHead)));
  // A tail: the key and the points past the first.
  EXPECT_EQ(sizeof(detail::ManifoldTail),
            padded(8 + (detail::kMaxManifoldPoints - 1) * sizeof(ContactPoint),
                   alignof(detail::ManifoldTail)));
  // The key, two rotations, two offsets and the packed rotation.
  EXPECT_EQ(
      sizeof(PairCache),
      padded(8 + 2 * sizeof(Quat) + 6 * kR + sizeof(detail::PackedRotation), alignof(PairCache)));
}

TEST(SnapshotFormat, RestoresIdsAndTheirGenerations) {
  World world = small_world();
  const BodyId id = world.body_at(2);
  const World copy = load_snapshot(save_snapshot(world));
  EXPECT_TRUE(copy.is_valid(id));
  EXPECT_EQ(copy.position(id), world.position(id));
  EXPECT_EQ(detail::state_of(copy).slot_generation, detail::state_of(world).slot_generation);
  EXPECT_EQ(detail::state_of(copy).free_slots, detail::state_of(world).free_slots);
}

TEST(SnapshotFormat, DestroyedBodiesAndShapesRoundTripAndContinueIdentically) {
  // Destroying leaves a free list, bumped generations, a moved-in last body and a destroyed
  // shape mark; all are state the next create_body and step read.
  World world = small_world();
  const BodyId gone = world.body_at(1);
  world.destroy_body(gone);
  ShapeDef unused;
  unused.radius = Real(0.1);
  const ShapeId dropped = world.create_shape(unused);
  world.destroy_shape(dropped);
  world.step(Real(1.0 / 60.0));
  World copy = load_snapshot(save_snapshot(world));
  EXPECT_FALSE(copy.is_valid(gone));
  EXPECT_EQ(detail::state_of(copy).free_slots, detail::state_of(world).free_slots);
  EXPECT_EQ(detail::state_of(copy).api.shape_destroyed,
            detail::state_of(world).api.shape_destroyed);
  BodyDef b;
  b.shape = ShapeId{1};
  b.position = Vec3(0, 2, 0);
  EXPECT_EQ(copy.create_body(b), world.create_body(b));
  for (int s = 0; s < 20; ++s) {
    world.step(Real(1.0 / 60.0));
    copy.step(Real(1.0 / 60.0));
    ASSERT_EQ(copy.state_hash(), world.state_hash()) << "step " << s;
  }
}

}  // namespace snapshot_format_test
}  // namespace elan
