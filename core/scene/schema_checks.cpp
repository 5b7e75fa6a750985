// SPDX-License-Identifier: MIT
// The scene file's schema checks: typed reads of JSON values with one-line messages.
#include "core/scene/schema_checks.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "elan/scene.hpp"

namespace elan::detail::scene_file {

[[noreturn]] void fail(const Ctx& ctx, const std::string& field, const std::string& message) {
  std::string s = ctx.file + ": ";
  if (!ctx.where.empty()) s += ctx.where + ": ";
  if (!field.empty()) s += ctx.prefix + field + ": ";
  s += message;
  throw SceneError(s, field.empty() ? std::string() : ctx.prefix + field);
}

// A short rendering of a value for "got ..." (containers by kind only: they may be huge).
std::string show(const Json& j) {
  if (j.is_array() || j.is_object()) return kind(j);
  std::string s = j.dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

std::string show(double v) {
  std::ostringstream os;
  os.precision(9);
  os << v;
  return os.str();
}

void check_keys(const Ctx& ctx, const Json& obj, std::span<const char* const> allowed,
                const std::string& field_prefix, const std::string& what) {
  for (const auto& item : obj.items()) {
    bool known = false;
    for (const char* a : allowed) known = known || item.key() == a;
    if (!known) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      fail(ctx, field_prefix + item.key(), "unknown key for " + what + " (allowed: " + list + ")");
    }
  }
}

const Json& require(const Ctx& ctx, const Json& obj, const std::string& key,
                    const std::string& field) {
  const auto it = obj.find(key);
  if (it == obj.end()) fail(ctx, field, "missing");
  return *it;
}

Real to_real(const Ctx& ctx, const Json& j, const std::string& field) {
  if (!j.is_number()) fail(ctx, field, "expected a number, got " + show(j));
  const double d = j.get<double>();
  const Real r = static_cast<Real>(d);
  // JSON has no NaN or infinity; a finite double can still overflow a float.
  if (!std::isfinite(r)) fail(ctx, field, "not a finite number: " + show(j));
  return r;
}

Real positive(const Ctx& ctx, const Json& j, const std::string& field) {
  const Real r = to_real(ctx, j, field);
  if (!(r > 0)) fail(ctx, field, "must be positive, got " + show(j));
  return r;
}

Real non_negative(const Ctx& ctx, const Json& j, const std::string& field) {
  const Real r = to_real(ctx, j, field);
  if (r < 0) fail(ctx, field, "must not be negative, got " + show(j));
  return r;
}

int64_t to_int(const Ctx& ctx, const Json& j, const std::string& field, int64_t lo, int64_t hi) {
  int64_t v = 0;
  if (j.is_number_integer()) {
    if (j.is_number_unsigned() && j.get<uint64_t>() > uint64_t(INT64_MAX)) {
      fail(ctx, field, "must be at most " + std::to_string(hi) + ", got " + show(j));
    }
    v = j.get<int64_t>();
  } else if (j.is_number_float() && std::floor(j.get<double>()) == j.get<double>() &&
             std::fabs(j.get<double>()) < 9e18) {
    v = static_cast<int64_t>(j.get<double>());
  } else {
    fail(ctx, field, "expected an integer, got " + show(j));
  }
  if (v < lo) fail(ctx, field, "must be at least " + std::to_string(lo) + ", got " + show(j));
  if (v > hi) fail(ctx, field, "must be at most " + std::to_string(hi) + ", got " + show(j));
  return v;
}

const Json& array_of(const Ctx& ctx, const Json& j, const std::string& field, std::size_t n) {
  if (!j.is_array())
    fail(ctx, field, "expected an array of " + std::to_string(n) + " numbers, got " + show(j));
  if (j.size() != n) {
    fail(ctx, field, "expected " + std::to_string(n) + " numbers, got " + std::to_string(j.size()));
  }
  return j;
}

Vec3 to_vec3(const Ctx& ctx, const Json& j, const std::string& field) {
  array_of(ctx, j, field, 3);
  Vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = to_real(ctx, j[i], field + "[" + std::to_string(i) + "]");
  return v;
}

// Quaternions are written [w, x, y, z] and normalised here (in double, so a float scene loses
// nothing before the final rounding).
Quat to_quat(const Ctx& ctx, const Json& j, const std::string& field) {
  array_of(ctx, j, field, 4);
  double q[4];
  for (int i = 0; i < 4; ++i) {
    q[i] = double(to_real(ctx, j[i], field + "[" + std::to_string(i) + "]"));
  }
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(norm > 0) || !std::isfinite(norm)) fail(ctx, field, "zero quaternion");
  return Quat(Real(q[0] / norm), Real(q[1] / norm), Real(q[2] / norm), Real(q[3] / norm));
}

std::string to_string(const Ctx& ctx, const Json& j, const std::string& field) {
  if (!j.is_string()) fail(ctx, field, "expected a string, got " + show(j));
  return j.get<std::string>();
}

bool to_bool(const Ctx& ctx, const Json& j, const std::string& field) {
  if (!j.is_boolean()) fail(ctx, field, "expected true or false, got " + show(j));
  return j.get<bool>();
}

const Json& object_of(const Ctx& ctx, const Json& j, const std::string& field) {
  if (!j.is_object()) fail(ctx, field, "expected an object, got " + show(j));
  return j;
}

}  // namespace elan::detail::scene_file
