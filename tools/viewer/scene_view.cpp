// SPDX-License-Identifier: MIT
#include "tools/viewer/scene_view.hpp"

#include <cstring>

#include "elan/debug_draw.hpp"

namespace elan::viewer {
namespace {

void put(std::string& key, const void* bytes, std::size_t n) {
  key.append(static_cast<const char*>(bytes), n);
}

// The bytes of everything that shapes the mesh of `def`: equal keys, equal meshes.
void shape_key(const ShapeDef& def, std::string& key) {
  put(key, &def.type, sizeof def.type);
  switch (def.type) {
    case ShapeType::Capsule:
      put(key, &def.radius, sizeof def.radius);
      put(key, &def.half_height, sizeof def.half_height);
      break;
    case ShapeType::ConvexHull:
      put(key, def.points.data(), def.points.size() * sizeof(Vec3));
      break;
    case ShapeType::Plane:
      put(key, def.normal.data(), sizeof(Vec3));
      put(key, &def.offset, sizeof def.offset);
      break;
    case ShapeType::Mesh:
      put(key, def.vertices.data(), def.vertices.size() * sizeof(Vec3));
      put(key, def.triangles.data(), def.triangles.size() * sizeof(def.triangles[0]));
      break;
    case ShapeType::Heightfield:
      put(key, def.heights.data(), def.heights.size() * sizeof(Real));
      put(key, &def.columns, sizeof def.columns);
      put(key, &def.spacing_x, sizeof def.spacing_x);
      put(key, &def.spacing_z, sizeof def.spacing_z);
      break;
    case ShapeType::Compound:
      for (const CompoundChild& c : def.children) {
        shape_key(c.shape, key);
        put(key, c.position.data(), sizeof(Vec3));
        put(key, c.orientation.coeffs().data(), 4 * sizeof(Real));
        // Unit-mesh children are built at their size.
        put(key, &c.shape.radius, sizeof(Real));
        put(key, &c.shape.half_height, sizeof(Real));
        put(key, c.shape.half_extents.data(), sizeof(Vec3));
      }
      break;
    default:
      break;
  }
}

constexpr float kPalette[8][3] = {
    {0.90f, 0.45f, 0.25f}, {0.30f, 0.65f, 0.90f}, {0.45f, 0.80f, 0.40f}, {0.95f, 0.75f, 0.25f},
    {0.70f, 0.45f, 0.85f}, {0.30f, 0.80f, 0.75f}, {0.90f, 0.40f, 0.55f}, {0.80f, 0.80f, 0.75f},
};

// Takes the colour debug_draw gives each body's shape (called in dense index order).
class IslandColors final : public DebugDrawer {
 public:
  explicit IslandColors(std::vector<Eigen::Vector4f>& out) : out_(out) { out_.clear(); }
  void draw_shape(BodyId, const ShapeDef&, const Transform&, DebugColor c, bool) override {
    out_.emplace_back(c.r, c.g, c.b, 1.0f);
  }
  void draw_line(const Vec3&, const Vec3&, DebugColor) override {}
  void draw_point(const Vec3&, float, DebugColor) override {}
  void draw_box(const Aabb&, DebugColor) override {}

 private:
  std::vector<Eigen::Vector4f>& out_;
};

// The joints' lines, as the scene's joints are drawn (depth-tested, with the bodies).
class JointLines final : public DebugDrawer {
 public:
  explicit JointLines(Renderer& r) : r_(r) {}
  void draw_shape(BodyId, const ShapeDef&, const Transform&, DebugColor, bool) override {}
  void draw_line(const Vec3& a, const Vec3& b, DebugColor c) override {
    r_.add_line(a.cast<float>(), b.cast<float>(), {c.r, c.g, c.b, c.a});
  }
  void draw_point(const Vec3&, float, DebugColor) override {}
  void draw_box(const Aabb&, DebugColor) override {}

 private:
  Renderer& r_;
};

}  // namespace

Eigen::Vector4f body_color(std::size_t index, MotionType motion, bool awake) {
  Eigen::Vector3f c;
  if (motion == MotionType::Static) {
    c = {0.55f, 0.56f, 0.58f};
  } else if (motion == MotionType::Kinematic) {
    c = {0.35f, 0.50f, 0.90f};
  } else {
    // A multiplicative hash spreads neighbouring indices (a pyramid's rows) over the palette.
    const float* p = kPalette[(uint32_t(index) * 2654435761u >> 29) & 7];
    c = {p[0], p[1], p[2]};
    if (!awake) c = 0.45f * c + Eigen::Vector3f::Constant(0.12f);
  }
  return {c.x(), c.y(), c.z(), 1.0f};
}

void SceneView::assign(const Simulation& sim, Renderer& renderer, std::size_t i) {
  const ShapeDef& def = sim.body_shape(i);
  const MeshKind kind = mesh_kind(def);
  body_scale_[i] = instance_scale(def);
  body_radius_[i] = bounding_radius(def);
  body_shape_[i] = sim.world().shape(sim.world().body_at(i));
  body_capsule_[i] = Eigen::Vector2f::Zero();
  if (def.type == ShapeType::Capsule) {
    body_capsule_[i] = {float(def.radius), float(def.half_height)};
    body_mesh_[i] = {unit_meshes_[0][3], unit_meshes_[1][3]};
    return;
  }
  if (kind != MeshKind::Own) {
    body_mesh_[i] = {unit_meshes_[0][int(kind)], unit_meshes_[1][int(kind)]};
    return;
  }
  std::string key;
  shape_key(def, key);
  auto it = own_meshes_.find(key);
  if (it == own_meshes_.end()) {
    const int fine = renderer.add_mesh(shape_mesh(def, kFine));
    const int coarse = is_curved(def) ? renderer.add_mesh(shape_mesh(def, kCoarse)) : fine;
    it = own_meshes_.emplace(std::move(key), std::array<int, 2>{fine, coarse}).first;
  }
  body_mesh_[i] = it->second;
}

void SceneView::rebuild(const Simulation& sim, Renderer& renderer) {
  renderer.clear_meshes();
  own_meshes_.clear();
  for (int level = 0; level < 2; ++level) {
    const Tessellation t = level == 0 ? kFine : kCoarse;
    unit_meshes_[level][0] = renderer.add_mesh(unit_sphere(t.rings, t.segments));
    unit_meshes_[level][1] = level == 0 ? renderer.add_mesh(unit_box()) : unit_meshes_[0][1];
    unit_meshes_[level][2] = renderer.add_mesh(unit_cylinder(t.segments));
    unit_meshes_[level][3] = renderer.add_mesh(unit_hemisphere(t.rings, t.segments));
    unit_meshes_[level][4] = renderer.add_mesh(unit_tube(t.segments));
  }
  const std::size_t n = sim.world().body_count();
  body_mesh_.assign(n, {-1, -1});
  body_scale_.assign(n, Eigen::Vector3f::Ones());
  body_radius_.assign(n, 0.0f);
  body_capsule_.assign(n, Eigen::Vector2f::Zero());
  body_shape_.assign(n, ShapeId{});
  for (std::size_t i = 0; i < n; ++i) assign(sim, renderer, i);
  version_ = sim.version();
  sim_ = &sim;
}

void SceneView::update(const Simulation& sim, Renderer& renderer,
                       std::optional<std::size_t> selected, std::optional<std::size_t> highlighted,
                       uint32_t overlays, const DetailView* detail) {
  if (sim.version() != version_ || &sim != sim_ || body_mesh_.size() != sim.world().body_count()) {
    rebuild(sim, renderer);
  }
  renderer.begin_frame();
  const World& world = sim.world();
  const std::size_t n = world.body_count();
  // A recorded program may swap a body's shape, or destroy one body and create another in the
  // same step: each body's mesh follows its current shape.
  for (std::size_t i = 0; i < n; ++i) {
    if (world.shape(world.body_at(i)) != body_shape_[i]) assign(sim, renderer, i);
  }
  // Islands and the solver's halves: the library's colours (debug_draw's kDrawIslands,
  // kDrawSolverHalves; a split body takes its half's colour over its island's).
  const uint32_t by_library = overlays & (kDrawIslands | kDrawSolverHalves);
  if (by_library) {
    IslandColors collect(island_colors_);
    world.debug_draw(collect, by_library);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const BodyId id = world.body_at(i);
    const Vec3 p = world.position(id);
    const Quat q = world.orientation(id);
    const MotionType motion = world.motion_type(id);
    Eigen::Vector4f c = body_color(i, motion, world.is_awake(id));
    if (by_library && motion == MotionType::Dynamic && i < island_colors_.size() &&
        ((overlays & kDrawIslands) || world.is_awake(id))) {
      // Halves alone: only the awake dynamic bodies were split (the library gives the others
      // its own colour by motion type; the viewer keeps its palette).
      c = island_colors_[i];
    }
    const bool sensor = world.is_sensor(id);
    if (sensor) c = Eigen::Vector4f(kSensorColor);
    if (selected && *selected == i) c = {1.0f, 0.85f, 0.2f, sensor ? kSensorColor[3] : 1.0f};
    if (highlighted && *highlighted == i) c = {1.0f, 0.15f, 0.1f, 1.0f};
    const Eigen::Vector3f& s = body_scale_[i];
    // The coarse mesh when the bounding sphere is small on the picture: radius r at distance d
    // spans r k / d pixels (k = detail->pixels_per_unit).
    int level = 0;
    if (detail != nullptr) {
      const float r = body_radius_[i];
      const float d = (detail->eye - p.cast<float>()).norm();
      level = r * detail->pixels_per_unit < kCoarseBelowPixels * d ? 1 : 0;
    }
    Instance inst{{float(p.x()), float(p.y()), float(p.z())},
                  {float(q.x()), float(q.y()), float(q.z()), float(q.w())},
                  {s.x(), s.y(), s.z()},
                  {c[0], c[1], c[2], c[3]},
                  motion == MotionType::Static && !sensor ? 1.0f : 0.0f};
    const Eigen::Vector2f cap = body_capsule_[i];
    if (cap.x() > 0) {
      // Upper hemisphere at +h along the shape's y, the lower one turned half a turn about x
      // (y -> -y) at -h, the tube between them scaled to (r, h, r).
      const Eigen::Quaternionf qf = q.cast<float>();
      const Eigen::Vector3f up = qf * Eigen::Vector3f(0, cap.y(), 0);
      const Eigen::Quaternionf down = qf * Eigen::Quaternionf(0, 1, 0, 0);
      const Eigen::Vector3f pf = p.cast<float>();
      Instance part = inst;
      part.scale[0] = part.scale[1] = part.scale[2] = cap.x();
      for (int k = 0; k < 3; ++k) part.position[k] = pf[k] + up[k];
      renderer.add_instance(unit_meshes_[level][3], part);
      for (int k = 0; k < 3; ++k) part.position[k] = pf[k] - up[k];
      part.rotation[0] = down.x();
      part.rotation[1] = down.y();
      part.rotation[2] = down.z();
      part.rotation[3] = down.w();
      renderer.add_instance(unit_meshes_[level][3], part);
      Instance tube = inst;
      tube.scale[0] = tube.scale[2] = cap.x();
      tube.scale[1] = cap.y();
      renderer.add_instance(unit_meshes_[level][4], tube);
      continue;
    }
    renderer.add_instance(body_mesh_[i][level], inst);
  }
  // A recorded program's joints are not the scene's: the library draws them.
  if (sim.joints().empty() && world.joint_count() > 0) {
    JointLines lines(renderer);
    world.debug_draw(lines, kDrawJoints);
  }
  // Joints: origin A -> anchor A -> anchor B -> origin B.
  const Eigen::Vector4f arm(0.95f, 0.95f, 0.55f, 1.0f), gap(1.0f, 0.3f, 0.3f, 1.0f);
  for (const JointLink& j : sim.joints()) {
    if (!world.is_valid(j.id) || j.body_a < 0 || std::size_t(j.body_a) >= n) continue;
    const BodyId a = world.body_at(std::size_t(j.body_a));
    const Eigen::Vector3f pa = world.position(a).cast<float>();
    const Eigen::Vector3f wa = (world.position(a) + world.orientation(a) * j.local_a).cast<float>();
    Eigen::Vector3f pb = j.local_b.cast<float>(), wb = pb;
    if (j.body_b >= 0 && std::size_t(j.body_b) < n) {
      const BodyId b = world.body_at(std::size_t(j.body_b));
      pb = world.position(b).cast<float>();
      wb = (world.position(b) + world.orientation(b) * j.local_b).cast<float>();
    }
    renderer.add_line(pa, wa, arm);
    renderer.add_line(wa, wb, gap);
    renderer.add_line(wb, pb, arm);
  }
}

}  // namespace elan::viewer
