// SPDX-License-Identifier: MIT
// The state behind a Python elan.World: the World, the run's totals for summary(), and the guard
// that keeps other Python threads out while a step runs without the GIL.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>

#include "elan/run_summary.hpp"
#include "elan/world.hpp"

namespace elan::py {

struct PyWorld {
  World world;
  Real timestep = Real(1.0 / 60.0);  ///< s per step when step() is given no dt
  std::string scene = "<world>";     ///< the name summary() reports
  RunTotals totals;
  /// Set while step() runs without the GIL; read and written only with the GIL held, so a
  /// plain bool is enough.
  bool busy = false;

  explicit PyWorld(World w) : world(std::move(w)) {}
  /// The world, or elan.Error "world" while another thread steps it (a call then would race
  /// with the step).
  World& get();
  const World& get() const;
};

/// Registers the class elan.World and its methods (one file per concept adds to it).
void bind_world_class(pybind11::module_& m);
void bind_errors(pybind11::module_& m);
void bind_loading(pybind11::class_<PyWorld>& c);
void bind_stepping(pybind11::class_<PyWorld>& c);
void bind_settings(pybind11::class_<PyWorld>& c);
void bind_shapes(pybind11::class_<PyWorld>& c);
void bind_bodies(pybind11::class_<PyWorld>& c);
void bind_joints(pybind11::class_<PyWorld>& c);
void bind_queries(pybind11::class_<PyWorld>& c);
void bind_events(pybind11::class_<PyWorld>& c);
void bind_columns(pybind11::class_<PyWorld>& c);
void bind_snapshots(pybind11::class_<PyWorld>& c);

}  // namespace elan::py
