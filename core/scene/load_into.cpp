// SPDX-License-Identifier: MIT
// Loading a scene into a World: identical shapes shared, bodies and then joints created in scene
// order, and the World's errors turned into scene messages naming the body or joint and field.
#include <map>
#include <string>
#include <vector>

#include "core/scene/body_schema.hpp"
#include "core/scene/joint_schema.hpp"
#include "core/scene/schema_checks.hpp"
#include "core/world/world_access.hpp"
#include "elan/scene.hpp"

namespace elan {

using namespace detail::scene_file;

namespace {

// The bits of the fields that matter for the shape's type, appended to `key`: equal keys mean
// identical shapes.
void append_shape_key(const ShapeDef& s, std::string& key) {
  key.push_back(char(s.type));
  auto add = [&key](const auto& v) { key.append(reinterpret_cast<const char*>(&v), sizeof v); };
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
    case ShapeType::Mesh:
      add(s.vertices.size());
      for (const Vec3& p : s.vertices) add3(p);
      for (const auto& t : s.triangles) add(t);
      break;
    case ShapeType::Heightfield:
      add(s.columns);
      add(s.spacing_x);
      add(s.spacing_z);
      for (const Real h : s.heights) add(h);
      break;
    case ShapeType::Compound:
      add(s.children.size());
      for (const CompoundChild& c : s.children) {
        append_shape_key(c.shape, key);
        add3(c.position);
        for (int i = 0; i < 4; ++i) add(c.orientation.coeffs()[i]);
      }
      break;
  }
}

void shape_key(const ShapeDef& s, std::string& key) {
  key.clear();
  append_shape_key(s, key);
}

}  // namespace

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
  std::vector<BodyId> ids;  // the world's id of scene body i
  ids.reserve(scene.bodies.size());
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
      ids.push_back(world.create_body(def));
    } catch (const Error& e) {
      const std::string& f = e.field();
      fail(ctx, f.empty() ? "body" : f,
           f.empty() ? e.what() : std::string(e.what()).substr(f.size() + 2));
    }
  }
  for (std::size_t i = 0; i < scene.joints.size(); ++i) {
    const SceneJoint& j = scene.joints[i];
    const Ctx ctx{file_name, joint_where(i, j.name), ""};
    const auto id = [&](int body, const char* field) {
      if (body < -1 || body >= int(ids.size())) {
        fail(ctx, field, "no body " + std::to_string(body) + " in the scene");
      }
      return body < 0 ? BodyId{} : ids[std::size_t(body)];
    };
    JointDef def = j.def;
    def.body_a = id(j.body_a, "bodies[0]");
    def.body_b = id(j.body_b, "bodies[1]");
    try {
      world.create_joint(def);
    } catch (const Error& e) {
      const std::string& f = e.field();
      fail(ctx, f.empty() ? "joint" : scene_field(def.type, f),
           f.empty() ? e.what() : std::string(e.what()).substr(f.size() + 2));
    }
  }
}

}  // namespace elan
