// SPDX-License-Identifier: MIT
// Convex hull of a point cloud: quickhull over triangles in double, then coplanar triangles merged
// into polygon faces with counter-clockwise loops, redundant vertices dropped, unique edges listed.
#include "core/base/convex_hull.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "elan/error.hpp"
#include "elan/limits.hpp"

namespace elan::detail {
namespace {

using Vec3d = Eigen::Vector3d;

// A hull is rebuilt at most this many times, the tolerance growing by kHullTolGrowth each time;
// the first attempt is quickhull's own tolerance. A merged face is within tol of its seed
// triangle's plane, so its Newell plane is within a few tol of every point on it: kConvexBand
// tolerances above a face plane still count as below it.
constexpr int kHullAttempts = 3;
constexpr double kHullTolGrowth = 16;
constexpr double kConvexBand = 8;

[[noreturn]] void fail(const std::string& message) {
  throw Error("points", message);
}

struct Tri {
  std::array<int, 3> v{};    // counter-clockwise seen from outside
  std::array<int, 3> adj{};  // adj[i]: triangle across edge (v[i], v[i+1])
  Vec3d normal = Vec3d::Zero();
  double offset = 0;
  std::vector<int> outside;  // conflict list: points strictly above this triangle (> tol)
  bool alive = true;
};

// Quickhull (Barber, Dobkin, Huhdanpaa 1996) on triangles. `tol` is the distance below which a
// point counts as on a plane: it absorbs the rounding of Real inputs, so near-coplanar points do
// not create slivers; faces within `tol` of each other are merged afterwards.
class Quickhull {
 public:
  Quickhull(std::vector<Vec3d> pts, double tol) : p_(std::move(pts)), tol_(tol) {}

  std::vector<Tri> run() {
    initial_simplex();
    // determinism: the eye point is the furthest conflict of the lowest-index triangle that has
    // any, so the result depends on the input order alone.
    for (size_t f = 0; f < tris_.size(); ++f) {
      while (tris_[f].alive && !tris_[f].outside.empty()) add_point(f);
    }
    // Compact the live triangles and renumber their adjacency.
    std::vector<int> index(tris_.size(), -1);
    std::vector<Tri> out;
    for (size_t f = 0; f < tris_.size(); ++f) {
      if (!tris_[f].alive) continue;
      index[f] = static_cast<int>(out.size());
      out.push_back(std::move(tris_[f]));
    }
    for (Tri& t : out) {
      for (int& a : t.adj) a = index[a];
    }
    return out;
  }

 private:
  double dist(const Tri& t, int i) const { return t.normal.dot(p_[i]) - t.offset; }

  void set_plane(Tri& t) const {
    const Vec3d& a = p_[t.v[0]];
    Vec3d n = (p_[t.v[1]] - a).cross(p_[t.v[2]] - a);
    const double len = n.norm();
    t.normal = len > 0 ? Vec3d(n / len) : Vec3d::Zero();
    t.offset = t.normal.dot(a);
  }

  void initial_simplex() {
    const int n = static_cast<int>(p_.size());
    // Extreme points along the axes; the widest pair among them spans the first edge.
    std::array<int, 6> ext{};
    for (int axis = 0; axis < 3; ++axis) {
      for (int i = 0; i < n; ++i) {
        if (p_[i][axis] < p_[ext[2 * axis]][axis]) ext[2 * axis] = i;
        if (p_[i][axis] > p_[ext[2 * axis + 1]][axis]) ext[2 * axis + 1] = i;
      }
    }
    int i0 = ext[0], i1 = ext[1];
    double best = -1;
    for (int a = 0; a < 6; ++a) {
      for (int b = a + 1; b < 6; ++b) {
        const double d2 = (p_[ext[a]] - p_[ext[b]]).squaredNorm();
        if (d2 > best) best = d2, i0 = ext[a], i1 = ext[b];
      }
    }
    if (std::sqrt(best) <= tol_) fail("all points coincide; a hull needs volume");

    const Vec3d dir = (p_[i1] - p_[i0]).normalized();
    int i2 = -1;
    best = tol_;
    for (int i = 0; i < n; ++i) {
      const Vec3d r = p_[i] - p_[i0];
      const double d = (r - dir * dir.dot(r)).norm();
      if (d > best) best = d, i2 = i;
    }
    if (i2 < 0) fail("all points are collinear; a hull needs volume");

    const Vec3d pn = (p_[i1] - p_[i0]).cross(p_[i2] - p_[i0]).normalized();
    int i3 = -1;
    best = tol_;
    for (int i = 0; i < n; ++i) {
      const double d = std::abs(pn.dot(p_[i] - p_[i0]));
      if (d > best) best = d, i3 = i;
    }
    if (i3 < 0) fail("all points are coplanar; a hull needs volume");

    // Orient the base (i0, i1, i2) so that i3 is below it, i.e. the base faces outward.
    if (pn.dot(p_[i3] - p_[i0]) > 0) std::swap(i1, i2);
    const std::array<std::array<int, 3>, 4> faces = {
        {{i0, i1, i2}, {i0, i3, i1}, {i1, i3, i2}, {i2, i3, i0}}};
    for (const auto& f : faces) {
      Tri t;
      t.v = f;
      set_plane(t);
      tris_.push_back(std::move(t));
    }
    link_all();
    for (int i = 0; i < n; ++i) {
      if (i == i0 || i == i1 || i == i2 || i == i3) continue;
      assign(i, 0, tris_.size());
    }
  }

  // Adjacency by matching each directed edge with its reverse.
  void link_all() {
    std::map<std::pair<int, int>, std::pair<int, int>> edge;
    for (int f = 0; f < static_cast<int>(tris_.size()); ++f) {
      for (int e = 0; e < 3; ++e) edge[{tris_[f].v[e], tris_[f].v[(e + 1) % 3]}] = {f, e};
    }
    for (int f = 0; f < static_cast<int>(tris_.size()); ++f) {
      for (int e = 0; e < 3; ++e) {
        tris_[f].adj[e] = edge.at({tris_[f].v[(e + 1) % 3], tris_[f].v[e]}).first;
      }
    }
  }

  // Gives point i to the first triangle in [first, last) it lies strictly above; a point above
  // none of them is inside the hull (or within tol of it) and is dropped.
  void assign(int i, size_t first, size_t last) {
    for (size_t f = first; f < last; ++f) {
      if (tris_[f].alive && dist(tris_[f], i) > tol_) {
        tris_[f].outside.push_back(i);
        return;
      }
    }
  }

  void add_point(size_t seed) {
    Tri& s = tris_[seed];
    int eye = s.outside[0];
    double far = dist(s, eye);
    for (int i : s.outside) {
      const double d = dist(s, i);
      if (d > far) far = d, eye = i;
    }
    const Vec3d& pe = p_[eye];

    // Visible set: flood from the seed across triangles the eye is above; its boundary against
    // the rest is the horizon, each edge kept with the orientation of its visible triangle.
    std::vector<int> visible{static_cast<int>(seed)};
    std::vector<char> mark(tris_.size(), 0);
    mark[seed] = 1;
    struct Edge {
      int a, b, beyond;
    };
    std::vector<Edge> horizon;
    for (size_t k = 0; k < visible.size(); ++k) {
      const Tri& t = tris_[visible[k]];
      for (int e = 0; e < 3; ++e) {
        const int nb = t.adj[e];
        if (mark[nb] == 1) continue;
        if (mark[nb] == 0 && tris_[nb].normal.dot(pe) - tris_[nb].offset > tol_) {
          mark[nb] = 1;
          visible.push_back(nb);
        } else {
          mark[nb] = 2;
          horizon.push_back({t.v[e], t.v[(e + 1) % 3], nb});
        }
      }
    }
    // A horizon seen through tolerance can, in pathological clouds, fail to be one simple loop;
    // a hull built from it would not be closed, so refuse the cloud rather than return garbage.
    std::map<int, int> from;  // horizon start vertex -> index into horizon
    for (size_t k = 0; k < horizon.size(); ++k) {
      if (!from.emplace(horizon[k].a, static_cast<int>(k)).second) {
        fail("numerically degenerate cloud (horizon is not a simple loop)");
      }
    }
    size_t walked = 0;
    for (int v = horizon[0].a; walked <= horizon.size(); ++walked) {
      const auto it = from.find(horizon[from.at(v)].b);
      if (it == from.end()) fail("numerically degenerate cloud (horizon is not closed)");
      v = it->first;
      if (v == horizon[0].a) break;
    }
    if (walked + 1 != horizon.size()) fail("numerically degenerate cloud (horizon has holes)");
    const int first_new = static_cast<int>(tris_.size());
    std::vector<int> freed;
    for (int f : visible) {
      tris_[f].alive = false;
      freed.insert(freed.end(), tris_[f].outside.begin(), tris_[f].outside.end());
      tris_[f].outside.clear();
    }
    for (const Edge& h : horizon) {
      Tri t;
      t.v = {h.a, h.b, eye};
      set_plane(t);
      t.adj[0] = h.beyond;
      t.adj[1] = first_new + from.at(h.b);
      Tri& beyond = tris_[h.beyond];
      for (int e = 0; e < 3; ++e) {
        if (beyond.v[e] == h.b && beyond.v[(e + 1) % 3] == h.a) {
          beyond.adj[e] = static_cast<int>(tris_.size());
        }
      }
      tris_.push_back(std::move(t));
    }
    for (size_t k = first_new; k < tris_.size(); ++k) tris_[tris_[k].adj[1]].adj[2] = int(k);
    for (int i : freed) {
      if (i != eye) assign(i, first_new, tris_.size());
    }
  }

  std::vector<Vec3d> p_;
  double tol_;
  std::vector<Tri> tris_;
};

// Merges adjacent triangles lying within tol of a common plane into polygons. Each group grows
// from its largest remaining triangle and accepts a neighbour only if all its corners are within
// tol of the seed's plane, so a gently curved cloud is not flattened by a chain of small bends.
struct Polygon {
  Vec3d normal = Vec3d::Zero();
  std::vector<int> loop;
};

std::vector<Polygon> merge_coplanar(const std::vector<Tri>& tris, const std::vector<Vec3d>& p,
                                    double tol) {
  const int nt = static_cast<int>(tris.size());
  std::vector<double> area(nt);
  std::vector<int> order(nt);
  for (int f = 0; f < nt; ++f) {
    const Tri& t = tris[f];
    area[f] = (p[t.v[1]] - p[t.v[0]]).cross(p[t.v[2]] - p[t.v[0]]).norm();
    order[f] = f;
  }
  // determinism: stable sort keeps ties in triangle order.
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return area[a] > area[b]; });

  std::vector<int> group(nt, -1);
  std::vector<Polygon> out;
  for (int seed : order) {
    if (group[seed] >= 0) continue;
    const int g = static_cast<int>(out.size());
    const Vec3d n = tris[seed].normal;
    const double off = tris[seed].offset;
    std::vector<int> members{seed};
    group[seed] = g;
    for (size_t k = 0; k < members.size(); ++k) {
      for (int nb : tris[members[k]].adj) {
        if (group[nb] >= 0 || tris[nb].normal.dot(n) <= 0) continue;
        bool flat = true;
        for (int v : tris[nb].v) flat = flat && std::abs(n.dot(p[v]) - off) <= tol;
        if (flat) {
          group[nb] = g;
          members.push_back(nb);
        }
      }
    }
    // Boundary edges of the group (those whose twin is outside it) chained into one loop. A
    // group whose boundary is not a single simple loop is split back into its triangles.
    std::map<int, int> next;
    bool simple = true;
    size_t boundary = 0;
    for (int f : members) {
      for (int e = 0; e < 3; ++e) {
        if (group[tris[f].adj[e]] == g) continue;
        ++boundary;
        simple = simple && next.emplace(tris[f].v[e], tris[f].v[(e + 1) % 3]).second;
      }
    }
    Polygon poly;
    if (simple) {
      int v = next.begin()->first;
      do {
        poly.loop.push_back(v);
        v = next.at(v);
      } while (v != poly.loop[0] && poly.loop.size() <= boundary);
      simple = poly.loop.size() == boundary && v == poly.loop[0];
    }
    if (!simple) {
      for (size_t k = 1; k < members.size(); ++k) group[members[k]] = -1;
      members.resize(1);
      poly.loop.assign(tris[seed].v.begin(), tris[seed].v.end());
    }
    poly.normal = n;
    out.push_back(std::move(poly));
  }
  return out;
}

// Newell's normal of a polygon loop: robust for non-planar and nearly degenerate loops.
Vec3d newell_normal(const std::vector<int>& loop, const std::vector<Vec3d>& p) {
  Vec3d n = Vec3d::Zero();
  for (size_t k = 0; k < loop.size(); ++k) {
    const Vec3d& a = p[loop[k]];
    const Vec3d& b = p[loop[(k + 1) % loop.size()]];
    n += Vec3d((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
               (a.x() - b.x()) * (a.y() + b.y()));
  }
  return n;
}

// Quickhull's triangles at tolerance `tol`, merged into polygon faces, without the vertices that
// only lie on an edge.
std::vector<Polygon> hull_polygons(const std::vector<Vec3d>& p, double tol) {
  const std::vector<Tri> tris = Quickhull(p, tol).run();
  std::vector<Polygon> polys = merge_coplanar(tris, p, tol);

  // A vertex on only two faces lies on their common edge (an input point on a hull edge that
  // quickhull kept): it is not an extreme point. It leaves both loops or neither (a loop keeps
  // three vertices), so the two faces still share the shortened edge.
  std::vector<std::vector<int>> faces_of(p.size());
  for (int f = 0; f < static_cast<int>(polys.size()); ++f) {
    for (int v : polys[f].loop) faces_of[v].push_back(f);
  }
  for (size_t v = 0; v < p.size(); ++v) {
    const std::vector<int>& fs = faces_of[v];
    if (fs.size() != 2 || polys[fs[0]].loop.size() <= 3 || polys[fs[1]].loop.size() <= 3) continue;
    for (int f : fs) std::erase(polys[f].loop, static_cast<int>(v));
  }
  return polys;
}

struct FacePlane {
  Vec3d normal;
  double offset;
};

// A face's unit Newell normal, and as offset its vertices' largest height, so every vertex of
// the loop satisfies dot(n, x) <= offset.
FacePlane face_plane(const Polygon& f, const std::vector<Vec3d>& p) {
  Vec3d n = newell_normal(f.loop, p);
  n = n.norm() > 0 ? Vec3d(n.normalized()) : f.normal;
  double off = -std::numeric_limits<double>::infinity();
  for (int v : f.loop) off = std::max(off, n.dot(p[v]));
  return {n, off};
}

// Whether every point lies below every face plane, or above it by at most `band`: the faces
// bound a convex solid holding the cloud.
bool points_below(const std::vector<FacePlane>& planes, const std::vector<Vec3d>& p, double band) {
  for (const FacePlane& f : planes) {
    for (const Vec3d& q : p) {
      if (!(f.normal.dot(q) - f.offset <= band)) return false;
    }
  }
  return true;
}

}  // namespace

ConvexHull build_convex_hull(std::span<const Vec3> points) {
  if (points.size() < 4) {
    fail("a convex hull needs at least 4 points, got " + std::to_string(points.size()));
  }
  std::vector<Vec3d> p;
  p.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) fail("point " + std::to_string(i) + " is not finite");
    // No point of a supported shape lies past the supported positions (elan/limits.hpp); past
    // them, clouds spanning 1e-40 to 1e30 defeated the relative tolerance (found by fuzz_hull).
    if (!(points[i].cwiseAbs().maxCoeff() <= Real(limits::kMaxPosition))) {
      fail("point " + std::to_string(i) + " is farther than " +
           std::to_string(int(limits::kMaxPosition)) + " m from the origin");
    }
    p.push_back(points[i].cast<double>());
  }
  // Tolerance relative to the cloud's magnitude (as in qhull): rounding of Real coordinates is
  // proportional to their size, so a cloud far from the origin gets a proportionally wider band.
  Vec3d max_abs = Vec3d::Zero();
  for (const Vec3d& q : p) max_abs = max_abs.cwiseMax(q.cwiseAbs());
  const double base_tol = 32 * double(std::numeric_limits<Real>::epsilon()) * max_abs.sum();

  // A cloud with points closer together than a few tolerances (two points 6e-5 m apart in a
  // 4 m cloud, found by fuzz_narrowphase) can come out of quickhull and the merge folded: two
  // faces lying back to back, with hull points metres above a face's plane. The SAT trusts
  // every face plane to bound the solid, and reads such a face as a separating axis of shapes
  // that overlap. So the result is checked (every input point below every face plane, within a
  // band of a few tolerances), and a cloud that fails is rebuilt with a wider tolerance, which
  // absorbs the near-coincident points; one that still fails is refused.
  std::vector<Polygon> polys;
  std::vector<FacePlane> planes;
  bool convex = false;
  for (int attempt = 0; attempt < kHullAttempts && !convex; ++attempt) {
    const double tol = base_tol * std::pow(kHullTolGrowth, attempt);
    polys = hull_polygons(p, tol);
    planes.clear();
    for (const Polygon& f : polys) planes.push_back(face_plane(f, p));
    convex = points_below(planes, p, kConvexBand * tol);
  }
  if (!convex) fail("numerically degenerate cloud (no convex hull within the tolerance)");

  // Renumber the vertices in order of first appearance in the input.
  std::vector<int> new_index(p.size(), -1);
  for (const Polygon& f : polys) {
    for (int v : f.loop) new_index[v] = 0;
  }
  ConvexHull hull;
  for (size_t i = 0; i < p.size(); ++i) {
    if (new_index[i] < 0) continue;
    new_index[i] = static_cast<int>(hull.vertices.size());
    hull.vertices.push_back(points[i]);
  }
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (std::size_t i = 0; i < polys.size(); ++i) {
    const Polygon& f = polys[i];
    HullFace face;
    face.normal = planes[i].normal.cast<Real>();
    face.offset = Real(planes[i].offset);
    face.first = static_cast<uint32_t>(hull.face_vertices.size());
    face.count = static_cast<uint32_t>(f.loop.size());
    for (size_t k = 0; k < f.loop.size(); ++k) {
      const auto a = static_cast<uint32_t>(new_index[f.loop[k]]);
      const auto b = static_cast<uint32_t>(new_index[f.loop[(k + 1) % f.loop.size()]]);
      hull.face_vertices.push_back(a);
      edges.emplace(std::make_pair(std::min(a, b), std::max(a, b)), 0);
    }
    hull.faces.push_back(face);
  }
  for (const auto& e : edges) hull.edges.push_back({e.first.first, e.first.second});
  // A closed convex polyhedron has at least a tetrahedron's features and V - E + F = 2. A cloud
  // whose coordinates span many orders of magnitude (1e-30 beside 1e30) has its small
  // differences inside the relative tolerance, and quickhull can then return fewer faces than a
  // solid: refused as flat rather than handed to the narrowphase (found by fuzz_hull).
  const std::size_t nv = hull.vertices.size(), ne = hull.edges.size(), nf = hull.faces.size();
  if (nv < 4 || nf < 4 || nv + nf != ne + 2) {
    fail("the points are coplanar or collinear within the tolerance of their magnitude");
  }
  compute_edge_faces(hull);
  return hull;
}

void compute_edge_faces(ConvexHull& hull) {
  // Directed edge u -> v of every face loop, sorted, then one lookup per undirected edge.
  std::vector<std::array<uint32_t, 3>> directed;  // u, v, face
  for (uint32_t f = 0; f < hull.faces.size(); ++f) {
    const HullFace& face = hull.faces[f];
    for (uint32_t k = 0; k < face.count; ++k) {
      directed.push_back({hull.face_vertices[face.first + k],
                          hull.face_vertices[face.first + (k + 1) % face.count], f});
    }
  }
  std::sort(directed.begin(), directed.end());
  const auto face_of = [&](uint32_t u, uint32_t v) -> uint32_t {
    const auto it =
        std::lower_bound(directed.begin(), directed.end(), std::array<uint32_t, 3>{u, v, 0});
    return (it != directed.end() && (*it)[0] == u && (*it)[1] == v) ? (*it)[2] : 0;
  };
  hull.edge_faces.resize(hull.edges.size());
  for (std::size_t e = 0; e < hull.edges.size(); ++e) {
    const auto [u, v] = hull.edges[e];
    hull.edge_faces[e] = {face_of(u, v), face_of(v, u)};
  }
}

ConvexHull transform_hull(const ConvexHull& hull, const Vec3& origin, const Mat3& rotation) {
  ConvexHull out = hull;
  for (Vec3& v : out.vertices) v = rotation * (v - origin);
  for (HullFace& f : out.faces) {
    f.normal = (rotation * f.normal).normalized();
    // Recompute as in build_convex_hull: the largest vertex height along the new normal.
    Real off = -std::numeric_limits<Real>::infinity();
    for (uint32_t k = 0; k < f.count; ++k) {
      off = std::max(off, f.normal.dot(out.vertices[out.face_vertices[f.first + k]]));
    }
    f.offset = off;
  }
  return out;
}

}  // namespace elan::detail
