// SPDX-License-Identifier: MIT
// Shape definitions derived from built shapes (see shape_defs.hpp).
#include "core/world/shape_defs.hpp"

#include "core/base/compound.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/triangle_mesh.hpp"

namespace elan::detail {

namespace {

// The definition in the shape's principal frame, in which a hull's vertices and a compound's
// part poses are kept.
ShapeDef principal_def(const Shape& s) {
  ShapeDef d;
  d.type = s.type;
  switch (s.type) {
    case ShapeType::Sphere:
      d.radius = s.radius;
      break;
    case ShapeType::Box:
      d.half_extents = s.half_extents;
      break;
    case ShapeType::Capsule:
    case ShapeType::Cylinder:
      d.radius = s.radius;
      d.half_height = s.half_height;
      break;
    case ShapeType::ConvexHull:
      d.points = s.hull->vertices;
      break;
    case ShapeType::Plane:
      d.normal = s.plane_normal;
      d.offset = s.plane_offset;
      break;
    case ShapeType::Mesh:
      d.vertices = s.mesh->vertices;
      d.triangles = s.mesh->triangles;
      break;
    case ShapeType::Heightfield: {
      const HeightField& h = *s.heightfield;
      d.heights.assign(h.heights.begin(), h.heights.end());
      d.columns = h.columns;
      d.spacing_x = h.spacing_x;
      d.spacing_z = h.spacing_z;
      break;
    }
    case ShapeType::Compound: {
      const Compound& c = *s.compound;
      d.children.resize(c.parts.size());
      for (std::size_t k = 0; k < c.parts.size(); ++k) {
        const CompoundPart& p = c.parts[k];
        // Each part in its own principal frame, placed by its pose in the compound's.
        CompoundChild& child = d.children[c.child_of[k]];
        child.shape = principal_def(p.shape);
        child.position = p.pose.position;
        child.orientation = p.pose.rotation;
      }
      break;
    }
  }
  return d;
}

}  // namespace

ShapeDef shape_def_of(const Shape& s) {
  ShapeDef d = principal_def(s);
  // x_user = frame_rotation x_principal + frame_position (identity but for hulls and compounds).
  const Transform frame{s.frame_position, s.frame_rotation};
  if (s.type == ShapeType::ConvexHull) {
    for (Vec3& p : d.points) p = frame.apply(p);
  } else if (s.type == ShapeType::Compound) {
    for (CompoundChild& c : d.children) {
      c.position = frame.apply(c.position);
      c.orientation = (frame.rotation * c.orientation).normalized();
    }
  }
  return d;
}

}  // namespace elan::detail
