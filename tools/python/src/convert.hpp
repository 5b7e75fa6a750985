// SPDX-License-Identifier: MIT
// Conversions between Python values and the engine's types: ids as ints, vectors as 3-tuples,
// quaternions as (w, x, y, z) like the scene file, arrays of n rows checked with elan.Error.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "elan/ids.hpp"
#include "elan/joints.hpp"
#include "elan/math.hpp"
#include "elan/queries.hpp"

namespace elan::py {

using V3 = std::array<double, 3>;
using Q4 = std::array<double, 4>;  ///< w, x, y, z (the scene file's order)

/// Body and joint ids are ints: generation << 32 | slot (a stale id stays distinct from the id
/// that reuses its slot). A null id is None in Python, -1 in arrays.
inline uint64_t to_int(BodyId id) {
  return uint64_t(id.generation) << 32 | id.slot;
}
inline uint64_t to_int(JointId id) {
  return uint64_t(id.generation) << 32 | id.slot;
}
inline BodyId body_id(uint64_t v) {
  return BodyId{uint32_t(v), uint32_t(v >> 32)};
}
inline JointId joint_id(uint64_t v) {
  return JointId{uint32_t(v), uint32_t(v >> 32)};
}
/// Engine byte buffers (snapshots, rollback states, recordings) as Python bytes.
inline pybind11::bytes to_bytes(const std::vector<uint8_t>& v) {
  return pybind11::bytes(reinterpret_cast<const char*>(v.data()), v.size());
}
inline int64_t to_array_int(BodyId id) {
  return id.is_null() ? -1 : int64_t(to_int(id));
}
/// The id, or None for a null one.
pybind11::object body_or_none(BodyId id);

inline Vec3 vec3(const V3& v) {
  return Vec3(Real(v[0]), Real(v[1]), Real(v[2]));
}
inline Quat quat(const Q4& q) {
  return Quat(Real(q[0]), Real(q[1]), Real(q[2]), Real(q[3]));
}
inline pybind11::tuple tuple3(const Vec3& v) {
  return pybind11::make_tuple(double(v.x()), double(v.y()), double(v.z()));
}
inline pybind11::tuple tuple4(const Quat& q) {
  return pybind11::make_tuple(double(q.w()), double(q.x()), double(q.y()), double(q.z()));
}

/// A float64 C-contiguous copy of `values` with `columns` columns (0: one dimension), n rows;
/// elan.Error `field` when it is not a numeric array of that shape.
pybind11::array_t<double> rows(const pybind11::handle& values, std::size_t columns,
                               const char* field);
/// The rows of an (n, 3) array as vectors.
std::vector<Vec3> vec3_rows(const pybind11::handle& values, const char* field);

/// The query filter of the keyword arguments category_bits, mask_bits, include_sensors.
QueryFilter filter(uint32_t category_bits, uint32_t mask_bits, bool include_sensors);

/// One field of a NumPy structured dtype laid over a C++ struct.
struct Field {
  const char* name;
  std::size_t offset;
  const char* format;  ///< NumPy type string, e.g. "<i8", "<f4", "(3,)<f4"
};
/// The dtype of `fields` at their offsets in a record of `itemsize` bytes.
pybind11::dtype record_dtype(const std::vector<Field>& fields, std::size_t itemsize);
/// NumPy type string of Real ("<f4" or "<f8"), and of three of them.
const char* real_format();
const char* real3_format();

}  // namespace elan::py
