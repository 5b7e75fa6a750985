// SPDX-License-Identifier: MIT
// The compiled part of the Python package elan: `elan._elan`. Each concept binds itself from its
// own file; elan/__init__.py re-exports the names.
#include <pybind11/pybind11.h>

#include "elan/profile.hpp"
#include "py_world.hpp"

PYBIND11_MODULE(_elan, m) {
  namespace ep = elan::py;
  m.doc() = "elan, a deterministic rigid-body physics engine (compiled core; use `import elan`).";
  ep::bind_errors(m);
  m.attr("STEP_OK") = uint32_t(elan::kStepOk);
  m.attr("STEP_FROZE_NON_FINITE") = uint32_t(elan::kStepFrozeNonFinite);
  m.attr("STEP_COLOR_OVERFLOW") = uint32_t(elan::kStepColorOverflow);
  m.attr("STEP_BAD_TIMESTEP") = uint32_t(elan::kStepBadTimestep);
  ep::bind_world_class(m);
}
