// SPDX-License-Identifier: MIT
// The viewer's Dear ImGui panels: controls (play, step, slow motion, reset, world settings,
// scenes to open), statistics (the last step's stage times and counts, live plots of the step
// time and kinetic energy), the selected body, overlays, and the replay timeline.
#pragma once

#include "tools/viewer/app_state.hpp"

namespace elan::viewer {

void draw_panels(AppState& app);

}  // namespace elan::viewer
