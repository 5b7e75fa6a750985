// SPDX-License-Identifier: MIT
// The scene file's chain and joint_grid generators: validation and expansion.
#include "core/scene/joint_generators.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/scene/body_schema.hpp"

namespace elan::detail::scene_file {
namespace {

// Points are computed in double and rounded once, like the grid's.
Vec3 rounded(const Eigen::Vector3d& p) {
  return p.cast<Real>();
}

Eigen::Vector3d unit(const Ctx& ctx, const Json& j, const std::string& field) {
  const Eigen::Vector3d v = to_vec3(ctx, j, field).cast<double>();
  const double n = v.norm();
  if (!(n > 0)) fail(ctx, field, "zero vector");
  return v / n;
}

// The link's length along its own Y axis (a capsule's and a cylinder's axis): the default
// spacing, so that consecutive links touch end to end.
double link_length(const ShapeDef& s) {
  switch (s.type) {
    case ShapeType::Sphere:
      return 2 * double(s.radius);
    case ShapeType::Box:
      return 2 * double(s.half_extents.y());
    case ShapeType::Capsule:
      return 2 * (double(s.half_height) + double(s.radius));
    case ShapeType::Cylinder:
      return 2 * double(s.half_height);
    case ShapeType::ConvexHull: {
      double lo = double(s.points[0].y()), hi = lo;
      for (const Vec3& p : s.points) {
        lo = std::min(lo, double(p.y()));
        hi = std::max(hi, double(p.y()));
      }
      return hi - lo;
    }
    case ShapeType::Plane:
    case ShapeType::Mesh:
    case ShapeType::Heightfield:
    case ShapeType::Compound:
      break;
  }
  return 0;
}

// The rotation that takes +Y to `d` (unit): the half-way quaternion, or a half turn about Z when
// d is -Y, where the half-way vector is undefined.
Quat y_to(const Eigen::Vector3d& d) {
  const double w = 1 + d.y();
  if (w < 1e-12) return Quat(0, 0, 0, 1);
  // (1 + y.d, y x d) normalised; y x d = (d.z, 0, -d.x).
  const Eigen::Quaterniond q(w, d.z(), 0, -d.x());
  return q.normalized().cast<Real>();
}

// Whether the top sphere of column k is static: the whole row, or Box2D's middle seven.
bool is_pinned(const JointGridDef& g, int64_t k) {
  return g.pin_row || (k >= g.count / 2 - 3 && k <= g.count / 2 + 3);
}

SceneJoint joint(JointType type, int a, int b, const Vec3& anchor) {
  SceneJoint j;
  j.body_a = a;
  j.body_b = b;
  j.def.type = type;
  j.def.anchor = anchor;
  return j;
}

}  // namespace

ChainDef parse_chain(const Ctx& ctx, const Json& j, SceneBody& link) {
  ChainDef c;
  c.links = to_int(ctx, require(ctx, j, "links", "links"), "links", 1, kMaxBodies);
  const Ctx link_ctx{ctx.file, ctx.where, "link."};
  link = parse_body(link_ctx, require(ctx, j, "link", "link"));
  if (!link.name.empty()) {
    fail(link_ctx, "name", "generated bodies cannot be named (names must be unique)");
  }
  if (link.body.motion != MotionType::Dynamic) fail(link_ctx, "motion", "a link must be dynamic");
  Eigen::Vector3d dir(0, -1, 0);
  if (const auto it = j.find("direction"); it != j.end()) dir = unit(ctx, *it, "direction");
  c.direction = rounded(dir);
  if (const auto it = j.find("link_spacing"); it != j.end()) {
    c.link_spacing = positive(ctx, *it, "link_spacing");
  } else {
    c.link_spacing = Real(link_length(link.shape));
    if (!(c.link_spacing > 0)) fail(ctx, "link_spacing", "missing (the link has no length)");
  }
  if (const auto it = j.find("joint"); it != j.end()) {
    const std::string t = to_string(ctx, *it, "joint");
    if (t == "ball") {
      c.joint = JointType::Ball;
    } else if (t == "hinge") {
      c.joint = JointType::Hinge;
    } else {
      fail(ctx, "joint", "unknown chain joint \"" + t + "\" (allowed: ball, hinge)");
    }
  }
  if (const auto it = j.find("axis"); it != j.end()) {
    if (c.joint != JointType::Hinge) fail(ctx, "axis", "only a hinge chain has an axis");
    c.axis = rounded(unit(ctx, *it, "axis"));
  }
  return c;
}

JointGridDef parse_joint_grid(const Ctx& ctx, const Json& j) {
  JointGridDef g;
  // count^2 bodies, at most kMaxBodies.
  g.count = to_int(ctx, require(ctx, j, "count", "count"), "count", 1, 3162);
  if (const auto it = j.find("spacing"); it != j.end()) g.spacing = positive(ctx, *it, "spacing");
  if (const auto it = j.find("radius"); it != j.end()) g.radius = positive(ctx, *it, "radius");
  if (const auto it = j.find("pinned"); it != j.end()) {
    const std::string p = to_string(ctx, *it, "pinned");
    if (p == "row") {
      g.pin_row = true;
    } else if (p != "middle") {
      fail(ctx, "pinned", "unknown pinning \"" + p + "\" (allowed: middle, row)");
    }
  }
  return g;
}

uint64_t chain_joints(const ChainDef& c) {
  return uint64_t(c.links);
}

// Two joints per sphere but the first row and column; none between two pinned spheres.
uint64_t joint_grid_joints(const JointGridDef& g) {
  const uint64_t n = uint64_t(g.count);
  uint64_t pinned_pairs = 0;
  for (int64_t k = 1; k < g.count; ++k) pinned_pairs += is_pinned(g, k) && is_pinned(g, k - 1);
  return 2 * n * (n - 1) - pinned_pairs;
}

void expand_chain(const ChainDef& c, const SceneBody& link, const Vec3& origin,
                  std::vector<SceneBody>& bodies, std::vector<SceneJoint>& joints) {
  const Eigen::Vector3d o = origin.cast<double>();
  const Eigen::Vector3d d = c.direction.cast<double>().normalized();
  const double s = double(c.link_spacing);
  const Quat q = y_to(d);
  for (int64_t i = 0; i < c.links; ++i) {
    const int index = int(bodies.size());
    SceneBody b = link;
    b.body.position = rounded(o + d * (s * (double(i) + 0.5)));
    b.body.orientation = q;
    bodies.push_back(std::move(b));
    // The first link hangs from the world; each other from the link before it.
    SceneJoint j = joint(c.joint, index, i == 0 ? -1 : index - 1, rounded(o + d * (s * double(i))));
    j.def.axis = c.axis;
    joints.push_back(std::move(j));
  }
}

void expand_joint_grid(const JointGridDef& g, const Vec3& origin, std::vector<SceneBody>& bodies,
                       std::vector<SceneJoint>& joints) {
  const Eigen::Vector3d o = origin.cast<double>();
  const double s = double(g.spacing);
  const int64_t n = g.count;
  SceneBody sphere;
  sphere.shape.type = ShapeType::Sphere;
  sphere.shape.radius = g.radius;
  // Box2D's filter: the spheres do not collide with one another, only with other bodies.
  sphere.body.category_bits = 2;
  sphere.body.mask_bits = ~uint32_t(2);
  const int first = int(bodies.size());
  // Column by column (Box2D's order), each top to bottom.
  for (int64_t k = 0; k < n; ++k) {
    for (int64_t i = 0; i < n; ++i) {
      const bool pinned = i == 0 && is_pinned(g, k);
      const int index = first + int(k * n + i);
      SceneBody b = sphere;
      b.body.motion = pinned ? MotionType::Static : MotionType::Dynamic;
      const Eigen::Vector3d p = o + Eigen::Vector3d(double(k) * s, -double(i) * s, 0);
      b.body.position = rounded(p);
      if (i > 0) {
        joints.push_back(
            joint(JointType::Ball, index, index - 1, rounded(p + Eigen::Vector3d(0, 0.5 * s, 0))));
      }
      if (k > 0) {
        if (!(pinned && is_pinned(g, k - 1))) {
          joints.push_back(joint(JointType::Ball, index, index - int(n),
                                 rounded(p - Eigen::Vector3d(0.5 * s, 0, 0))));
        }
      }
      bodies.push_back(std::move(b));
    }
  }
}

}  // namespace elan::detail::scene_file
