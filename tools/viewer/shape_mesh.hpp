// SPDX-License-Identifier: MIT
// Triangle meshes of the shapes, in the shape's own frame, for the renderer. Sphere, box and
// cylinder are unit meshes the renderer scales per instance; the other kinds are built per shape
// definition. Faces of flat shapes have one normal per triangle (vertices not shared).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "elan/defs.hpp"

namespace elan::viewer {

struct MeshVertex {
  float position[3];
  float normal[3];
};

struct MeshData {
  std::vector<MeshVertex> vertices;
  std::vector<uint32_t> indices;  ///< triangles
};

/// Half size of the quad that stands for an infinite plane, m.
inline constexpr float kPlaneHalfSize = 250;

MeshData unit_sphere(int rings, int segments);  ///< radius 1
MeshData unit_box();                            ///< [-1, 1]^3
MeshData unit_cylinder(int segments);           ///< radius 1, y in [-1, 1]
/// The upper half of unit_sphere (y >= 0, open at the equator), with the capsule's ring count.
MeshData unit_hemisphere(int rings, int segments);
MeshData unit_tube(int segments);  ///< unit_cylinder's side alone (no end discs)
MeshData capsule(float radius, float half_height, int rings, int segments);
/// The convex hull of `points` (faces found by testing every triple's plane against all points,
/// O(n^4): hull inputs are small clouds; larger ones are thinned first).
MeshData convex_hull(const std::vector<Vec3>& points);
MeshData triangle_mesh(const std::vector<Vec3>& vertices,
                       const std::vector<std::array<uint32_t, 3>>& triangles);
MeshData heightfield(const ShapeDef& def);
/// A square of kPlaneHalfSize around the plane's point nearest the shape frame's origin.
MeshData plane_quad(const Vec3& normal, Real offset);
/// How finely curved surfaces (spheres, capsules, cylinders) are cut into triangles.
struct Tessellation {
  int rings = 12;     ///< from pole to pole (a capsule's hemispheres take half each)
  int segments = 20;  ///< around the axis
};
/// What a body near the eye gets (480 triangles a sphere), and one a few pixels across (120):
/// under software rendering the triangle count of a large pile sets the frame rate.
inline constexpr Tessellation kFine{12, 20};
inline constexpr Tessellation kCoarse{6, 10};
/// Any shape kind at its own size (unit meshes scaled, compound children placed).
MeshData shape_mesh(const ShapeDef& def, Tessellation t = kFine);
/// Whether shape_mesh depends on the tessellation (the shape or a compound child is curved).
bool is_curved(const ShapeDef& def);

/// The radius of a sphere about the shape frame's origin that holds the shape, m (infinite for
/// a plane).
float bounding_radius(const ShapeDef& def);

/// How the renderer draws a shape: the mesh kind and the per-instance scale of a unit mesh.
enum class MeshKind : uint8_t { Sphere, Box, Cylinder, Own };
MeshKind mesh_kind(const ShapeDef& def);
Eigen::Vector3f instance_scale(const ShapeDef& def);

/// Appends `part`, moved by `pose` (and scaled by `scale` before it), to `into`.
void append(MeshData& into, const MeshData& part, const Eigen::Affine3f& pose,
            const Eigen::Vector3f& scale = Eigen::Vector3f::Ones());

}  // namespace elan::viewer
