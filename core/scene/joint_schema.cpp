// SPDX-License-Identifier: MIT
// The scene file's joints, validated field by field into JointDefs.
#include "core/scene/joint_schema.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace elan::detail::scene_file {
namespace {

// The hinge and cone angle bounds are compared as Real, as the World compares them, so that a
// file the parser passes is one the World accepts (Real(pi) rounds up in float).
const Real kPi = Real(3.14159265358979323846);

// A body reference: an index into the scene's bodies (generated ones included), a body name, or
// null for the static world (-1).
int body_ref(const Ctx& ctx, const Json& v, const std::string& field, const BodyRefs& refs) {
  if (v.is_null()) return -1;
  if (v.is_string()) {
    const std::string name = v.get<std::string>();
    const auto it = refs.names.find(name);
    if (it == refs.names.end()) fail(ctx, field, "no body named \"" + name + "\"");
    return int(it->second);
  }
  if (!v.is_number()) {
    fail(ctx, field, "expected a body index, a body name or null, got " + show(v));
  }
  const int64_t i = to_int(ctx, v, field, 0, INT64_MAX);
  if (uint64_t(i) >= refs.bodies.size()) {
    fail(ctx, field,
         "no body " + std::to_string(i) + " (the scene has " + std::to_string(refs.bodies.size()) +
             " bodies, generated ones included)");
  }
  return int(i);
}

std::string describe(int body, const BodyRefs& refs) {
  if (body < 0) return "the world is static";
  const SceneBody& b = refs.bodies[std::size_t(body)];
  const char* motion = b.body.motion == MotionType::Static ? "static" : "kinematic";
  std::string s = "body " + std::to_string(body);
  if (!b.name.empty()) s += " (\"" + b.name + "\")";
  return s + " is " + motion;
}

Vec3 unit_axis(const Ctx& ctx, const Json& j, const std::string& field) {
  const Vec3 v = to_vec3(ctx, j, field);
  const double x = double(v.x()), y = double(v.y()), z = double(v.z());
  const double n = std::sqrt(x * x + y * y + z * z);
  if (!(n > 0)) fail(ctx, field, "zero axis");
  return Vec3(Real(x / n), Real(y / n), Real(z / n));
}

// [lo, hi] with lo <= hi; angles also within [-pi, pi].
JointLimits parse_limits(const Ctx& ctx, const Json& j, const std::string& field, bool angles) {
  array_of(ctx, j, field, 2);
  JointLimits l;
  l.enabled = true;
  l.lower = to_real(ctx, j[0], field + "[0]");
  l.upper = to_real(ctx, j[1], field + "[1]");
  if (angles) {
    for (int i = 0; i < 2; ++i) {
      const Real v = i == 0 ? l.lower : l.upper;
      if (!(v >= -kPi && v <= kPi)) {
        fail(ctx, field + "[" + std::to_string(i) + "]",
             "must be in [-pi, pi] rad, got " + show(j[i]));
      }
    }
  }
  if (l.lower > l.upper) {
    fail(ctx, field, "lo > hi: " + show(j[0]) + " is above " + show(j[1]));
  }
  return l;
}

// Hinge: {speed, max_torque}; slider: {speed, max_force}. The library's max_force is either.
JointMotor parse_motor(const Ctx& ctx, const Json& j, const char* force_key, const char* what) {
  object_of(ctx, j, "motor");
  check_keys(ctx, j, {"speed", force_key}, "motor.", what);
  JointMotor m;
  m.enabled = true;
  if (const auto it = j.find("speed"); it != j.end()) m.speed = to_real(ctx, *it, "motor.speed");
  const std::string force = std::string("motor.") + force_key;
  m.max_force = non_negative(ctx, require(ctx, j, force_key, force), force);
  return m;
}

// Hinge and slider: {frequency, damping_ratio, target}; distance: {frequency, damping_ratio,
// rest_length}, the rest length also allowed beside the spring.
JointSpring parse_spring(const Ctx& ctx, const Json& j, bool distance) {
  object_of(ctx, j, "spring");
  if (distance) {
    check_keys(ctx, j, {"frequency", "damping_ratio", "rest_length"}, "spring.",
               "a distance spring");
  } else {
    check_keys(ctx, j, {"frequency", "damping_ratio", "target"}, "spring.", "a spring");
  }
  JointSpring s;
  s.enabled = true;
  s.frequency = positive(ctx, require(ctx, j, "frequency", "spring.frequency"), "spring.frequency");
  if (const auto it = j.find("damping_ratio"); it != j.end()) {
    s.damping_ratio = non_negative(ctx, *it, "spring.damping_ratio");
  }
  if (const auto it = j.find("target"); it != j.end()) {
    s.target = to_real(ctx, *it, "spring.target");
  }
  return s;
}

const Json* find(const Json& j, const char* key) {
  const auto it = j.find(key);
  return it == j.end() ? nullptr : &*it;
}

}  // namespace

namespace {

// A joint type of the file: its name, its JointType and the keys it takes (those every joint
// takes first).
struct JointKind {
  const char* name;
  JointType type;
  std::vector<const char*> keys;
};

const std::vector<JointKind>& joint_kinds() {
  static const std::vector<JointKind> kinds = [] {
    const std::vector<const char*> common = {"type",
                                             "name",
                                             "bodies",
                                             "collide_connected",
                                             "break_force",
                                             "constraint_hertz",
                                             "constraint_damping_ratio"};
    std::vector<JointKind> out = {
        {"ball", JointType::Ball, {"anchor", "friction"}},
        {"hinge", JointType::Hinge, {"anchor", "axis", "limits", "motor", "spring", "friction"}},
        {"slider", JointType::Slider, {"anchor", "axis", "limits", "motor", "spring", "friction"}},
        {"fixed", JointType::Fixed, {"anchor"}},
        {"distance",
         JointType::Distance,
         {"anchors", "min_length", "max_length", "spring", "rest_length"}},
        {"cone", JointType::Cone, {"anchor", "axis", "swing_limit", "twist_limits", "friction"}},
    };
    for (JointKind& k : out) k.keys.insert(k.keys.begin(), common.begin(), common.end());
    return out;
  }();
  return kinds;
}

}  // namespace

SceneJoint parse_joint(const Ctx& ctx, const Json& j, const BodyRefs& refs) {
  object_of(ctx, j, "");
  const std::string type = to_string(ctx, require(ctx, j, "type", "type"), "type");
  SceneJoint out;
  JointDef& d = out.def;
  const JointKind* kind = nullptr;
  for (const JointKind& k : joint_kinds()) kind = type == k.name ? &k : kind;
  if (!kind) {
    fail(ctx, "type",
         "unknown joint type \"" + type +
             "\" (allowed: ball, hinge, slider, fixed, distance, cone)");
  }
  check_keys(ctx, j, kind->keys, "", std::string("a ") + kind->name + " joint");
  d.type = kind->type;
  if (const Json* v = find(j, "name")) out.name = to_string(ctx, *v, "name");

  const Json& bodies = require(ctx, j, "bodies", "bodies");
  if (!bodies.is_array() || bodies.size() != 2) {
    fail(ctx, "bodies",
         "expected two bodies [first, second] (each an index, a name or null), got " +
             (bodies.is_array() ? std::to_string(bodies.size()) + " elements" : show(bodies)));
  }
  int a = body_ref(ctx, bodies[0], "bodies[0]", refs);
  int b = body_ref(ctx, bodies[1], "bodies[1]", refs);
  if (a == b) {
    fail(ctx, "bodies",
         a < 0 ? std::string("both are the world (null)")
               : "the same body twice (body " + std::to_string(a) + ")");
  }
  const auto dynamic = [&](int i) {
    return i >= 0 && refs.bodies[std::size_t(i)].body.motion == MotionType::Dynamic;
  };
  if (!dynamic(a) && !dynamic(b)) {
    fail(
        ctx, "bodies",
        "at least one body must be dynamic (" + describe(a, refs) + ", " + describe(b, refs) + ")");
  }
  // The library's body B may be the world, A may not: a file that gives the world first has
  // its bodies swapped, and the coordinate's sign with them (below).
  const bool swapped = a < 0;
  if (swapped) std::swap(a, b);
  out.body_a = a;
  out.body_b = b;

  if (const Json* v = find(j, "anchor")) {
    d.anchor = to_vec3(ctx, *v, "anchor");
  } else if (d.type == JointType::Fixed) {
    d.has_anchor = false;
  } else if (d.type == JointType::Slider) {
    // With the relative orientation held, any point of the first body serves as the anchor.
    d.anchor = refs.bodies[std::size_t(a)].body.position;
  } else if (d.type != JointType::Distance) {
    require(ctx, j, "anchor", "anchor");
  }
  if (d.type == JointType::Hinge || d.type == JointType::Slider || d.type == JointType::Cone) {
    d.axis = unit_axis(ctx, require(ctx, j, "axis", "axis"), "axis");
  }
  if (d.type == JointType::Hinge || d.type == JointType::Slider) {
    const bool hinge = d.type == JointType::Hinge;
    if (const Json* v = find(j, "limits")) d.limits = parse_limits(ctx, *v, "limits", hinge);
    if (const Json* v = find(j, "motor")) {
      d.motor = hinge ? parse_motor(ctx, *v, "max_torque", "a hinge motor")
                      : parse_motor(ctx, *v, "max_force", "a slider motor");
    }
    if (const Json* v = find(j, "spring")) d.spring = parse_spring(ctx, *v, false);
  }
  if (d.type == JointType::Cone) {
    if (const Json* v = find(j, "swing_limit")) {
      d.swing_limit = to_real(ctx, *v, "swing_limit");
      if (!(d.swing_limit >= 0 && d.swing_limit <= kPi)) {
        fail(ctx, "swing_limit", "must be in [0, pi] rad, got " + show(*v));
      }
    }
    if (const Json* v = find(j, "twist_limits")) {
      d.limits = parse_limits(ctx, *v, "twist_limits", true);
    }
  }
  if (d.type == JointType::Distance) {
    const Json& anchors = require(ctx, j, "anchors", "anchors");
    if (!anchors.is_array() || anchors.size() != 2) {
      fail(ctx, "anchors",
           "expected two points [[x, y, z], [x, y, z]], got " +
               (anchors.is_array() ? std::to_string(anchors.size()) + " elements" : show(anchors)));
    }
    d.anchor = to_vec3(ctx, anchors[0], "anchors[0]");
    d.anchor_b = to_vec3(ctx, anchors[1], "anchors[1]");
    const Json* min = find(j, "min_length");
    const Json* max = find(j, "max_length");
    if (min) d.min_length = non_negative(ctx, *min, "min_length");
    if (max) d.max_length = non_negative(ctx, *max, "max_length");
    // An absent length is the distance at load (the library's negative length).
    const Real load = (d.anchor_b - d.anchor).norm();
    if (min && max && d.min_length > d.max_length) {
      fail(ctx, "min_length", "min_length " + show(*min) + " is above max_length " + show(*max));
    }
    if (min && !max && d.min_length > load) {
      fail(ctx, "min_length",
           "min_length " + show(*min) + " is above the distance at load, " + show(double(load)) +
               " (the default max_length)");
    }
    if (max && !min && d.max_length < load) {
      fail(ctx, "max_length",
           "max_length " + show(*max) + " is below the distance at load, " + show(double(load)) +
               " (the default min_length)");
    }
    const Json* spring = find(j, "spring");
    if (spring) d.spring = parse_spring(ctx, *spring, true);
    const Json* rest = find(j, "rest_length");
    const Json* inner_rest = spring ? find(*spring, "rest_length") : nullptr;
    if (rest && inner_rest) {
      fail(ctx, "rest_length", "given twice, beside the spring and in it (spring.rest_length)");
    }
    d.spring.target = Real(-1);  // the distance at load
    if (rest) d.spring.target = non_negative(ctx, *rest, "rest_length");
    if (inner_rest) d.spring.target = non_negative(ctx, *inner_rest, "spring.rest_length");
  }
  if (const Json* v = find(j, "collide_connected")) {
    d.collide_connected = to_bool(ctx, *v, "collide_connected");
  }
  if (const Json* v = find(j, "break_force")) d.break_force = positive(ctx, *v, "break_force");
  if (const Json* v = find(j, "friction")) d.friction = non_negative(ctx, *v, "friction");
  if (const Json* v = find(j, "constraint_hertz")) {
    d.constraint_hertz = non_negative(ctx, *v, "constraint_hertz");
  }
  if (const Json* v = find(j, "constraint_damping_ratio")) {
    d.constraint_damping_ratio = non_negative(ctx, *v, "constraint_damping_ratio");
  }

  if (swapped) {
    // The coordinate of the world relative to the body is minus that of the body relative to
    // the world.
    if (d.limits.enabled) d.limits = {true, -d.limits.upper, -d.limits.lower};
    if (d.motor.enabled) d.motor.speed = -d.motor.speed;
    if (d.spring.enabled && d.type != JointType::Distance) d.spring.target = -d.spring.target;
    if (d.type == JointType::Distance) std::swap(d.anchor, d.anchor_b);
  }
  return out;
}

std::string joint_where(std::size_t index, const std::string& name) {
  std::string w = "joint " + std::to_string(index);
  if (!name.empty()) w += " (\"" + name + "\")";
  return w;
}

std::string scene_field(JointType type, const std::string& f) {
  if (f == "body_a" || f == "body_b") return "bodies";
  if (type == JointType::Hinge && f == "motor.max_force") return "motor.max_torque";
  if (type == JointType::Cone && f.rfind("limits", 0) == 0) return "twist_" + f;
  if (type == JointType::Distance) {
    if (f == "anchor") return "anchors[0]";
    if (f == "anchor_b") return "anchors[1]";
    if (f == "spring.target") return "rest_length";
  }
  return f;
}

}  // namespace elan::detail::scene_file
