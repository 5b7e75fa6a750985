// SPDX-License-Identifier: MIT
// Zero-copy views of the body columns and the bulk setters that take arrays.
//
// A view is a read-only NumPy array whose buffer IS the engine's column (World::body_columns)
// and whose base is the Python World, so the world lives as long as the view. Steps and setters
// write the columns in place, so a view shows the new values without being fetched again;
// create_body, destroy_body and restore_snapshot may reallocate the columns, after which older
// views must not be read (docs/python.md).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <span>
#include <string>
#include <vector>

#include "convert.hpp"
#include "errors.hpp"
#include "py_world.hpp"

namespace elan::py {
namespace {

constexpr const char* kColumns[] = {"px", "py", "pz", "qw", "qx", "qy", "qz",
                                    "vx", "vy", "vz", "wx", "wy", "wz"};

std::span<const Real> column(const World::BodyColumns& c, const std::string& name) {
  const std::span<const Real> all[] = {c.px, c.py, c.pz, c.qw, c.qx, c.qy, c.qz,
                                       c.vx, c.vy, c.vz, c.wx, c.wy, c.wz};
  for (std::size_t i = 0; i < std::size(kColumns); ++i) {
    if (name == kColumns[i]) return all[i];
  }
  raise("column", "expected one of px py pz qw qx qy qz vx vy vz wx wy wz, got '" + name + "'");
}

pybind11::array view(pybind11::handle owner, std::span<const Real> s) {
  // An empty column may have no storage; NumPy still wants a non-null pointer.
  static const Real empty = 0;
  const Real* data = s.empty() ? &empty : s.data();
  pybind11::array a(pybind11::dtype::of<Real>(), {pybind11::ssize_t(s.size())},
                    {pybind11::ssize_t(sizeof(Real))}, data, owner);
  pybind11::detail::array_proxy(a.ptr())->flags &= ~pybind11::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// x, y, z columns of an (n, 3) array, n = the body count; elan.Error `field` otherwise.
void split(const World& world, const pybind11::handle& values, const char* field,
           std::vector<Real>& x, std::vector<Real>& y, std::vector<Real>& z) {
  const auto a = rows(values, 3, field);
  if (std::size_t(a.shape(0)) != world.body_count()) {
    raise(field, "expected " + std::to_string(world.body_count()) + " rows (one per body), got " +
                     std::to_string(a.shape(0)));
  }
  const auto r = a.unchecked<2>();
  const std::size_t n = std::size_t(a.shape(0));
  x.resize(n);
  y.resize(n);
  z.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = Real(r(i, 0));
    y[i] = Real(r(i, 1));
    z[i] = Real(r(i, 2));
  }
}

}  // namespace

void bind_columns(pybind11::class_<PyWorld>& c) {
  using pybind11::arg;
  c.def(
      "_body_columns",
      [](pybind11::object self) {
        const World& world = self.cast<const PyWorld&>().get();
        const World::BodyColumns cols = world.body_columns();
        pybind11::list out;
        for (const char* name : kColumns) out.append(view(self, column(cols, name)));
        return pybind11::tuple(out);
      },
      "The 13 column views, in the order px py pz qw qx qy qz vx vy vz wx wy wz.");
  c.def(
      "column",
      [](pybind11::object self, const std::string& name) {
        const World& world = self.cast<const PyWorld&>().get();
        return view(self, column(world.body_columns(), name));
      },
      arg("name"),
      "A read-only, zero-copy view of one body column in dense index order: 'px' 'py' 'pz' "
      "(m, centre of mass), 'qw' 'qx' 'qy' 'qz' (principal axes to world), 'vx' 'vy' 'vz' "
      "(m/s), 'wx' 'wy' 'wz' (rad/s). Shows new values after every step; invalid after "
      "create_body, destroy_body or restore_snapshot.");
  c.def(
      "_column_address",
      [](const PyWorld& w, const std::string& name) {
        return reinterpret_cast<std::uintptr_t>(column(w.get().body_columns(), name).data());
      },
      arg("name"), "Debug: the address of the engine's column (for the zero-copy test).");
  c.def(
      "body_ids",
      [](const PyWorld& w) {
        const std::span<const BodyId> ids = w.get().body_ids();
        pybind11::array_t<uint64_t> out(pybind11::ssize_t(ids.size()));
        uint64_t* p = out.mutable_data();
        for (std::size_t i = 0; i < ids.size(); ++i) p[i] = to_int(ids[i]);
        return out;
      },
      "Body ids in dense index order (a copy): row i of the column views is body_ids()[i].");
  c.def(
      "set_center_of_mass_positions",
      [](PyWorld& w, pybind11::handle positions) {
        World& world = w.get();
        std::vector<Real> x, y, z;
        split(world, positions, "positions", x, y, z);
        world.set_center_of_mass_positions(x, y, z);
      },
      arg("positions"),
      "Moves every body's centre of mass to the rows of an (n, 3) array (m, world), n = "
      "body_count, in dense index order. Moved bodies wake. elan.Error 'positions' for a wrong "
      "shape or a non-finite value (nothing changed).");
  c.def(
      "set_linear_velocities",
      [](PyWorld& w, pybind11::handle velocities) {
        World& world = w.get();
        std::vector<Real> x, y, z;
        split(world, velocities, "velocities", x, y, z);
        world.set_linear_velocities(x, y, z);
      },
      arg("velocities"), "(n, 3) array, m/s, world, in dense index order.");
  c.def(
      "set_angular_velocities",
      [](PyWorld& w, pybind11::handle velocities) {
        World& world = w.get();
        std::vector<Real> x, y, z;
        split(world, velocities, "angular_velocities", x, y, z);
        world.set_angular_velocities(x, y, z);
      },
      arg("velocities"), "(n, 3) array, rad/s, world, in dense index order.");
}

}  // namespace elan::py
