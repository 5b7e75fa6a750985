// SPDX-License-Identifier: MIT
// Loads a scene from JSON text through elan::elan_scene and checks its ball falls as v = g t says.
#include <elan/elan.hpp>

#include <cmath>
#include <cstdio>

constexpr const char* kScene = R"({
  "bodies": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "position": [0, 10, 0]}]
})";

int main() {
  const elan::Scene scene = elan::parse_scene(kScene, "inline.json");
  elan::World world(scene.world);
  elan::load_into(scene, world, "inline.json");
  for (int i = 0; i < 60; ++i) world.step(scene.timestep);
  const float vy = world.linear_velocity(world.body_at(0)).y();
  std::printf("scene: %zu bodies, vy after 1 s: %.4f m/s\n", world.body_count(), vy);
  return world.body_count() == 1 && std::abs(vy + 9.81f) < 1e-3f ? 0 : 1;
}
