// SPDX-License-Identifier: MIT
// elan.Error: the Python face of elan::Error and elan::SceneError, a ValueError carrying the name
// of the field at fault in `.field`.
#include <pybind11/pybind11.h>

#include <exception>
#include <string>

#include "elan/error.hpp"
#include "elan/scene.hpp"
#include "errors.hpp"
#include "py_world.hpp"

namespace py = pybind11;

namespace elan::py {
namespace {

PyObject* error_type = nullptr;

void set_error(const std::string& field, const char* message) {
  pybind11::object type = pybind11::reinterpret_borrow<pybind11::object>(error_type);
  pybind11::object exc = type(message);
  exc.attr("field") = field;
  PyErr_SetObject(error_type, exc.ptr());
}

}  // namespace

[[noreturn]] void raise(const std::string& field, const std::string& message) {
  throw Error(field, message);
}

void bind_errors(pybind11::module_& m) {
  static pybind11::exception<Error> type(m, "Error", PyExc_ValueError);
  error_type = type.ptr();
  type.attr("field") = "";
  type.attr("__doc__") =
      "An invalid argument, scene or snapshot. `field` names what was wrong (e.g. "
      "'shape.radius', 'mass', 'positions'); empty when no single field is at fault.";
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      set_error(e.field(), e.what());
    } catch (const SceneError& e) {
      set_error(e.field().empty() ? "scene" : e.field(), e.what());
    }
  });
}

}  // namespace elan::py
