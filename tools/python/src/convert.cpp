// SPDX-License-Identifier: MIT
#include "convert.hpp"

#include "errors.hpp"

namespace elan::py {

pybind11::object body_or_none(BodyId id) {
  if (id.is_null()) return pybind11::none();
  return pybind11::int_(to_int(id));
}

pybind11::array_t<double> rows(const pybind11::handle& values, std::size_t columns,
                               const char* field) {
  pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast> a;
  try {
    a = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>::ensure(
        values);
  } catch (const pybind11::error_already_set&) {
    a = {};
  }
  if (!a) {
    PyErr_Clear();
    raise(field, "expected an array of numbers");
  }
  if (columns == 0) {
    if (a.ndim() != 1) raise(field, "expected a 1-dimensional array");
  } else if (a.ndim() != 2 || std::size_t(a.shape(1)) != columns) {
    raise(field, "expected an array of shape (n, " + std::to_string(columns) + ")");
  }
  return a;
}

std::vector<Vec3> vec3_rows(const pybind11::handle& values, const char* field) {
  const auto a = rows(values, 3, field);
  const auto r = a.unchecked<2>();
  std::vector<Vec3> out(std::size_t(a.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = Vec3(Real(r(i, 0)), Real(r(i, 1)), Real(r(i, 2)));
  }
  return out;
}

QueryFilter filter(uint32_t category_bits, uint32_t mask_bits, bool include_sensors) {
  QueryFilter f;
  f.category_bits = category_bits;
  f.mask_bits = mask_bits;
  f.include_sensors = include_sensors;
  return f;
}

pybind11::dtype record_dtype(const std::vector<Field>& fields, std::size_t itemsize) {
  pybind11::list names, formats, offsets;
  for (const Field& f : fields) {
    names.append(f.name);
    formats.append(f.format);
    offsets.append(f.offset);
  }
  pybind11::dict spec;
  spec["names"] = names;
  spec["formats"] = formats;
  spec["offsets"] = offsets;
  spec["itemsize"] = itemsize;
  return pybind11::dtype::from_args(spec);
}

const char* real_format() {
  return sizeof(Real) == 4 ? "<f4" : "<f8";
}
const char* real3_format() {
  return sizeof(Real) == 4 ? "(3,)<f4" : "(3,)<f8";
}

}  // namespace elan::py
