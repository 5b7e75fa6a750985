// SPDX-License-Identifier: MIT
// The world settings the viewer changes live (gravity, sleeping, substeps, iterations, threads):
// a plain struct and the function that applies it to a world between steps, with no window or
// OpenGL, so that tests drive exactly what the panel does.
#pragma once

#include "elan/world.hpp"

namespace elan::viewer {

struct LiveSettings {
  Vec3 gravity = Vec3(0, Real(-9.81), 0);  ///< m/s^2, world
  bool sleeping = true;                    ///< World::sleep_enabled
  int substeps = 4;
  int iterations = 2;
  int threads = 1;  ///< worker count (never changes a result)
};

/// The world's current settings.
LiveSettings settings_of(const World& world);

/// Applies `s` to `world` between steps, each setting only when it differs from the world's (a
/// new gravity wakes every body, World::set_gravity; sleeping off wakes them too,
/// World::set_sleep_enabled). Throws elan::Error naming the field for a value the world refuses,
/// with the settings before it applied.
void apply_settings(World& world, const LiveSettings& s);

}  // namespace elan::viewer
