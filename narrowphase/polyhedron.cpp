// SPDX-License-Identifier: MIT
// Builds the working-frame polyhedron of a box (from a static unit box) or a convex hull,
// including the edge-to-face adjacency the Gauss-map edge pruning needs.
#include "narrowphase/polyhedron.hpp"

#include "narrowphase/box_topology.hpp"

namespace elan::detail {

namespace {

void make_box(const Shape& box, const Mat3& r, const Vec3& centre, Polyhedron& out) {
  const Vec3& h = box.half_extents;
  out.vertex_count = 8;
  out.face_count = 6;
  out.edge_count = 12;
  const Vec3 ax = r.col(0) * h.x(), ay = r.col(1) * h.y(), az = r.col(2) * h.z();
  // Vertex i is ((centre +- ax) +- ay) +- az, summed in that order; perf: the partial sums are
  // shared (2, then 4, then 8 additions instead of 24), in named values rather than arrays: GCC
  // stored an array's sums one float at a time and read them back 16 bytes at once, a failed
  // store-to-load forwarding.
  const Vec3 x0 = centre - ax, x1 = centre + ax;
  const Vec3 xy0 = x0 - ay, xy1 = x1 - ay, xy2 = x0 + ay, xy3 = x1 + ay;
  out.vertices[0] = xy0 - az;
  out.vertices[1] = xy1 - az;
  out.vertices[2] = xy2 - az;
  out.vertices[3] = xy3 - az;
  out.vertices[4] = xy0 + az;
  out.vertices[5] = xy1 + az;
  out.vertices[6] = xy2 + az;
  out.vertices[7] = xy3 + az;
  for (int k = 0; k < 3; ++k) {
    const Vec3 n = r.col(k);
    const Real d = n.dot(centre);
    out.normals[2 * k] = n;
    out.normals[2 * k + 1] = -n;
    out.offsets[2 * k] = d + h[k];
    out.offsets[2 * k + 1] = -d + h[k];
  }
  for (int f = 0; f < 6; ++f) {
    out.face_first[f] = uint32_t(4 * f);
    out.face_count_of[f] = 4;
  }
  out.face_vertices = kBoxLoops;
  out.edges = kBoxEdges;
  out.edge_faces = kBoxEdgeFaces;
  out.centre = centre;
  out.half_axes[0] = ax;
  out.half_axes[1] = ay;
  out.half_axes[2] = az;
  out.is_box = true;
}

// The hull placed in the world; its edge-to-face adjacency was built once with the hull.
void make_hull(const ConvexHull& hull, const Mat3& r, const Vec3& centre, Polyhedron& out) {
  const int nv = int(hull.vertices.size());
  const int nf = int(hull.faces.size());
  out.vertex_count = nv;
  out.face_count = nf;
  out.edge_count = int(hull.edges.size());
  for (int i = 0; i < nv; ++i) out.vertices[i] = r * hull.vertices[i] + centre;
  out.face_vertices = hull.face_vertices.data();

  for (int f = 0; f < nf; ++f) {
    const HullFace& face = hull.faces[f];
    out.normals[f] = r * face.normal;
    out.offsets[f] = out.normals[f].dot(out.vertices[hull.face_vertices[face.first]]);
    out.face_first[f] = face.first;
    out.face_count_of[f] = face.count;
  }
  out.edges = hull.edges.data();
  out.edge_faces = hull.edge_faces.data();
  out.centre = centre;
  out.is_box = false;
}

}  // namespace

bool is_sat_polyhedron(const Shape& shape) {
  if (shape.type == ShapeType::Box) return true;
  if (shape.type != ShapeType::ConvexHull || !shape.hull) return false;
  const ConvexHull& h = *shape.hull;
  return h.vertices.size() <= kMaxPolyVertices && h.faces.size() <= kMaxPolyFaces &&
         h.face_vertices.size() <= kMaxPolyLoop && h.edges.size() <= kMaxPolyEdges;
}

bool sat_is_affordable(const Shape& a, const Shape& b) {
  if (!is_sat_polyhedron(a) || !is_sat_polyhedron(b)) return false;
  // A box has 12 edges (the edge query of two boxes takes nine axes, but counting 144 is safe).
  auto edges = [](const Shape& s) -> std::size_t {
    return s.type == ShapeType::Box ? 12 : s.hull->edges.size();
  };
  return edges(a) * edges(b) <= kMaxSatEdgePairs;
}

void make_polyhedron(const Shape& shape, const Quat& rotation, const Vec3& centre,
                     Polyhedron& out) {
  const Mat3 r = rotation.toRotationMatrix();
  if (shape.type == ShapeType::Box) {
    make_box(shape, r, centre, out);
  } else {
    make_hull(*shape.hull, r, centre, out);
  }
}

}  // namespace elan::detail
