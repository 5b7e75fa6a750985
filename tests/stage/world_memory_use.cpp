// SPDX-License-Identifier: MIT
// The memory report accounts for the heap a world holds: its parts add up to what glibc says the
// world allocated, so a buffer added to the world and left out of the report shows here.
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdio>

#include "core/base/compound.hpp"
#include "core/base/grow.hpp"
#include "core/base/heap_bytes.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/triangle_mesh.hpp"
#include "core/world/memory_use.hpp"
#include "core/world/world_access.hpp"
#include "elan/scene.hpp"
#include "elan/world.hpp"
#include "physics/physics_util.hpp"

namespace elan {
namespace world_memory_use_test {

std::size_t heap_in_use() {
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
}

TEST(MemoryUse, PartsAddUpToTheHeapTheWorldHolds) {
  const Scene scene = load_scene(std::string(ELAN_SCENE_DIR) + "/pile1k.json");
  WorldDef def = scene.world;
  def.threads = 1;
  const std::size_t before = heap_in_use();
  World world(def);
  load_into(scene, world, "pile1k");
  for (int i = 0; i < 120; ++i) world.step(scene.timestep);
  const std::size_t held = heap_in_use() - before;
  const detail::MemoryUse use = detail::memory_use(detail::state_of(world));
  std::printf(
      "held %zu B, reported %zu B: bodies %zu shapes %zu broadphase %zu contacts %zu "
      "solver %zu api %zu\n",
      held, use.total(), use.bodies, use.shapes, use.broadphase, use.contacts, use.solver, use.api);
  EXPECT_GT(use.contacts,
            detail::state_of(world).contacts.size() * sizeof(detail::ManifoldHead) +
                detail::state_of(world).contacts.tails().size() * sizeof(detail::ManifoldTail));
  EXPECT_GT(use.solver, 0u);
  EXPECT_GT(use.broadphase, detail::state_of(world).pairs.size() * sizeof(uint64_t));
  if (test::kSanitized) {
    GTEST_SKIP() << "AddressSanitizer's allocator does not feed glibc's mallinfo2 counters";
  }
  // Every reported byte is a live buffer of the world, so the report cannot exceed the heap.
  EXPECT_LE(use.total(), held);
  // What it leaves out is the allocator's 8-16 bytes a block, shared_ptr control blocks and
  // the thread pool's bookkeeping: a few percent. A forgotten contact-sized buffer is 10%+.
  EXPECT_GE(double(use.total()), 0.9 * double(held));
}

// A mesh, a heightfield and a compound are counted once each however many bodies share them, and
// they are nearly all of the heap such a world holds.
TEST(MemoryUse, SharedSurfacesAreCountedOnce) {
  World world;
  // The world's own buffers (its thread pool, scratch) are there before the shapes.
  const std::size_t before = heap_in_use();
  const std::size_t reported_before = detail::memory_use(detail::state_of(world)).total();
  ShapeDef mesh;
  mesh.type = ShapeType::Mesh;
  const uint32_t n = 100;
  for (uint32_t j = 0; j <= n; ++j) {
    for (uint32_t i = 0; i <= n; ++i)
      mesh.vertices.emplace_back(Real(i), Real((i * j) % 3), Real(j));
  }
  for (uint32_t j = 0; j < n; ++j) {
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i;
      mesh.triangles.push_back({a, a + n + 2, a + 1});
      mesh.triangles.push_back({a, a + n + 1, a + n + 2});
    }
  }
  ShapeDef field;
  field.type = ShapeType::Heightfield;
  field.columns = 200;
  field.heights.assign(200 * 150, Real(1));
  ShapeDef compound;
  compound.type = ShapeType::Compound;
  compound.children.resize(10);
  for (int k = 0; k < 10; ++k) compound.children[k].position = Vec3(Real(k), 0, 0);
  BodyDef b;
  b.motion = MotionType::Static;
  for (const ShapeDef* d : {&mesh, &field, &compound}) {
    b.shape = world.create_shape(*d);
    for (int copy = 0; copy < 3; ++copy) {
      b.position = Vec3(Real(300 * copy), 0, 0);
      world.create_body(b);
    }
  }
  // Move-assigned (a copy of an empty vector would keep the buffer): the definitions let go.
  mesh = ShapeDef{};
  field = ShapeDef{};
  compound = ShapeDef{};
  const std::size_t held = heap_in_use() - before;
  const detail::WorldState& s = detail::state_of(world);
  const detail::MemoryUse use = detail::memory_use(s);
  const std::size_t surfaces = detail::mesh_bytes(*s.shapes[0].mesh) +
                               detail::heightfield_bytes(*s.shapes[1].heightfield) +
                               detail::compound_bytes(*s.shapes[2].compound);
  EXPECT_EQ(use.shapes, detail::heap_bytes(s.shapes) + surfaces);
  if (test::kSanitized) {
    GTEST_SKIP() << "AddressSanitizer's allocator does not feed glibc's mallinfo2 counters";
  }
  const std::size_t reported = use.total() - reported_before;
  std::printf("held %zu B, reported %zu B, surfaces %zu B\n", held, reported, surfaces);
  EXPECT_LE(reported, held);
  EXPECT_GE(double(reported), 0.9 * double(held));
}

// A spike is cut once its window has passed, to a quarter past the window's high; a use that swings
// between steps within a window is left alone, so a buffer is never cut and regrown in turn.
TEST(SpikeTrim, CutsWhatASpikeLeftAndLeavesSwingsAlone) {
  detail::SpikeTrim trim;
  const std::size_t element = 64, floor = detail::SpikeTrim::kFloorBytes / element;
  std::size_t cuts = 0, capacity = 100000;
  for (uint32_t step = 0; step < 4 * detail::SpikeTrim::kWindow; ++step) {
    const std::size_t used = step < 5 ? 100000 : 400;  // the first steps, then a settled scene
    if (const std::size_t cut = trim.note(used, capacity, element)) {
      ++cuts;
      capacity = cut;
    }
  }
  // The first window saw the spike and is left; the second saw 400 a step at most.
  EXPECT_EQ(cuts, 1u);
  EXPECT_EQ(capacity, 500u);

  detail::SpikeTrim swing;
  for (uint32_t step = 0; step < 4 * detail::SpikeTrim::kWindow; ++step) {
    const std::size_t used = step % 2 == 0 ? 4000 : 40;
    EXPECT_EQ(swing.note(used, 5000, element), 0u) << "step " << step;
  }
  // Small buffers are not worth a reallocation.
  detail::SpikeTrim small;
  for (uint32_t step = 0; step < 2 * detail::SpikeTrim::kWindow; ++step) {
    EXPECT_EQ(small.note(0, floor, element), 0u);
  }
}

// The step's scratch: the sweep's, the collide stage's and the solver's per-step buffers are
// taken from it and given back within the step, so between steps it holds nothing (a buffer still
// held would keep its bytes from the next phase, and the block would only grow), and the stages'
// own buffers of new keys and bundles stay empty. (That the block hands back what a pile's first
// steps left is StepScratch.HandsBackWhatASpikeLeft.)
TEST(MemoryUse, StepBuffersAreGivenBackWithinTheStep) {
  const Scene scene = load_scene(std::string(ELAN_SCENE_DIR) + "/pile4k.json");
  // Sanitized (ten times slower), the 2-thread run alone: it takes the same buffers.
  const std::vector<int> thread_counts = test::kSanitized ? std::vector{2} : std::vector{1, 2};
  for (int threads : thread_counts) {
    WorldDef def = scene.world;
    def.threads = threads;
    World world(def);
    load_into(scene, world, "pile4k");
    const detail::WorldState& w = detail::state_of(world);
    auto kept = [&] {
      std::size_t bytes = detail::heap_bytes(w.solver.bundles) + detail::heap_bytes(w.solver.rows);
      bytes += w.contacts.step_buffer_bytes();
      return bytes;
    };
    for (int i = 0; i < 120; ++i) {
      world.step(scene.timestep);
      ASSERT_EQ(w.scratch.held_bytes(), 0u) << "step " << i << ", " << threads << " threads";
      ASSERT_EQ(kept(), 0u) << "step " << i << ", " << threads << " threads";
    }
    EXPECT_GT(w.scratch.heap_bytes(), 0u);
    EXPECT_GT(w.stats.manifolds, 4000u);  // the pile is in contact: the phases did use it
  }
}

}  // namespace world_memory_use_test
}  // namespace elan
