// SPDX-License-Identifier: MIT
// The class elan.World and its guard against use during a step.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "convert.hpp"
#include "elan/run_summary.hpp"
#include "errors.hpp"
#include "options.hpp"
#include "py_world.hpp"

namespace elan::py {

World& PyWorld::get() {
  if (busy) raise("world", "the world is stepping in another thread");
  return world;
}

const World& PyWorld::get() const {
  if (busy) raise("world", "the world is stepping in another thread");
  return world;
}

}  // namespace elan::py

namespace elan::py {

void bind_world_class(pybind11::module_& m) {
  pybind11::class_<PyWorld> c(m, "World",
                              "A physics world: bodies, shapes and joints advanced by step(). "
                              "Units are SI (m, kg, s, rad). Not for use from two threads at "
                              "once.");
  c.def(pybind11::init([](V3 gravity, int substeps, int iterations, bool allow_sleep,
                          std::optional<int> threads, const std::string& broadphase,
                          double timestep) {
          WorldDef def;
          def.gravity = vec3(gravity);
          def.substeps = substeps;
          def.iterations = iterations;
          def.allow_sleep = allow_sleep;
          def.threads = threads_from(threads);
          def.broadphase = broadphase_from_name(broadphase);
          if (!std::isfinite(timestep) || !(timestep > 0)) {
            raise("timestep", "must be finite and positive");
          }
          auto w = std::make_unique<PyWorld>(World(def));
          w->timestep = Real(timestep);
          return w;
        }),
        pybind11::kw_only(), pybind11::arg("gravity") = V3{0, -9.81, 0},
        pybind11::arg("substeps") = 4, pybind11::arg("iterations") = 2,
        pybind11::arg("allow_sleep") = true, pybind11::arg("threads") = pybind11::none(),
        pybind11::arg("broadphase") = "sap", pybind11::arg("timestep") = 1.0 / 60.0,
        "An empty world. gravity: m/s^2, world; substeps: 1..64 per step; iterations: solver "
        "iterations per substep, 1..64; threads: workers (None or 0 = all cores; results do not "
        "depend on it); broadphase: 'sap', 'all-pairs' or 'tree' (same results); timestep: s "
        "per step() by default.");
  bind_loading(c);
  bind_stepping(c);
  bind_settings(c);
  bind_shapes(c);
  bind_bodies(c);
  bind_joints(c);
  bind_queries(c);
  bind_events(c);
  bind_columns(c);
  bind_snapshots(c);
}

}  // namespace elan::py
