// SPDX-License-Identifier: MIT
// Fuzz target: the scene loader on any text. A scene is either refused with one SceneError
// line, or it loads and runs a few steps with every body finite.
#include <string>

#include "elan/scene.hpp"
#include "fuzz/world_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace elan;
  // A scene file is text a person writes; past 64 KiB the mutations only make the run slower.
  if (size > (64u << 10)) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  Scene scene;
  try {
    scene = parse_scene(text, "fuzz.json");
  } catch (const SceneError& e) {
    fuzz::require_one_line(e.what());
    return 0;
  }
  // Generators make thousands of bodies from a few bytes; their loading is what is fuzzed, a
  // long run of a big pile is the benchmarks' business. Past the largest standard scene a load
  // runs the same code for longer, and the largest the format allows outlast libFuzzer's
  // timeout under the sanitizers (docs/fuzzing.md).
  constexpr std::size_t kMaxLoaded = 40000;
  if (scene.bodies.size() + scene.joints.size() > kMaxLoaded) return 0;
  WorldDef def = scene.world;
  def.threads = 1;
  World world(def);
  try {
    load_into(scene, world, "fuzz.json");
  } catch (const SceneError& e) {
    fuzz::require_one_line(e.what());
    return 0;
  }
  fuzz::require_finite(world, "after loading");
  const int steps = world.body_count() <= 64 ? 8 : world.body_count() <= 512 ? 1 : 0;
  for (int k = 0; k < steps; ++k) {
    world.step(scene.timestep);
    fuzz::require_finite(world, "after a step");
  }
  return 0;
}
