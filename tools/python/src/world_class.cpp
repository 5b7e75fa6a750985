// SPDX-License-Identifier: MIT
// The class elan.World and its guard against use during a step.
#include <pybind11/pybind11.h>

#include "errors.hpp"
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
  bind_loading(c);
  bind_stepping(c);
}

}  // namespace elan::py
