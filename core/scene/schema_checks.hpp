// SPDX-License-Identifier: MIT
// The scene file's schema checks: typed reads of JSON values (numbers, integers in a range,
// vectors, unit quaternions, strings, booleans, objects with known keys), each failure a
// SceneError naming the file, the body and the field.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>

#include "core/scene/json_reader.hpp"
#include "elan/math.hpp"

namespace elan::detail::scene_file {

// A generator typo such as a count of [100000, 100000, 100000] must fail at once with a message,
// not exhaust memory over minutes.
inline constexpr uint64_t kMaxBodies = 10'000'000;
inline constexpr uint64_t kMaxJoints = 10'000'000;

// Where a value sits: the file, the body or generator, and a field prefix ("body." inside a
// grid's template body).
struct Ctx {
  const std::string& file;
  std::string where;
  std::string prefix;
};

// Throws the SceneError "file: where: prefix+field: message" (parts left out when empty).
[[noreturn]] void fail(const Ctx& ctx, const std::string& field, const std::string& message);

// A short rendering of a value for "got ..." (containers by kind only: they may be huge).
std::string show(const Json& j);
std::string show(double v);

// Each key of `obj` is one of `allowed`, or fail naming it (`field_prefix` + key) and `what`.
void check_keys(const Ctx& ctx, const Json& obj, std::span<const char* const> allowed,
                const std::string& field_prefix, const std::string& what);
inline void check_keys(const Ctx& ctx, const Json& obj, std::initializer_list<const char*> allowed,
                       const std::string& field_prefix, const std::string& what) {
  check_keys(ctx, obj, std::span<const char* const>(allowed.begin(), allowed.size()), field_prefix,
             what);
}
// obj[key], or fail "missing" naming `field`.
const Json& require(const Ctx& ctx, const Json& obj, const std::string& key,
                    const std::string& field);
// A number that is finite as Real; also positive, or not negative.
Real to_real(const Ctx& ctx, const Json& j, const std::string& field);
Real positive(const Ctx& ctx, const Json& j, const std::string& field);
Real non_negative(const Ctx& ctx, const Json& j, const std::string& field);
// An integer (or a float with an integer value) in [lo, hi].
int64_t to_int(const Ctx& ctx, const Json& j, const std::string& field, int64_t lo, int64_t hi);
// An array of exactly n elements.
const Json& array_of(const Ctx& ctx, const Json& j, const std::string& field, std::size_t n);
Vec3 to_vec3(const Ctx& ctx, const Json& j, const std::string& field);
// [w, x, y, z], normalised.
Quat to_quat(const Ctx& ctx, const Json& j, const std::string& field);
std::string to_string(const Ctx& ctx, const Json& j, const std::string& field);
bool to_bool(const Ctx& ctx, const Json& j, const std::string& field);
const Json& object_of(const Ctx& ctx, const Json& j, const std::string& field);

}  // namespace elan::detail::scene_file
