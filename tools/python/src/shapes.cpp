// SPDX-License-Identifier: MIT
// Shapes: created with keyword arguments as in the scene file's "shape" objects.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>

#include "convert.hpp"
#include "errors.hpp"
#include "py_world.hpp"

namespace elan::py {
namespace {

ShapeType shape_type(const std::string& name, const char* field) {
  if (const std::optional<ShapeType> type = shape_type_from_name(name)) return *type;
  raise(field,
        "expected sphere, box, capsule, cylinder, convex_hull, plane, mesh, heightfield or "
        "compound, got '" +
            name + "'");
}

struct ShapeArgs {
  std::string type;
  double radius = 0.5, half_height = 0.5;
  V3 half_extents{0.5, 0.5, 0.5};
  pybind11::object points, vertices, triangles, heights, children;
  V3 normal{0, 1, 0};
  double offset = 0, spacing_x = 1, spacing_z = 1;
  uint64_t user_data = 0;
};

ShapeDef make_def(const ShapeArgs& a, const std::string& prefix) {
  ShapeDef d;
  d.type = shape_type(a.type, (prefix + "type").c_str());
  d.radius = Real(a.radius);
  d.half_height = Real(a.half_height);
  d.half_extents = vec3(a.half_extents);
  d.normal = vec3(a.normal);
  d.offset = Real(a.offset);
  d.spacing_x = Real(a.spacing_x);
  d.spacing_z = Real(a.spacing_z);
  d.user_data = a.user_data;
  if (a.points && !a.points.is_none()) d.points = vec3_rows(a.points, (prefix + "points").c_str());
  if (a.vertices && !a.vertices.is_none())
    d.vertices = vec3_rows(a.vertices, (prefix + "vertices").c_str());
  if (a.triangles && !a.triangles.is_none()) {
    const auto t = rows(a.triangles, 3, (prefix + "triangles").c_str());
    const auto r = t.unchecked<2>();
    for (pybind11::ssize_t i = 0; i < t.shape(0); ++i) {
      std::array<uint32_t, 3> tri{};
      for (int k = 0; k < 3; ++k) {
        const double v = r(i, k);
        // Out-of-range indices are the library's to refuse; values no uint32 holds are ours.
        if (!(v >= 0 && v <= 4294967295.0) || v != double(uint64_t(v))) {
          raise(prefix + "triangles",
                "triangle " + std::to_string(i) + ": indices must be whole numbers >= 0");
        }
        tri[std::size_t(k)] = uint32_t(v);
      }
      d.triangles.push_back(tri);
    }
  }
  if (a.heights && !a.heights.is_none()) {
    pybind11::array_t<double> h;
    try {
      h = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>::ensure(
          a.heights);
    } catch (const pybind11::error_already_set&) {
    }
    if (!h || h.ndim() != 2) {
      PyErr_Clear();
      raise(prefix + "heights", "expected a 2-dimensional array (rows, columns) of heights");
    }
    d.columns = uint32_t(h.shape(1));
    const double* p = h.data();
    d.heights.assign(p, p + h.size());
  }
  if (a.children && !a.children.is_none()) {
    if (!pybind11::isinstance<pybind11::sequence>(a.children)) {
      raise(prefix + "children", "expected a list of dicts");
    }
    std::size_t i = 0;
    for (const pybind11::handle& item : a.children) {
      const std::string p = prefix + "children[" + std::to_string(i++) + "].";
      if (!pybind11::isinstance<pybind11::dict>(item)) raise(p, "expected a dict");
      pybind11::dict kw = pybind11::reinterpret_borrow<pybind11::dict>(item);
      ShapeArgs ca;
      CompoundChild child;
      try {
        for (const auto& [key, value] : kw) {
          const std::string k = pybind11::str(key);
          if (k == "type")
            ca.type = value.cast<std::string>();
          else if (k == "radius")
            ca.radius = value.cast<double>();
          else if (k == "half_height")
            ca.half_height = value.cast<double>();
          else if (k == "half_extents")
            ca.half_extents = value.cast<V3>();
          else if (k == "points")
            ca.points = pybind11::reinterpret_borrow<pybind11::object>(value);
          else if (k == "position")
            child.position = vec3(value.cast<V3>());
          else if (k == "orientation")
            child.orientation = quat(value.cast<Q4>());
          else
            raise(p + k, "unknown key for a compound child");
        }
      } catch (const pybind11::cast_error& e) {
        throw pybind11::type_error(p + ": " + e.what());
      }
      if (ca.type.empty()) raise(p + "type", "missing");
      child.shape = make_def(ca, p);
      d.children.push_back(std::move(child));
    }
  }
  return d;
}

}  // namespace

void bind_shapes(pybind11::class_<PyWorld>& c) {
  using pybind11::arg;
  c.def(
      "create_shape",
      [](PyWorld& w, const std::string& type, double radius, double half_height, V3 half_extents,
         pybind11::object points, V3 normal, double offset, pybind11::object vertices,
         pybind11::object triangles, pybind11::object heights, double spacing_x, double spacing_z,
         pybind11::object children, uint64_t user_data) {
        World& world = w.get();
        ShapeArgs a{type,    radius,   half_height, half_extents, points,    vertices,  triangles,
                    heights, children, normal,      offset,       spacing_x, spacing_z, user_data};
        return world.create_shape(make_def(a, "shape.")).index;
      },
      arg("type"), pybind11::kw_only(), arg("radius") = 0.5, arg("half_height") = 0.5,
      arg("half_extents") = V3{0.5, 0.5, 0.5}, arg("points") = pybind11::none(),
      arg("normal") = V3{0, 1, 0}, arg("offset") = 0.0, arg("vertices") = pybind11::none(),
      arg("triangles") = pybind11::none(), arg("heights") = pybind11::none(),
      arg("spacing_x") = 1.0, arg("spacing_z") = 1.0, arg("children") = pybind11::none(),
      arg("user_data") = 0,
      "Creates a shape any number of bodies may share; returns its id (int). type: 'sphere' "
      "(radius m), 'box' (half_extents m), 'capsule' and 'cylinder' (radius, half_height m; "
      "axis local Y), 'convex_hull' (points: (n, 3) m), 'plane' (normal, offset m: the solid "
      "dot(normal, x) <= offset; static bodies only), 'mesh' (vertices (n, 3) m, triangles (m, "
      "3) indices; static only), 'heightfield' (heights (rows, columns) m, NaN for a hole, "
      "spacing_x, spacing_z m; static only), 'compound' (children: dicts with type, its "
      "parameters, position (m) and orientation (w, x, y, z)). Raises elan.Error naming the "
      "field.");
  c.def(
      "destroy_shape", [](PyWorld& w, uint32_t shape) { w.get().destroy_shape(ShapeId{shape}); },
      arg("shape"), "Destroys a shape no body uses (elan.Error 'shape' otherwise).");
  c.def(
      "is_valid_shape",
      [](const PyWorld& w, uint32_t shape) { return w.get().is_valid(ShapeId{shape}); },
      arg("shape"));
  c.def(
      "shape_type",
      [](const PyWorld& w, uint32_t shape) {
        return std::string(shape_type_name(w.get().shape_def(ShapeId{shape}).type));
      },
      arg("shape"), "The shape's type name ('sphere', 'box', ...).");
  c.def(
      "shape_user_data",
      [](const PyWorld& w, uint32_t shape) { return w.get().user_data(ShapeId{shape}); },
      arg("shape"));
  c.def(
      "set_shape_user_data",
      [](PyWorld& w, uint32_t shape, uint64_t v) { w.get().set_user_data(ShapeId{shape}, v); },
      arg("shape"), arg("value"));
}

}  // namespace elan::py
