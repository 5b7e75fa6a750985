// SPDX-License-Identifier: MIT
// The static triangle mesh: validation, edge adjacency and active edges, the tree and the
// triangles in its leaf order; the ray against a triangle and against the mesh.
#include "core/base/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/base/range_checks.hpp"
#include "elan/error.hpp"

namespace elan::detail {
namespace {

// Triangles a leaf of the mesh's tree, at most. perf: leaves of 4 would make about one 32-byte
// binary node per two triangles (16 bytes a triangle, ~35 in all on a grid); up to 8 make about
// one per three (~10 bytes, ~30 in all), and the 4-wide tree collapsed from them as many bytes. A
// query tests each triangle's box before the triangle itself, so a wider leaf costs box tests
// only.
constexpr int kMeshLeafSize = 8;

// More triangles than this are refused: edge records number them 3 t + k in 32 bits.
constexpr std::size_t kMaxTriangles = std::size_t(1) << 30;

using Vec3d = Eigen::Vector3d;

std::string triangle_prefix(std::size_t t) {
  return "triangle " + std::to_string(t) + ": ";
}

void check_vertices(std::span<const Vec3> vertices) {
  if (vertices.empty()) throw Error("shape.vertices", "must have at least one vertex");
  if (vertices.size() > std::size_t(UINT32_MAX)) {
    throw Error("shape.vertices", "more than " + std::to_string(UINT32_MAX) + " vertices");
  }
  static constexpr char kAxis[] = "xyz";
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    for (int a = 0; a < 3; ++a) {
      const double x = vertices[v][a];
      if (!std::isfinite(x)) {
        throw Error("shape.vertices", "vertex " + std::to_string(v) + ": " + kAxis[a] +
                                          " is not finite (" + show_value(x) + ")");
      }
      if (!(std::fabs(x) <= limits::kMaxPosition)) {
        throw Error("shape.vertices", "vertex " + std::to_string(v) +
                                          ": each coordinate must be in [" +
                                          show_value(-limits::kMaxPosition) + ", " +
                                          show_value(limits::kMaxPosition) + "] m, got " +
                                          kAxis[a] + " = " + show_value(x));
      }
    }
  }
}

// The unit normal in double (a float cross product of a thin triangle loses its direction).
Vec3 unit_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3d ad = a.cast<double>();
  const Vec3d n = (b.cast<double>() - ad).cross(c.cast<double>() - ad);
  return n.normalized().cast<Real>();
}

// One side of a triangle: the edge k from v[k] to v[k + 1] of triangle t, keyed by its vertices
// in increasing order.
struct EdgeRecord {
  uint32_t high;    // the larger vertex index
  uint32_t corner;  // 3 t + k
};

// Active-edge flags of every triangle (input order). determinism: the edges sharing a vertex pair
// are found by a counting sort on the smaller vertex (stable, so triangle order within it) then an
// insertion sort on the larger; no hashing.
std::vector<uint8_t> find_active_edges(std::span<const Vec3> vertices,
                                       std::span<const std::array<uint32_t, 3>> triangles,
                                       std::span<const Vec3> normals) {
  const std::size_t nt = triangles.size(), nv = vertices.size();
  std::vector<uint32_t> start(nv + 1, 0);
  for (const auto& tri : triangles) {
    for (int k = 0; k < 3; ++k) ++start[std::min(tri[k], tri[(k + 1) % 3]) + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<EdgeRecord> edges(3 * nt);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < nt; ++t) {
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
        edges[fill[std::min(a, b)]++] = EdgeRecord{std::max(a, b), uint32_t(3 * t + k)};
      }
    }
  }
  std::vector<uint8_t> active(nt, 0);
  for (std::size_t v = 0; v < nv; ++v) {
    EdgeRecord* first = edges.data() + start[v];
    EdgeRecord* last = edges.data() + start[v + 1];
    // Stable insertion sort by the larger vertex: a vertex has a handful of edges.
    for (EdgeRecord* i = first + 1; i < last; ++i) {
      const EdgeRecord e = *i;
      EdgeRecord* j = i;
      while (j > first && (j - 1)->high > e.high) {
        *j = *(j - 1);
        --j;
      }
      *j = e;
    }
    for (EdgeRecord* g = first; g < last;) {
      EdgeRecord* end = g + 1;
      while (end < last && end->high == g->high) ++end;
      if (end - g == 2) {
        // Two triangles share the edge: each side is active per edge_is_active, the neighbour's
        // normal flipped if it walks the edge the same way (the two wound inconsistently).
        const uint32_t t1 = g[0].corner / 3, k1 = g[0].corner % 3;
        const uint32_t t2 = g[1].corner / 3, k2 = g[1].corner % 3;
        const bool same_way = triangles[t1][k1] == triangles[t2][k2];
        const Vec3 n2 = same_way ? Vec3(-normals[t2]) : normals[t2];
        const Vec3 e1 = vertices[triangles[t1][(k1 + 1) % 3]] - vertices[triangles[t1][k1]];
        const Vec3 e2 = vertices[triangles[t2][(k2 + 1) % 3]] - vertices[triangles[t2][k2]];
        const Vec3 n1 = same_way ? Vec3(-normals[t1]) : normals[t1];
        if (edge_is_active(normals[t1], n2, e1)) active[t1] |= uint8_t(1u << k1);
        if (edge_is_active(normals[t2], n1, e2)) active[t2] |= uint8_t(1u << k2);
      } else {
        // A boundary edge, or one shared by three or more triangles (no one neighbour to
        // smooth against).
        for (EdgeRecord* e = g; e < end; ++e)
          active[e->corner / 3] |= uint8_t(1u << (e->corner % 3));
      }
      g = end;
    }
  }
  return active;
}

}  // namespace

TriangleMesh build_triangle_mesh(std::span<const Vec3> vertices,
                                 std::span<const std::array<uint32_t, 3>> triangles) {
  check_vertices(vertices);
  if (triangles.empty()) throw Error("shape.triangles", "must have at least one triangle");
  if (triangles.size() > kMaxTriangles) {
    throw Error("shape.triangles", "more than " + std::to_string(kMaxTriangles) + " triangles");
  }
  const std::size_t nt = triangles.size();
  const uint32_t nv = uint32_t(vertices.size());
  std::vector<Vec3> normals(nt);
  std::vector<Aabb> boxes(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (tri[k] >= nv) {
        throw Error("shape.triangles", triangle_prefix(t) + "index " + std::to_string(tri[k]) +
                                           " out of range (" + std::to_string(nv) + " vertices)");
      }
    }
    for (int k = 0; k < 3; ++k) {
      if (tri[k] == tri[(k + 1) % 3]) {
        throw Error("shape.triangles",
                    triangle_prefix(t) + "repeats vertex " + std::to_string(tri[k]));
      }
    }
    const Vec3& a = vertices[tri[0]];
    const Vec3& b = vertices[tri[1]];
    const Vec3& c = vertices[tri[2]];
    // Zero area relative to the triangle's size: |cross| is twice the area, the longest edge
    // squared its scale.
    // In double from the start: a float difference of far-off corners would round.
    const Vec3d ad = a.cast<double>(), bd = b.cast<double>(), cd = c.cast<double>();
    const Vec3d ab = bd - ad, ac = cd - ad, bc = cd - bd;
    const double longest2 = std::max({ab.squaredNorm(), ac.squaredNorm(), bc.squaredNorm()});
    const Vec3d cross = ab.cross(ac);
    if (!(cross.norm() > 1e-12 * longest2)) {
      throw Error("shape.triangles", triangle_prefix(t) + "has zero area");
    }
    normals[t] = (cross / cross.norm()).cast<Real>();
    boxes[t].min = a.cwiseMin(b).cwiseMin(c);
    boxes[t].max = a.cwiseMax(b).cwiseMax(c);
  }

  TriangleMesh mesh;
  const std::vector<uint8_t> active = find_active_edges(vertices, triangles, normals);
  normals = {};
  std::vector<uint32_t> order;
  mesh.tree = collapse_to_bvh4(build_bvh(boxes, kMeshLeafSize, order));
  mesh.min = Vec3::Constant(std::numeric_limits<Real>::max());
  mesh.max = -mesh.min;
  for (const Aabb& b : boxes) {
    mesh.min = mesh.min.cwiseMin(b.min);
    mesh.max = mesh.max.cwiseMax(b.max);
  }
  mesh.vertices.assign(vertices.begin(), vertices.end());
  mesh.triangles.resize(nt);
  mesh.active_edges.resize(nt);
  for (std::size_t k = 0; k < nt; ++k) {
    mesh.triangles[k] = triangles[order[k]];
    mesh.active_edges[k] = active[order[k]];
  }
  return mesh;
}

bool ray_triangle(const Vec3& origin, const Vec3& dir, const Vec3& a, const Vec3& b, const Vec3& c,
                  Real max_t, Real& t) {
  // Moller & Trumbore 1997, in double: the barycentric tests of two triangles sharing an edge
  // then agree closely enough that a ray on the edge hits one of them.
  const Vec3d d = dir.cast<double>();
  // Differences taken in double: a float o - a would round by an ulp of the coordinates, and
  // the triangles around a vertex would then leave a crack that thin.
  const Vec3d ad = a.cast<double>();
  const Vec3d e1 = b.cast<double>() - ad, e2 = c.cast<double>() - ad;
  const Vec3d p = d.cross(e2);
  const double det = e1.dot(p);
  if (det == 0 || !std::isfinite(det)) return false;
  const double inv = 1 / det;
  const Vec3d s = origin.cast<double>() - ad;
  // The barycentric bounds are widened by kBarycentricSlack so that the triangles around an edge
  // or a vertex overlap by a hair instead of leaving a crack of rounding between them.
  constexpr double kBarycentricSlack = 1e-12;
  const double u = s.dot(p) * inv;
  if (u < -kBarycentricSlack || u > 1 + kBarycentricSlack) return false;
  const Vec3d q = s.cross(e1);
  const double v = d.dot(q) * inv;
  if (v < -kBarycentricSlack || u + v > 1 + kBarycentricSlack) return false;
  const double hit = e2.dot(q) * inv;
  if (!(hit >= 0 && hit <= double(max_t))) return false;
  t = Real(hit);
  return true;
}

bool ray_cast_mesh(const TriangleMesh& mesh, const Vec3& origin, const Vec3& dir, Real max_t,
                   SurfaceHit& hit) {
  bool found = false;
  bvh4_ray(mesh.tree, origin, dir, max_t, [&](uint32_t first, uint32_t count, Real limit) {
    for (uint32_t t = first; t < first + count; ++t) {
      const auto& tri = mesh.triangles[t];
      Real th;
      if (!ray_triangle(origin, dir, mesh.vertices[tri[0]], mesh.vertices[tri[1]],
                        mesh.vertices[tri[2]], limit, th)) {
        continue;
      }
      // determinism: a tie keeps the lower triangle, whichever the walk met first (it visits a
      // leaf entered exactly at the nearest hit so far, so every tied triangle is met).
      if (found && (th > hit.t || (th == hit.t && t > hit.triangle))) continue;
      found = true;
      hit.t = th;
      hit.triangle = t;
      limit = th;
    }
    return limit;
  });
  if (found) {
    const auto& tri = mesh.triangles[hit.triangle];
    Vec3 n = unit_normal(mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
    if (n.dot(dir) > 0) n = -n;
    hit.normal = n;
  }
  return found;
}

std::size_t mesh_bytes(const TriangleMesh& mesh) {
  return sizeof(TriangleMesh) + mesh.vertices.capacity() * sizeof(Vec3) +
         mesh.triangles.capacity() * sizeof(mesh.triangles[0]) + mesh.active_edges.capacity() +
         bvh4_bytes(mesh.tree);
}

}  // namespace elan::detail
