// SPDX-License-Identifier: MIT
// World.step (without the GIL), the state hash, and the summary `elan run` prints.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>

#include "elan/run_summary.hpp"
#include "errors.hpp"
#include "py_world.hpp"

namespace py = pybind11;

namespace elan::py {
namespace {

using Clock = std::chrono::steady_clock;

// Marks the world busy for the duration of a step that runs without the GIL.
struct BusyGuard {
  PyWorld& w;
  explicit BusyGuard(PyWorld& world) : w(world) { w.busy = true; }
  ~BusyGuard() { w.busy = false; }
  BusyGuard(const BusyGuard&) = delete;
  BusyGuard& operator=(const BusyGuard&) = delete;
};

uint32_t step(PyWorld& w, int64_t n, std::optional<double> dt) {
  World& world = w.get();
  if (n < 0) raise("n", "must be >= 0, got " + std::to_string(n));
  const Real h = dt ? Real(*dt) : w.timestep;
  if (!std::isfinite(h) || !(h > 0)) raise("dt", "must be finite and positive");
  uint32_t status = kStepOk;
  BusyGuard guard(w);
  // Other Python threads run meanwhile; `busy` keeps them off this world (PyWorld::get).
  pybind11::gil_scoped_release release;
  for (int64_t i = 0; i < n; ++i) {
    const auto t0 = Clock::now();
    const uint32_t s = world.step(h);
    w.totals.add(world, s, std::chrono::duration<double>(Clock::now() - t0).count());
    status |= s;
  }
  return status;
}

}  // namespace

void bind_stepping(pybind11::class_<PyWorld>& c) {
  c.def("step", &step, pybind11::arg("n") = 1, pybind11::arg("dt") = pybind11::none(),
        "Advances the world by `n` steps of `dt` seconds each (default: the scene's timestep, "
        "`World.timestep`). Runs without the GIL: other Python threads go on meanwhile (but may "
        "not use this world: elan.Error 'world'). Returns the OR of the steps' status flags "
        "(elan.STEP_FROZE_NON_FINITE, STEP_COLOR_OVERFLOW, STEP_BAD_TIMESTEP; 0 = all fine).");
  c.def_property_readonly(
      "state_hash", [](const PyWorld& w) { return w.get().state_hash(); },
      "64-bit hash of every body's stored position, orientation and velocities, in body index "
      "order; `elan run` prints it as 16 hex digits (state_hash == int(summary['state_hash'], "
      "16)).");
  c.def_property_readonly(
      "step_count", [](const PyWorld& w) { return w.totals.steps; },
      "Steps taken through this object (since it was made or unpickled).");
  c.def_property(
      "timestep", [](const PyWorld& w) { return double(w.timestep); },
      [](PyWorld& w, double dt) {
        if (!std::isfinite(dt) || !(dt > 0)) raise("timestep", "must be finite and positive");
        w.timestep = Real(dt);
      },
      "s per step when step() is given no dt (the scene's `timestep`, 1/60 by default).");
  c.def(
      "_summary_json",
      [](const PyWorld& w) { return run_summary_json(w.get(), w.scene, w.timestep, w.totals); },
      "The summary as the JSON line `elan run` prints.");
  c.def(
      "summary",
      [](const PyWorld& w) {
        const std::string text = run_summary_json(w.get(), w.scene, w.timestep, w.totals);
        return pybind11::module_::import("json").attr("loads")(text);
      },
      "The summary `elan run` prints, as a dict with the same keys and values: scene, bodies, "
      "joints, steps (taken through this object), threads, broadphase, timestep (s), "
      "substeps, iterations, wall_seconds, ms_per_step, state_hash (16 hex digits), "
      "kinetic_energy (J), linear_momentum (kg m/s), angular_momentum (kg m^2/s), pairs, "
      "manifolds, contacts, awake, colors, overflow, status, profile_ms.");
}

}  // namespace elan::py
