// SPDX-License-Identifier: MIT
// Shape: immutable geometry in its principal frame (centre of mass at the origin, inertia
// diagonal), plus the frame's placement in the user's shape frame and exact mass properties.
#pragma once

#include <memory>

#include "core/base/convex_hull.hpp"
#include "elan/defs.hpp"
#include "elan/math.hpp"

namespace elan::detail {

struct TriangleMesh;  // core/base/triangle_mesh.hpp
struct HeightField;   // core/base/heightfield.hpp
struct Compound;      // core/base/compound.hpp

struct Shape {
  ShapeType type = ShapeType::Sphere;
  // perf: beside the type, in the first cache line: the collide stage reads both of every pair's
  // shapes for its separation cache (closing, position_step) and nothing else of most of them.
  Real bounding_radius = 0;                // m: max distance of the surface from the origin
  Real radius = 0;                         // m: sphere, capsule, cylinder
  Real half_height = 0;                    // m: capsule segment / cylinder, along local Y
  Vec3 half_extents = Vec3::Zero();        // m: box
  std::shared_ptr<const ConvexHull> hull;  // principal frame; null unless ConvexHull
  // Shared, never copied per body or per rollback frame; each null unless the shape is one. A
  // mesh's and a heightfield's principal frame is their shape frame (static: no mass).
  std::shared_ptr<const TriangleMesh> mesh;
  std::shared_ptr<const HeightField> heightfield;
  std::shared_ptr<const Compound> compound;  // principal frame, the compound's centre of mass
  Vec3 plane_normal = Vec3::UnitY();         // plane: dot(n, x) <= offset (principal = user frame)
  Real plane_offset = 0;

  // Placement of the principal frame in the user's shape frame:
  // x_user = frame_rotation * x_principal + frame_position. Identity except for hulls and
  // compounds.
  Vec3 frame_position = Vec3::Zero();
  Quat frame_rotation = Quat::Identity();

  Real volume = 0;                   // m^3 (0 for planes)
  Vec3 unit_inertia = Vec3::Zero();  // m^2: principal moments per kg (I = mass * this)
  Vec3 local_min = Vec3::Zero();     // m: bounds in the principal frame (planes: unused)
  Vec3 local_max = Vec3::Zero();
};

// Validates `def` and builds the shape. Throws elan::Error naming the field ("shape.radius",
// "shape.points", ...) for zero, negative or non-finite sizes, a zero plane normal or a
// degenerate hull.
Shape make_shape(const ShapeDef& def);

// Whether the shape is one convex solid (support, GJK and the convex pair routines apply): not a
// plane, mesh, heightfield or compound.
inline bool is_convex(const Shape& s) {
  return s.type <= ShapeType::ConvexHull;
}

// A point or direction as three numbers. perf: a trivially copyable type of three floats travels
// in registers (two), an Eigen vector by hidden reference through memory, where GCC stored it one
// float at a time and read it back eight bytes at once: a failed store-to-load forwarding on
// every support GJK takes. The support functions pass their directions and results this way.
struct Xyz {
  Real x, y, z;
};

// support's body, with the direction and the result in registers.
Xyz support_xyz(const Shape& shape, Real dx, Real dy, Real dz);

// Support point of the shape (principal frame) in direction d (need not be unit). Planes, meshes,
// heightfields and compounds have no support and are handled by their own routines.
inline Vec3 support(const Shape& shape, const Vec3& d) {
  const Xyz s = support_xyz(shape, d.x(), d.y(), d.z());
  return Vec3(s.x, s.y, s.z);
}

}  // namespace elan::detail
