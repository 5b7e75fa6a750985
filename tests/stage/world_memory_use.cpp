// The memory report accounts for the heap a world holds: its parts add up to what glibc says the
// world allocated, so a buffer added to the world and left out of the report shows here.
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdio>

#include "core/world/memory_use.hpp"
#include "elan/scene.hpp"
#include "elan/world.hpp"
#include "physics/physics_util.hpp"

namespace elan {
namespace {

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

}  // namespace
}  // namespace elan
