// SPDX-License-Identifier: MIT
// World settings that may change between steps, and the world's totals (energy, momenta).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "elan/run_summary.hpp"
#include "options.hpp"
#include "py_world.hpp"

namespace elan::py {

void bind_settings(pybind11::class_<PyWorld>& c) {
  using pybind11::arg;
  c.def_property(
      "gravity", [](const PyWorld& w) { return tuple3(w.get().settings().gravity); },
      [](PyWorld& w, V3 g) { w.get().set_gravity(vec3(g)); },
      "m/s^2, world. Setting it wakes every body.");
  c.def_property(
      "substeps", [](const PyWorld& w) { return w.get().settings().substeps; },
      [](PyWorld& w, int n) { w.get().set_substeps(n); }, "Substeps per step, 1..64.");
  c.def_property(
      "iterations", [](const PyWorld& w) { return w.get().settings().iterations; },
      [](PyWorld& w, int n) { w.get().set_iterations(n); },
      "Solver iterations per substep, 1..64.");
  c.def_property(
      "threads", [](const PyWorld& w) { return w.get().settings().threads; },
      [](PyWorld& w, std::optional<int> n) { w.get().set_threads(threads_from(n)); },
      "Worker threads of the step (None or 0 = all cores). Results do not depend on it.");
  c.def_property(
      "broadphase", [](const PyWorld& w) { return broadphase_name(w.get().settings().broadphase); },
      [](PyWorld& w, const std::string& name) {
        w.get().set_broadphase(broadphase_from_name(name));
      },
      "'sap', 'all-pairs' or 'tree'. Results do not depend on it.");
  c.def_property(
      "allow_sleep", [](const PyWorld& w) { return w.get().sleep_enabled(); },
      [](PyWorld& w, bool on) { w.get().set_sleep_enabled(on); },
      "Whether resting bodies fall asleep. Off wakes every body; back on, a body sleeps after the "
      "full time at rest (World::set_sleep_enabled).");
  c.def(
      "set_hit_event_threshold",
      [](PyWorld& w, double speed) { w.get().set_hit_event_threshold(Real(speed)); }, arg("speed"),
      "Approach speed (m/s, >= 0) from which a new contact is a hit event.");
  c.def_property_readonly(
      "kinetic_energy", [](const PyWorld& w) { return double(w.get().kinetic_energy()); },
      "J, all dynamic bodies.");
  c.def_property_readonly(
      "linear_momentum", [](const PyWorld& w) { return tuple3(w.get().linear_momentum()); },
      "kg m/s, dynamic bodies.");
  c.def_property_readonly(
      "angular_momentum", [](const PyWorld& w) { return tuple3(w.get().angular_momentum()); },
      "kg m^2/s, dynamic bodies, about the world origin.");
  c.def(
      "last_step",
      [](const PyWorld& w) {
        const StepStats& s = w.get().last_step();
        pybind11::dict d;
        d["pairs"] = s.pairs;
        d["manifolds"] = s.manifolds;
        d["contacts"] = s.contacts;
        d["awake"] = s.awake;
        d["colors"] = s.colors;
        d["overflow"] = s.overflow;
        d["status"] = s.status;
        d["total_ms"] = s.profile.total;
        return d;
      },
      "Counts of the last step: pairs, manifolds, contacts, awake, colors, overflow, status, "
      "total_ms (wall time).");
}

}  // namespace elan::py
