// SPDX-License-Identifier: MIT
// The debug-draw overlays (bounds, contacts, joints, centres of mass): the library's
// World::debug_draw drives a DebugDrawer that turns its lines, points and boxes into the
// renderer's overlay lines, drawn over the bodies. Shapes (and their island colours) are drawn
// by the scene view, so draw_shape is not asked for.
#pragma once

#include <cstdint>

#include "elan/world.hpp"
#include "tools/viewer/renderer.hpp"

namespace elan::viewer {

/// Adds the overlays `flags` (elan::DebugDrawFlags; kDrawShapes and kDrawIslands are ignored,
/// kDrawSolverHalves adds the contacts of the cut) to this frame's overlay lines.
void draw_overlays(const World& world, uint32_t flags, Renderer& renderer);

}  // namespace elan::viewer
