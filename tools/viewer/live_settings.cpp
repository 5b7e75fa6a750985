// SPDX-License-Identifier: MIT
#include "tools/viewer/live_settings.hpp"

namespace elan::viewer {

LiveSettings settings_of(const World& world) {
  const WorldDef& d = world.settings();
  LiveSettings s;
  s.gravity = d.gravity;
  s.sleeping = world.sleep_enabled();
  s.substeps = d.substeps;
  s.iterations = d.iterations;
  s.threads = d.threads;
  return s;
}

void apply_settings(World& world, const LiveSettings& s) {
  const WorldDef& d = world.settings();
  // Exact comparison: a gravity set again to the same bits must not wake the bodies.
  if (s.gravity != d.gravity) world.set_gravity(s.gravity);
  if (s.sleeping != world.sleep_enabled()) world.set_sleep_enabled(s.sleeping);
  if (s.substeps != d.substeps) world.set_substeps(s.substeps);
  if (s.iterations != d.iterations) world.set_iterations(s.iterations);
  if (s.threads != d.threads) world.set_threads(s.threads);
}

}  // namespace elan::viewer
