// SPDX-License-Identifier: MIT
// The debug-draw overlays (bounds, contacts, joints, centres of mass): the library's
// World::debug_draw drives a DebugDrawer that turns its lines, points and boxes into the
// renderer's lines. Shapes are drawn by the scene view, so draw_shape is not asked for.
#pragma once

#include <cstdint>

#include "elan/world.hpp"
#include "tools/viewer/renderer.hpp"

namespace elan::viewer {

/// Adds the overlays `flags` (elan::DebugDrawFlags, without kDrawShapes) to this frame's lines.
void draw_overlays(const World& world, uint32_t flags, Renderer& renderer);

}  // namespace elan::viewer
