// SPDX-License-Identifier: MIT
// Bodies: creation with keyword arguments, every getter and setter of one body.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>

#include "convert.hpp"
#include "errors.hpp"
#include "py_world.hpp"

namespace elan::py {
namespace {

MotionType motion_type(const std::string& name, const char* field) {
  if (name == "static") return MotionType::Static;
  if (name == "kinematic") return MotionType::Kinematic;
  if (name == "dynamic") return MotionType::Dynamic;
  raise(field, "expected 'static', 'kinematic' or 'dynamic', got '" + name + "'");
}

const char* motion_name(MotionType t) {
  switch (t) {
    case MotionType::Static:
      return "static";
    case MotionType::Kinematic:
      return "kinematic";
    case MotionType::Dynamic:
      break;
  }
  return "dynamic";
}

// Binds a read-only query of one body: world.NAME(body) -> f(world, id).
template <class F>
void getter(pybind11::class_<PyWorld>& c, const char* name, F f, const char* doc) {
  c.def(
      name, [f](const PyWorld& w, uint64_t body) { return f(w.get(), body_id(body)); },
      pybind11::arg("body"), doc);
}

}  // namespace

void bind_bodies(pybind11::class_<PyWorld>& c) {
  using pybind11::arg;
  c.def(
      "create_body",
      [](PyWorld& w, uint32_t shape, const std::string& motion, V3 position, Q4 orientation,
         V3 linear_velocity, V3 angular_velocity, std::optional<double> mass, double density,
         double friction, double restitution, double linear_damping, double angular_damping,
         uint32_t category_bits, uint32_t mask_bits, bool awake, bool sensor, double gravity_scale,
         uint64_t user_data) {
        World& world = w.get();
        BodyDef d;
        d.shape = ShapeId{shape};
        d.motion = motion_type(motion, "motion");
        d.position = vec3(position);
        d.orientation = quat(orientation);
        d.linear_velocity = vec3(linear_velocity);
        d.angular_velocity = vec3(angular_velocity);
        if (mass) d.mass = Real(*mass);
        d.density = Real(density);
        d.friction = Real(friction);
        d.restitution = Real(restitution);
        d.linear_damping = Real(linear_damping);
        d.angular_damping = Real(angular_damping);
        d.category_bits = category_bits;
        d.mask_bits = mask_bits;
        d.awake = awake;
        d.sensor = sensor;
        d.gravity_scale = Real(gravity_scale);
        d.user_data = user_data;
        return to_int(world.create_body(d));
      },
      arg("shape"), pybind11::kw_only(), arg("motion") = "dynamic", arg("position") = V3{0, 0, 0},
      arg("orientation") = Q4{1, 0, 0, 0}, arg("linear_velocity") = V3{0, 0, 0},
      arg("angular_velocity") = V3{0, 0, 0}, arg("mass") = pybind11::none(),
      arg("density") = 1000.0, arg("friction") = 0.5, arg("restitution") = 0.0,
      arg("linear_damping") = 0.0, arg("angular_damping") = 0.0, arg("category_bits") = 1u,
      arg("mask_bits") = 0xFFFFFFFFu, arg("awake") = true, arg("sensor") = false,
      arg("gravity_scale") = 1.0, arg("user_data") = 0,
      "Creates a body of `shape`; returns its id (int). motion: 'static', 'kinematic' or "
      "'dynamic'; position (m) and orientation (w, x, y, z) place the shape frame in the "
      "world; linear_velocity (m/s, of the centre of mass) and angular_velocity (rad/s, "
      "world); mass (kg) or else density (kg/m^3) times volume; friction (mixed as sqrt(f1 "
      "f2)); restitution (mixed as max); damping in 1/s; collision filter bits; sensor bodies "
      "report overlaps instead of colliding. Raises elan.Error naming the field.");
  c.def(
      "destroy_body", [](PyWorld& w, uint64_t body) { w.get().destroy_body(body_id(body)); },
      arg("body"),
      "Destroys a body. The last body moves into its dense index: column views and dense "
      "indices taken before are invalid.");
  c.def(
      "is_valid", [](const PyWorld& w, uint64_t body) { return w.get().is_valid(body_id(body)); },
      arg("body"), "Is `body` a live body of this world?");
  c.def_property_readonly(
      "body_count", [](const PyWorld& w) { return w.get().body_count(); }, "Bodies in the world.");
  c.def(
      "body_at",
      [](const PyWorld& w, std::size_t index) {
        const World& world = w.get();
        if (index >= world.body_count()) {
          raise("index", std::to_string(index) + " out of range (" +
                             std::to_string(world.body_count()) + " bodies)");
        }
        return to_int(world.body_at(index));
      },
      arg("index"), "The id of the body at dense index `index` (scene order for scene worlds).");
  c.def(
      "__len__", [](const PyWorld& w) { return w.get().body_count(); }, "body_count");

  getter(
      c, "position", [](const World& w, BodyId b) { return tuple3(w.position(b)); },
      "m, world: the shape frame's origin.");
  getter(
      c, "orientation", [](const World& w, BodyId b) { return tuple4(w.orientation(b)); },
      "(w, x, y, z): shape frame to world.");
  getter(
      c, "linear_velocity", [](const World& w, BodyId b) { return tuple3(w.linear_velocity(b)); },
      "m/s, world, of the centre of mass.");
  getter(
      c, "angular_velocity", [](const World& w, BodyId b) { return tuple3(w.angular_velocity(b)); },
      "rad/s, world.");
  getter(
      c, "center_of_mass", [](const World& w, BodyId b) { return tuple3(w.center_of_mass(b)); },
      "m, world.");
  getter(
      c, "mass", [](const World& w, BodyId b) { return double(w.mass(b)); },
      "kg (0 for static and kinematic bodies).");
  getter(
      c, "inertia",
      [](const World& w, BodyId b) {
        const Mat3 m = w.inertia(b);
        pybind11::list rows_;
        for (int i = 0; i < 3; ++i) {
          rows_.append(pybind11::make_tuple(double(m(i, 0)), double(m(i, 1)), double(m(i, 2))));
        }
        return pybind11::tuple(rows_);
      },
      "kg m^2, world frame, about the centre of mass (3 rows of 3).");
  getter(
      c, "motion_type", [](const World& w, BodyId b) { return motion_name(w.motion_type(b)); },
      "'static', 'kinematic' or 'dynamic'.");
  getter(
      c, "is_awake", [](const World& w, BodyId b) { return w.is_awake(b); }, "");
  getter(
      c, "is_sensor", [](const World& w, BodyId b) { return w.is_sensor(b); }, "");
  getter(
      c, "friction", [](const World& w, BodyId b) { return double(w.friction(b)); }, "");
  getter(
      c, "restitution", [](const World& w, BodyId b) { return double(w.restitution(b)); }, "");
  getter(
      c, "category_bits", [](const World& w, BodyId b) { return w.category_bits(b); }, "");
  getter(
      c, "mask_bits", [](const World& w, BodyId b) { return w.mask_bits(b); }, "");
  getter(
      c, "gravity_scale", [](const World& w, BodyId b) { return double(w.gravity_scale(b)); }, "");
  getter(
      c, "linear_damping", [](const World& w, BodyId b) { return double(w.linear_damping(b)); },
      "1/s.");
  getter(
      c, "angular_damping", [](const World& w, BodyId b) { return double(w.angular_damping(b)); },
      "1/s.");
  getter(
      c, "shape", [](const World& w, BodyId b) { return w.shape(b).index; },
      "The body's shape id.");
  getter(
      c, "user_data", [](const World& w, BodyId b) { return w.user_data(b); }, "");
  getter(
      c, "bounds",
      [](const World& w, BodyId b) {
        const Aabb a = w.bounds(b);
        return pybind11::make_tuple(tuple3(a.lo), tuple3(a.hi));
      },
      "(lo, hi), m, world: the bounding box the broadphase and queries use.");

  const auto vec_setter = [&c](const char* name, void (World::*set)(BodyId, const Vec3&),
                               const char* value, const char* doc) {
    c.def(
        name, [set](PyWorld& w, uint64_t body, V3 v) { (w.get().*set)(body_id(body), vec3(v)); },
        arg("body"), arg(value), doc);
  };
  vec_setter("set_linear_velocity", &World::set_linear_velocity, "velocity",
             "m/s, world, of the centre of mass. Wakes the body.");
  vec_setter("set_angular_velocity", &World::set_angular_velocity, "velocity",
             "rad/s, world. Wakes the body.");
  vec_setter("set_position", &World::set_position, "position",
             "Teleports the shape frame (m, world); velocities are kept.");
  vec_setter("apply_force", &World::apply_force, "force",
             "N, world, through the centre of mass, for the next step only.");
  vec_setter("apply_torque", &World::apply_torque, "torque", "N m, world, for the next step only.");
  vec_setter("apply_linear_impulse", &World::apply_linear_impulse, "impulse",
             "N s, world: dv = J / m (dynamic bodies).");
  vec_setter("apply_angular_impulse", &World::apply_angular_impulse, "impulse",
             "N m s, world: dw = I^-1 L (dynamic bodies).");
  c.def(
      "set_orientation",
      [](PyWorld& w, uint64_t body, Q4 q) { w.get().set_orientation(body_id(body), quat(q)); },
      arg("body"), arg("orientation"), "(w, x, y, z), normalised; zero is an elan.Error.");
  c.def(
      "set_transform",
      [](PyWorld& w, uint64_t body, V3 p, Q4 q) {
        w.get().set_transform(body_id(body), Transform{vec3(p), quat(q)});
      },
      arg("body"), arg("position"), arg("orientation"), "Both at once (m; w, x, y, z).");
  c.def(
      "apply_force_at",
      [](PyWorld& w, uint64_t body, V3 f, V3 p) {
        w.get().apply_force_at(body_id(body), vec3(f), vec3(p));
      },
      arg("body"), arg("force"), arg("point"),
      "Force (N, world) at a world point (m) for the next step: adds (point - com) x force.");
  c.def(
      "apply_impulse",
      [](PyWorld& w, uint64_t body, V3 j, V3 p) {
        w.get().apply_impulse(body_id(body), vec3(j), vec3(p));
      },
      arg("body"), arg("impulse"), arg("point"),
      "Impulse (N s, world) at a world point (m): dv = J / m, dw = I^-1 ((p - com) x J).");
  c.def(
      "move_kinematic",
      [](PyWorld& w, uint64_t body, V3 p, Q4 q, double dt) {
        w.get().move_kinematic(body_id(body), Transform{vec3(p), quat(q)}, Real(dt));
      },
      arg("body"), arg("position"), arg("orientation"), arg("dt"),
      "Kinematic bodies: velocities that carry the shape frame to the target pose in dt s.");
  c.def(
      "wake", [](PyWorld& w, uint64_t body) { w.get().wake(body_id(body)); }, arg("body"));
  c.def(
      "sleep", [](PyWorld& w, uint64_t body) { w.get().sleep(body_id(body)); }, arg("body"));
  c.def(
      "set_friction",
      [](PyWorld& w, uint64_t body, double f) { w.get().set_friction(body_id(body), Real(f)); },
      arg("body"), arg("friction"), ">= 0.");
  c.def(
      "set_restitution",
      [](PyWorld& w, uint64_t body, double e) { w.get().set_restitution(body_id(body), Real(e)); },
      arg("body"), arg("restitution"), ">= 0.");
  c.def(
      "set_mass",
      [](PyWorld& w, uint64_t body, double m) { w.get().set_mass(body_id(body), Real(m)); },
      arg("body"), arg("mass"), "kg, > 0, dynamic bodies; the inertia follows from the shape.");
  c.def(
      "set_collision_filter",
      [](PyWorld& w, uint64_t body, uint32_t category, uint32_t mask) {
        w.get().set_collision_filter(body_id(body), category, mask);
      },
      arg("body"), arg("category_bits"), arg("mask_bits"));
  c.def(
      "set_motion_type",
      [](PyWorld& w, uint64_t body, const std::string& t) {
        w.get().set_motion_type(body_id(body), motion_type(t, "motion"));
      },
      arg("body"), arg("motion"), "'static', 'kinematic' or 'dynamic'.");
  c.def(
      "set_gravity_scale",
      [](PyWorld& w, uint64_t body, double s) {
        w.get().set_gravity_scale(body_id(body), Real(s));
      },
      arg("body"), arg("scale"));
  c.def(
      "set_damping",
      [](PyWorld& w, uint64_t body, double lin, double ang) {
        w.get().set_damping(body_id(body), Real(lin), Real(ang));
      },
      arg("body"), arg("linear"), arg("angular"), "1/s, >= 0.");
  c.def(
      "set_shape",
      [](PyWorld& w, uint64_t body, uint32_t shape) {
        w.get().set_shape(body_id(body), ShapeId{shape});
      },
      arg("body"), arg("shape"), "Swaps the body's shape (mass follows at its density).");
  c.def(
      "set_sensor", [](PyWorld& w, uint64_t body, bool s) { w.get().set_sensor(body_id(body), s); },
      arg("body"), arg("sensor"));
  c.def(
      "set_user_data",
      [](PyWorld& w, uint64_t body, uint64_t v) { w.get().set_user_data(body_id(body), v); },
      arg("body"), arg("value"));
}

}  // namespace elan::py
