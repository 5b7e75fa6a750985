// SPDX-License-Identifier: MIT
// A snapshot taken mid-run (step 100) and restored into a fresh world continues with the same bits
// as the run that never stopped, at 1 and 2 threads and with either broadphase.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/world/world_access.hpp"
#include "determinism/snapshot_scene.hpp"
#include "elan/snapshot.hpp"

namespace elan {
namespace snapshot_restore_test {

constexpr int kSaveAt = 100;
constexpr int kEnd = 130;

struct Reference {
  std::vector<uint8_t> snapshot;  // taken after kSaveAt steps
  std::vector<uint64_t> hashes;   // hashes[s] after kSaveAt + s steps, s = 0..kEnd - kSaveAt
  std::size_t asleep_at_save = 0;
  std::size_t contacts_with_impulse = 0;
  bool stack_woke = false;
};

std::size_t asleep(const World& w) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < w.body_count(); ++i) {
    const BodyId id = w.body_at(i);
    n += w.motion_type(id) == MotionType::Dynamic && !w.is_awake(id);
  }
  return n;
}

const Reference& reference() {
  static const Reference r = [] {
    Reference r;
    World world = test::make_snapshot_world(1);
    for (int s = 0; s < kSaveAt; ++s) world.step(test::kSnapshotDt);
    r.snapshot = save_snapshot(world);
    r.asleep_at_save = asleep(world);
    for (const detail::ManifoldHead& m : detail::state_of(world).contacts.heads()) {
      r.contacts_with_impulse += m.point_count > 0 && m.first.normal_impulse != 0;
    }
    const BodyId stack_bottom = world.body_at(world.body_count() - 4);
    r.hashes.push_back(world.state_hash());
    for (int s = kSaveAt; s < kEnd; ++s) {
      world.step(test::kSnapshotDt);
      r.hashes.push_back(world.state_hash());
    }
    r.stack_woke = world.is_awake(stack_bottom);
    return r;
  }();
  return r;
}

void expect_continues_like_reference(World& world) {
  const Reference& r = reference();
  ASSERT_EQ(world.state_hash(), r.hashes[0]);
  for (std::size_t s = 1; s < r.hashes.size(); ++s) {
    world.step(test::kSnapshotDt);
    ASSERT_EQ(world.state_hash(), r.hashes[s]) << "step " << kSaveAt + s;
  }
}

TEST(Snapshot, WindowHoldsSleepingBodiesWarmStartsAndAWakeUp) {
  // Guards the scene: without these the restore tests would not exercise what they claim.
  const Reference& r = reference();
  EXPECT_GE(r.asleep_at_save, 6u);
  EXPECT_GT(r.contacts_with_impulse, 100u);
  EXPECT_TRUE(r.stack_woke);
}

TEST(Snapshot, LoadedWorldContinuesBitIdenticallyAtOneAndTwoThreads) {
  for (int threads : {1, 2}) {
    SCOPED_TRACE(threads);
    World world = load_snapshot(reference().snapshot);
    world.set_threads(threads);
    expect_continues_like_reference(world);
  }
}

TEST(Snapshot, RestoredIntoAFreshWorldContinuesBitIdentically) {
  for (BroadphaseType broadphase : {BroadphaseType::SweepAndPrune, BroadphaseType::AllPairs}) {
    WorldDef def;
    def.threads = 2;
    def.broadphase = broadphase;
    World world(def);
    restore_snapshot(world, reference().snapshot);
    expect_continues_like_reference(world);
  }
}

TEST(Snapshot, RestoredOverARunningWorldContinuesBitIdentically) {
  // The target already has other bodies, contacts and a kept sweep order; all are replaced.
  World world = test::make_snapshot_world(2);
  for (int s = 0; s < 30; ++s) world.step(test::kSnapshotDt);
  restore_snapshot(world, reference().snapshot);
  expect_continues_like_reference(world);
}

TEST(Snapshot, SavingALoadedWorldGivesTheSameBytes) {
  const World world = load_snapshot(reference().snapshot);
  EXPECT_EQ(save_snapshot(world), reference().snapshot);
}

// Forces applied for the next step are state: a snapshot or rollback state taken between
// apply_force and step carries them, and the restored world steps with them.
TEST(Snapshot, ForcesAppliedForTheNextStepAreSavedAndRestored) {
  World world = test::make_snapshot_world(1);
  for (int s = 0; s < 20; ++s) world.step(test::kSnapshotDt);
  World unpushed = load_snapshot(save_snapshot(world));
  for (std::size_t i = 0; i < world.body_count(); i += 97) {
    const BodyId id = world.body_at(i);
    world.apply_force(id, Vec3(Real(40 + i), Real(300), Real(-25)));
    world.apply_torque(id, Vec3(0, Real(3), Real(1)));
  }
  ASSERT_GT(detail::state_of(world).bodies.applied_forces.size(), 5u);
  const std::vector<uint8_t> snapshot = save_snapshot(world);
  const std::vector<uint8_t> rollback = save_rollback(world);
  world.step(test::kSnapshotDt);
  const uint64_t pushed = world.state_hash();
  unpushed.step(test::kSnapshotDt);
  ASSERT_NE(unpushed.state_hash(), pushed) << "the forces change the step";
  World loaded = load_snapshot(snapshot);
  loaded.step(test::kSnapshotDt);
  EXPECT_EQ(loaded.state_hash(), pushed);
  restore_rollback(world, rollback);
  world.step(test::kSnapshotDt);
  EXPECT_EQ(world.state_hash(), pushed);
}

TEST(Snapshot, RestoresSettingsStepCountAndShapes) {
  const World world = load_snapshot(reference().snapshot);
  EXPECT_EQ(detail::state_of(world).step_count, uint64_t(kSaveAt));
  const World original = test::make_snapshot_world(1);
  EXPECT_EQ(world.settings().substeps, original.settings().substeps);
  EXPECT_EQ(world.settings().gravity, original.settings().gravity);
  ASSERT_EQ(detail::state_of(world).shapes.size(), detail::state_of(original).shapes.size());
  for (std::size_t i = 0; i < detail::state_of(world).shapes.size(); ++i) {
    const detail::Shape& a = detail::state_of(world).shapes[i];
    const detail::Shape& b = detail::state_of(original).shapes[i];
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.frame_position, b.frame_position);
    EXPECT_EQ(a.frame_rotation.coeffs(), b.frame_rotation.coeffs());
    EXPECT_EQ(a.unit_inertia, b.unit_inertia);
    EXPECT_EQ(a.bounding_radius, b.bounding_radius);
    ASSERT_EQ(bool(a.hull), bool(b.hull));
    if (a.hull) {
      EXPECT_EQ(a.hull->vertices, b.hull->vertices);
      EXPECT_EQ(a.hull->face_vertices, b.hull->face_vertices);
      EXPECT_EQ(a.hull->edges, b.hull->edges);
      ASSERT_EQ(a.hull->faces.size(), b.hull->faces.size());
      for (std::size_t f = 0; f < a.hull->faces.size(); ++f) {
        EXPECT_EQ(a.hull->faces[f].normal, b.hull->faces[f].normal);
        EXPECT_EQ(a.hull->faces[f].offset, b.hull->faces[f].offset);
      }
    }
  }
}

}  // namespace snapshot_restore_test
}  // namespace elan
