// Scene files: JSON parsing with validation (every message names the file, the body and the
// field), the grid and pyramid generators, and loading into a World with identical shapes shared.
#include "elan/scene.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/base/convex_hull.hpp"
#include "core/world/world_access.hpp"

namespace elan {
namespace {

using Json = nlohmann::json;

// A generator typo such as a count of [100000, 100000, 100000] must fail at once with a message,
// not exhaust memory over minutes.
constexpr uint64_t kMaxBodies = 10'000'000;
constexpr int kMaxSolverCount = 10'000;  // substeps, iterations
// Scene files are a few levels deep; a cap keeps pathological nesting from costing stack later.
constexpr std::size_t kMaxDepth = 64;

// Builds the DOM like nlohmann's own parser, but also rejects duplicate keys (which nlohmann
// would silently overwrite) and keeps the byte position of any error, overflow included.
class SceneSax {
 public:
  Json root;
  std::string error;  // empty when the text parsed
  std::size_t error_position = 0;

  bool null() { return put(Json(nullptr)); }
  bool boolean(bool v) { return put(Json(v)); }
  bool number_integer(Json::number_integer_t v) { return put(Json(v)); }
  bool number_unsigned(Json::number_unsigned_t v) { return put(Json(v)); }
  bool number_float(Json::number_float_t v, const std::string&) { return put(Json(v)); }
  bool string(std::string& v) { return put(Json(std::move(v))); }
  bool binary(Json::binary_t& v) { return put(Json::binary(std::move(v))); }
  bool start_object(std::size_t) { return open(Json::object()); }
  bool start_array(std::size_t) { return open(Json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(std::string& k) {
    Frame& top = stack_.back();
    if (!top.keys.insert(k).second) {
      error = path() + (stack_.size() > 1 ? "." : "") + k + ": duplicate key";
      return false;
    }
    member_ = &(*top.value)[k];
    top.member = k;
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) {
    error_position = position;
    // nlohmann's text is "[json.exception.parse_error.101] parse error at line 1, column 5: ..."
    std::string what = e.what();
    const std::size_t bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    const std::size_t column = what.find("column ");
    const std::size_t colon = column == std::string::npos ? column : what.find(": ", column);
    if (colon != std::string::npos) what = what.substr(colon + 2);
    std::string at = path();
    const std::string next = next_name();
    if (!next.empty()) at += (at.empty() || next[0] == '[' ? "" : ".") + next;
    error = "malformed JSON" + (at.empty() ? "" : " at " + at) + ": " + what;
    return false;
  }

 private:
  struct Frame {
    Json* value;
    std::string name;  // key or [index] that leads to this container, for messages
    std::set<std::string> keys;
    std::string member;  // the key being read, in an object
  };
  std::vector<Frame> stack_;
  Json* member_ = nullptr;

  std::string next_name() const {
    if (stack_.empty()) return "";
    const Json& top = *stack_.back().value;
    return top.is_array() ? "[" + std::to_string(top.size()) + "]" : stack_.back().member;
  }
  Json* place(Json&& v) {
    if (stack_.empty()) {
      root = std::move(v);
      return &root;
    }
    // Pointers to open containers stay valid: an open container is the last element of its
    // parent array (which grows only after it closes) or a std::map node.
    Json& top = *stack_.back().value;
    if (top.is_array()) {
      top.push_back(std::move(v));
      return &top.back();
    }
    *member_ = std::move(v);
    return member_;
  }
  bool put(Json&& v) {
    place(std::move(v));
    return true;
  }
  bool open(Json&& v) {
    if (stack_.size() >= kMaxDepth) {
      error = path() + ": nesting deeper than " + std::to_string(kMaxDepth) + " levels";
      return false;
    }
    std::string name = next_name();
    stack_.push_back(Frame{place(std::move(v)), std::move(name), {}, {}});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }
  std::string path() const {
    std::string p;
    for (std::size_t i = 1; i < stack_.size(); ++i) {
      const std::string& n = stack_[i].name;
      if (!p.empty() && n[0] != '[') p += '.';
      p += n;
    }
    return p;
  }
};

// Where a value sits: the file, the body or generator, and a field prefix ("body." inside a
// grid's template body).
struct Ctx {
  const std::string& file;
  std::string where;
  std::string prefix;
};

[[noreturn]] void fail(const Ctx& ctx, const std::string& field, const std::string& message) {
  std::string s = ctx.file + ": ";
  if (!ctx.where.empty()) s += ctx.where + ": ";
  if (!field.empty()) s += ctx.prefix + field + ": ";
  s += message;
  throw SceneError(s);
}

std::string kind(const Json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_array()) return "an array";
  return "an object";
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

void check_keys(const Ctx& ctx, const Json& obj, std::initializer_list<const char*> allowed,
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

ShapeDef parse_shape(const Ctx& ctx, const Json& j) {
  object_of(ctx, j, "shape");
  const std::string type = to_string(ctx, require(ctx, j, "type", "shape.type"), "shape.type");
  ShapeDef s;
  auto get = [&](const char* key) -> const Json& {
    return require(ctx, j, key, std::string("shape.") + key);
  };
  auto field = [](const char* key) { return std::string("shape.") + key; };
  if (type == "sphere") {
    check_keys(ctx, j, {"type", "radius"}, "shape.", "a sphere");
    s.type = ShapeType::Sphere;
    s.radius = positive(ctx, get("radius"), field("radius"));
  } else if (type == "box") {
    check_keys(ctx, j, {"type", "half_extents"}, "shape.", "a box");
    s.type = ShapeType::Box;
    s.half_extents = to_vec3(ctx, get("half_extents"), field("half_extents"));
    for (int i = 0; i < 3; ++i) {
      if (!(s.half_extents[i] > 0)) {
        fail(ctx, field("half_extents") + "[" + std::to_string(i) + "]",
             "must be positive, got " + show(double(s.half_extents[i])));
      }
    }
  } else if (type == "capsule" || type == "cylinder") {
    check_keys(ctx, j, {"type", "radius", "half_height"}, "shape.",
               type == "capsule" ? "a capsule" : "a cylinder");
    s.type = type == "capsule" ? ShapeType::Capsule : ShapeType::Cylinder;
    s.radius = positive(ctx, get("radius"), field("radius"));
    s.half_height = positive(ctx, get("half_height"), field("half_height"));
  } else if (type == "convex_hull") {
    check_keys(ctx, j, {"type", "points"}, "shape.", "a convex_hull");
    s.type = ShapeType::ConvexHull;
    const Json& points = get("points");
    if (!points.is_array())
      fail(ctx, field("points"), "expected an array of [x, y, z], got " + show(points));
    if (points.size() < 4) {
      fail(ctx, field("points"),
           "a hull needs at least 4 points, got " + std::to_string(points.size()));
    }
    s.points.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      s.points.push_back(to_vec3(ctx, points[i], field("points") + "[" + std::to_string(i) + "]"));
    }
    try {
      detail::build_convex_hull(s.points);
    } catch (const Error& e) {
      const std::string what = e.what();
      const std::size_t skip = e.field().empty() ? 0 : e.field().size() + 2;
      fail(ctx, field("points"), "degenerate hull: " + what.substr(std::min(skip, what.size())));
    }
  } else if (type == "plane") {
    check_keys(ctx, j, {"type", "normal", "offset"}, "shape.", "a plane");
    s.type = ShapeType::Plane;
    s.normal = to_vec3(ctx, get("normal"), field("normal"));
    if (s.normal.squaredNorm() == 0) fail(ctx, field("normal"), "zero normal");
    const auto it = j.find("offset");
    s.offset = it == j.end() ? Real(0) : to_real(ctx, *it, field("offset"));
  } else {
    fail(ctx, "shape.type",
         "unknown shape type \"" + type +
             "\" (allowed: sphere, box, capsule, cylinder, convex_hull, plane)");
  }
  return s;
}

SceneBody parse_body(const Ctx& ctx, const Json& j) {
  object_of(ctx, j, "");
  check_keys(ctx, j,
             {"name", "motion", "shape", "position", "orientation", "linear_velocity",
              "angular_velocity", "mass", "density", "friction", "restitution", "linear_damping",
              "angular_damping", "category_bits", "mask_bits", "awake"},
             "", "a body");
  SceneBody b;
  if (const auto it = j.find("name"); it != j.end()) b.name = to_string(ctx, *it, "name");
  BodyDef& d = b.body;
  if (const auto it = j.find("motion"); it != j.end()) {
    const std::string m = to_string(ctx, *it, "motion");
    if (m == "static") {
      d.motion = MotionType::Static;
    } else if (m == "dynamic") {
      d.motion = MotionType::Dynamic;
    } else if (m == "kinematic") {
      d.motion = MotionType::Kinematic;
    } else {
      fail(ctx, "motion", "unknown motion \"" + m + "\" (allowed: static, dynamic, kinematic)");
    }
  }
  b.shape = parse_shape(ctx, require(ctx, j, "shape", "shape"));
  if (b.shape.type == ShapeType::Plane && d.motion != MotionType::Static) {
    fail(ctx, "motion", "a plane must be static");
  }
  auto opt = [&](const char* key) -> const Json* {
    const auto it = j.find(key);
    return it == j.end() ? nullptr : &*it;
  };
  if (const Json* v = opt("position")) d.position = to_vec3(ctx, *v, "position");
  if (const Json* v = opt("orientation")) d.orientation = to_quat(ctx, *v, "orientation");
  if (const Json* v = opt("linear_velocity"))
    d.linear_velocity = to_vec3(ctx, *v, "linear_velocity");
  if (const Json* v = opt("angular_velocity")) {
    d.angular_velocity = to_vec3(ctx, *v, "angular_velocity");
  }
  const Json* mass = opt("mass");
  const Json* density = opt("density");
  if (mass && density) fail(ctx, "mass", "give either mass or density, not both");
  if (mass) d.mass = positive(ctx, *mass, "mass");
  if (density) d.density = positive(ctx, *density, "density");
  if (const Json* v = opt("friction")) d.friction = non_negative(ctx, *v, "friction");
  if (const Json* v = opt("restitution")) d.restitution = non_negative(ctx, *v, "restitution");
  if (const Json* v = opt("linear_damping"))
    d.linear_damping = non_negative(ctx, *v, "linear_damping");
  if (const Json* v = opt("angular_damping")) {
    d.angular_damping = non_negative(ctx, *v, "angular_damping");
  }
  if (const Json* v = opt("category_bits")) {
    d.category_bits = uint32_t(to_int(ctx, *v, "category_bits", 0, UINT32_MAX));
  }
  if (const Json* v = opt("mask_bits"))
    d.mask_bits = uint32_t(to_int(ctx, *v, "mask_bits", 0, UINT32_MAX));
  if (const Json* v = opt("awake")) d.awake = to_bool(ctx, *v, "awake");
  return b;
}

std::string body_where(std::size_t index, const std::string& name) {
  std::string w = "body " + std::to_string(index);
  if (!name.empty()) w += " (\"" + name + "\")";
  return w;
}

// A validated generator, expanded only once the total body count is known to be sane.
struct Generator {
  bool pyramid = false;
  int64_t count[3] = {1, 1, 1};  // grid
  Vec3 spacing = Vec3::Zero();   // m, grid
  SceneBody body;                // grid template
  int64_t base = 1;              // pyramid
  Real half_extent = Real(0.5);  // m, pyramid cube
  Vec3 origin = Vec3::Zero();    // m
  uint64_t bodies = 0;
};

Generator parse_generator(const Ctx& ctx, const Json& j) {
  object_of(ctx, j, "");
  const std::string type = to_string(ctx, require(ctx, j, "type", "type"), "type");
  Generator g;
  if (type == "grid") {
    check_keys(ctx, j, {"type", "count", "spacing", "origin", "body"}, "", "a grid generator");
    const Json& count = array_of(ctx, require(ctx, j, "count", "count"), "count", 3);
    uint64_t total = 1;
    for (int i = 0; i < 3; ++i) {
      g.count[i] = to_int(ctx, count[i], "count[" + std::to_string(i) + "]", 1, kMaxBodies);
      total *= uint64_t(g.count[i]);
      if (total > kMaxBodies) {
        fail(ctx, "count",
             "too many bodies: at most " + std::to_string(kMaxBodies) + " bodies are allowed");
      }
    }
    g.bodies = total;
    g.spacing = to_vec3(ctx, require(ctx, j, "spacing", "spacing"), "spacing");
    const Ctx body_ctx{ctx.file, ctx.where, "body."};
    g.body = parse_body(body_ctx, require(ctx, j, "body", "body"));
    if (!g.body.name.empty()) {
      fail(body_ctx, "name", "generated bodies cannot be named (names must be unique)");
    }
  } else if (type == "pyramid") {
    check_keys(ctx, j, {"type", "base", "half_extent", "origin"}, "", "a pyramid generator");
    // base(base+1)(2 base+1)/6 <= kMaxBodies needs base <= 310; 10^6 keeps the product exact.
    g.base = to_int(ctx, require(ctx, j, "base", "base"), "base", 1, 1'000'000);
    g.pyramid = true;
    g.bodies = uint64_t(g.base) * uint64_t(g.base + 1) * uint64_t(2 * g.base + 1) / 6;
    if (g.bodies > kMaxBodies) {
      fail(ctx, "base",
           "too many bodies: a pyramid of base " + std::to_string(g.base) + " has " +
               std::to_string(g.bodies) + " cubes, at most " + std::to_string(kMaxBodies) +
               " bodies are allowed");
    }
    if (const auto it = j.find("half_extent"); it != j.end()) {
      g.half_extent = positive(ctx, *it, "half_extent");
    }
  } else {
    fail(ctx, "type", "unknown generator type \"" + type + "\" (allowed: grid, pyramid)");
  }
  if (const auto it = j.find("origin"); it != j.end()) g.origin = to_vec3(ctx, *it, "origin");
  return g;
}

// Positions are computed in double and rounded once, so a pyramid's cubes touch exactly as far
// as Real can say.
void expand(const Generator& g, std::vector<SceneBody>& out) {
  const Vec3& o = g.origin;
  if (!g.pyramid) {
    for (int64_t k = 0; k < g.count[2]; ++k) {
      for (int64_t j = 0; j < g.count[1]; ++j) {
        for (int64_t i = 0; i < g.count[0]; ++i) {
          SceneBody b = g.body;
          b.body.position = Vec3(Real(double(o.x()) + double(i) * double(g.spacing.x())),
                                 Real(double(o.y()) + double(j) * double(g.spacing.y())),
                                 Real(double(o.z()) + double(k) * double(g.spacing.z())));
          out.push_back(std::move(b));
        }
      }
    }
    return;
  }
  const double h = double(g.half_extent);
  SceneBody cube;
  cube.shape.type = ShapeType::Box;
  cube.shape.half_extents = Vec3::Constant(g.half_extent);
  for (int64_t layer = 0; layer < g.base; ++layer) {
    const int64_t n = g.base - layer;
    // Cube centres of one layer sit 2h apart, symmetric about the origin: (2i - (n-1)) h.
    for (int64_t k = 0; k < n; ++k) {
      for (int64_t i = 0; i < n; ++i) {
        SceneBody b = cube;
        b.body.position = Vec3(Real(double(o.x()) + double(2 * i - (n - 1)) * h),
                               Real(double(o.y()) + double(2 * layer + 1) * h),
                               Real(double(o.z()) + double(2 * k - (n - 1)) * h));
        out.push_back(std::move(b));
      }
    }
  }
}

Json parse_json(const std::string& text, const std::string& file) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw SceneError(file + ": empty file (expected a JSON object)");
  }
  SceneSax sax;
  const bool ok = Json::sax_parse(text, &sax, Json::input_format_t::json, true, false);
  if (!ok || !sax.error.empty()) {
    if (sax.error.rfind("malformed", 0) == 0) {
      std::size_t line = 1, column = 1;
      const std::size_t end = std::min(sax.error_position, text.size());
      for (std::size_t i = 0; i + 1 < end; ++i) {
        if (text[i] == '\n') {
          ++line;
          column = 1;
        } else {
          ++column;
        }
      }
      throw SceneError(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " +
                       sax.error);
    }
    // "bodies[3].shape.radius: ..." reads as the other messages do: "body 3: shape.radius: ...".
    std::string error = sax.error;
    if (error.rfind("bodies[", 0) == 0 && error.find("]") != std::string::npos) {
      const std::size_t close = error.find(']');
      std::string rest = error.substr(close + 1);
      if (!rest.empty() && rest[0] == '.') rest = rest.substr(1);
      error = "body " + error.substr(7, close - 7) + ": " + rest;
    }
    throw SceneError(file + ": " + error);
  }
  if (!sax.root.is_object()) {
    throw SceneError(file + ": expected a JSON object at the top level, got " + kind(sax.root));
  }
  return std::move(sax.root);
}

// The bits of the fields that matter for the shape's type: equal keys mean identical shapes.
void shape_key(const ShapeDef& s, std::string& key) {
  key.clear();
  key.push_back(char(s.type));
  auto add = [&key](const Real& r) { key.append(reinterpret_cast<const char*>(&r), sizeof r); };
  auto add3 = [&](const Vec3& v) {
    for (int i = 0; i < 3; ++i) add(v[i]);
  };
  switch (s.type) {
    case ShapeType::Sphere:
      add(s.radius);
      break;
    case ShapeType::Box:
      add3(s.half_extents);
      break;
    case ShapeType::Capsule:
    case ShapeType::Cylinder:
      add(s.radius);
      add(s.half_height);
      break;
    case ShapeType::ConvexHull:
      for (const Vec3& p : s.points) add3(p);
      break;
    case ShapeType::Plane:
      add3(s.normal);
      add(s.offset);
      break;
  }
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& file_name) {
  const Json root = parse_json(text, file_name);
  const Ctx ctx{file_name, "", ""};
  check_keys(
      ctx, root,
      {"gravity", "timestep", "substeps", "iterations", "allow_sleep", "bodies", "generators"}, "",
      "the scene");
  Scene scene;
  if (const auto it = root.find("gravity"); it != root.end()) {
    scene.world.gravity = to_vec3(ctx, *it, "gravity");
  }
  if (const auto it = root.find("timestep"); it != root.end()) {
    scene.timestep = positive(ctx, *it, "timestep");
  }
  if (const auto it = root.find("substeps"); it != root.end()) {
    scene.world.substeps = int(to_int(ctx, *it, "substeps", 1, kMaxSolverCount));
    scene.has_substeps = true;
  }
  if (const auto it = root.find("iterations"); it != root.end()) {
    scene.world.iterations = int(to_int(ctx, *it, "iterations", 1, kMaxSolverCount));
    scene.has_iterations = true;
  }
  if (const auto it = root.find("allow_sleep"); it != root.end()) {
    scene.world.allow_sleep = to_bool(ctx, *it, "allow_sleep");
  }

  static const Json kEmpty = Json::array();
  const auto bodies_it = root.find("bodies");
  const Json& bodies = bodies_it == root.end() ? kEmpty : *bodies_it;
  if (!bodies.is_array()) fail(ctx, "bodies", "expected an array of bodies, got " + show(bodies));
  const auto gens_it = root.find("generators");
  const Json& gens = gens_it == root.end() ? kEmpty : *gens_it;
  if (!gens.is_array()) fail(ctx, "generators", "expected an array, got " + show(gens));
  if (bodies.size() > kMaxBodies) {
    fail(ctx, "bodies", "too many bodies: at most " + std::to_string(kMaxBodies) + " are allowed");
  }

  // determinism: ordered map; only looked up, never iterated into results.
  std::map<std::string, std::size_t> names;
  scene.bodies.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Ctx body_ctx{file_name, body_where(i, ""), ""};
    if (bodies[i].is_object()) {
      const auto name = bodies[i].find("name");
      if (name != bodies[i].end() && name->is_string()) {
        body_ctx.where = body_where(i, name->get<std::string>());
      }
    }
    SceneBody b = parse_body(body_ctx, bodies[i]);
    if (!b.name.empty()) {
      const auto [it, inserted] = names.emplace(b.name, i);
      if (!inserted) {
        fail(body_ctx, "name",
             "duplicate name \"" + b.name + "\" (also body " + std::to_string(it->second) + ")");
      }
    }
    scene.bodies.push_back(std::move(b));
  }

  std::vector<Generator> generators;
  uint64_t total = bodies.size();
  for (std::size_t i = 0; i < gens.size(); ++i) {
    std::string where = "generator " + std::to_string(i);
    if (gens[i].is_object()) {
      const auto type = gens[i].find("type");
      if (type != gens[i].end() && type->is_string()) {
        where += " (" + type->get<std::string>() + ")";
      }
    }
    const Ctx gen_ctx{file_name, where, ""};
    generators.push_back(parse_generator(gen_ctx, gens[i]));
    total += generators.back().bodies;
    if (total > kMaxBodies) {
      fail(gen_ctx, "",
           "too many bodies: the scene would have " + std::to_string(total) + ", at most " +
               std::to_string(kMaxBodies) + " are allowed");
    }
  }
  scene.bodies.reserve(total);
  for (const Generator& g : generators) expand(g, scene.bodies);
  return scene;
}

Scene load_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open file: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path + ": cannot read file");
  return parse_scene(text.str(), path);
}

void load_into(const Scene& scene, World& world, const std::string& file_name) {
  // determinism: ordered map keyed by the shape's bytes; only looked up, and shapes are created
  // in first-use order, so ids depend on the scene alone.
  std::map<std::string, ShapeId> shapes;
  std::string key;
  // First the distinct shapes, so the world can make room for exactly what the scene adds.
  for (const SceneBody& b : scene.bodies) {
    shape_key(b.shape, key);
    shapes.emplace(key, ShapeId{});
  }
  world.reserve(world.body_count() + scene.bodies.size(),
                detail::state_of(world).shapes.size() + shapes.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const SceneBody& b = scene.bodies[i];
    const Ctx ctx{file_name, body_where(i, b.name), ""};
    shape_key(b.shape, key);
    const auto it = shapes.find(key);
    if (it->second.is_null()) {
      try {
        it->second = world.create_shape(b.shape);
      } catch (const Error& e) {
        const std::string& f = e.field();
        const std::string message =
            f.empty() ? e.what() : std::string(e.what()).substr(f.size() + 2);
        fail(ctx, f.rfind("shape", 0) == 0 ? f : "shape" + (f.empty() ? "" : "." + f), message);
      }
    }
    BodyDef def = b.body;
    def.shape = it->second;
    try {
      world.create_body(def);
    } catch (const Error& e) {
      const std::string& f = e.field();
      fail(ctx, f.empty() ? "body" : f,
           f.empty() ? e.what() : std::string(e.what()).substr(f.size() + 2));
    }
  }
}

}  // namespace elan
