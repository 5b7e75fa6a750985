// The memory report accounts for the heap a world holds: its parts add up to what glibc says the
// world allocated, so a buffer added to the world and left out of the report shows here.
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdio>

#include "core/base/grow.hpp"
#include "core/world/memory_use.hpp"
#include "core/world/world_state.hpp"
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
  const detail::MemoryUse use = detail::memory_use(world.state());
  std::printf(
      "held %zu B, reported %zu B: bodies %zu shapes %zu broadphase %zu contacts %zu "
      "solver %zu api %zu\n",
      held, use.total(), use.bodies, use.shapes, use.broadphase, use.contacts, use.solver, use.api);
  EXPECT_GT(use.contacts, world.state().contacts.size() * sizeof(detail::Manifold));
  EXPECT_GT(use.solver, 0u);
  EXPECT_GT(use.broadphase, world.state().pairs.size() * sizeof(uint64_t));
  if (test::kSanitized) {
    GTEST_SKIP() << "AddressSanitizer's allocator does not feed glibc's mallinfo2 counters";
  }
  // Every reported byte is a live buffer of the world, so the report cannot exceed the heap.
  EXPECT_LE(use.total(), held);
  // What it leaves out is the allocator's 8-16 bytes a block, shared_ptr control blocks and
  // the thread pool's bookkeeping: a few percent. A forgotten contact-sized buffer is 10%+.
  EXPECT_GE(double(use.total()), 0.9 * double(held));
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

// The collide stage's new-key buffers: in the first steps most pairs are new, in a settling pile
// a few are; the buffers hand the difference back. (pile1k's stay under SpikeTrim's floor.)
TEST(MemoryUse, NewKeyBuffersShrinkOnceAPileSettles) {
  const Scene scene = load_scene(std::string(ELAN_SCENE_DIR) + "/pile4k.json");
  WorldDef def = scene.world;
  def.threads = 1;
  World world(def);
  load_into(scene, world, "pile4k");
  auto capacity = [&] {
    std::size_t bytes = 0;
    for (const auto& b : world.state().contact_blocks.contacts.added) {
      bytes += b.capacity() * sizeof(detail::Manifold);
    }
    for (const auto& b : world.state().contact_blocks.separated.added) {
      bytes += b.capacity() * sizeof(detail::SeparatedPair);
    }
    return bytes;
  };
  std::size_t high = 0;
  for (int i = 0; i < 200; ++i) {
    world.step(scene.timestep);
    high = std::max(high, capacity());
  }
  std::printf("new-key buffers: %zu B at most, %zu B after 200 steps\n", high, capacity());
  EXPECT_LT(capacity(), high / 2);
}

}  // namespace world_memory_use_test
}  // namespace elan
