// SPDX-License-Identifier: MIT
// EPA, the Expanding Polytope Algorithm (van den Bergen 2001, "Proximity queries and penetration
// depth computation on 3D game objects"): penetration depth, normal and witness points of
// overlapping convex shapes, run on their cores (radii added after) in fixed-size buffers.
#include <cmath>
#include <limits>

#include "narrowphase/any_perpendicular.hpp"
#include "narrowphase/gjk.hpp"
#include "narrowphase/minkowski.hpp"

namespace elan::detail {
namespace {

constexpr Real kEpaEps = std::numeric_limits<Real>::epsilon();
constexpr Real kInf = std::numeric_limits<Real>::infinity();
// perf: fixed buffers, no allocation per call. A closed triangulated polytope with V vertices
// has 2V - 4 faces (Euler), so kMaxFaces never overflows; the horizon walk may list each edge of
// every removed face once before cancelling shared ones.
constexpr int kMaxVertices = 64;
constexpr int kMaxFaces = 2 * kMaxVertices;
constexpr int kMaxEdges = 3 * kMaxFaces;
constexpr int kEpaMaxIterations = kMaxVertices;
// Converged when the support along the closest face's normal lies within this fraction of the
// face's distance (plus a rounding floor relative to the polytope's size).
constexpr Real kEpaRelTol = sizeof(Real) == 4 ? Real(1e-5) : Real(1e-10);

struct Face {
  int v[3];
  Vec3 n;  // unit outward normal (zero for a sliver)
  Real d;  // distance of the face's plane from the origin, kInf for a sliver
  bool alive;
};

struct Polytope {
  SimplexVertex vert[kMaxVertices];
  int vertex_count = 0;
  Face face[kMaxFaces];
  int face_count = 0;
};

// Adds face (i, j, k) with its normal turned away from `inner` (a point inside the polytope).
void set_face(Polytope& p, int slot, int i, int j, int k, const Vec3* inner) {
  Face& f = p.face[slot];
  const Vec3& a = p.vert[i].w;
  Vec3 n = (p.vert[j].w - a).cross(p.vert[k].w - a);
  if (inner && n.dot(*inner - a) > 0) std::swap(j, k), n = -n;
  f.v[0] = i, f.v[1] = j, f.v[2] = k;
  f.alive = true;
  const Real len = n.norm();
  if (len > 0) {
    f.n = n / len;
    f.d = f.n.dot(a);
  } else {
    f.n = Vec3::Zero();
    f.d = kInf;
  }
}

int free_face_slot(Polytope& p) {
  for (int i = 0; i < p.face_count; ++i) {
    if (!p.face[i].alive) return i;
  }
  return p.face_count < kMaxFaces ? p.face_count++ : -1;
}

// Barycentric weights of p's projection on triangle abc (Ericson, Real-Time Collision Detection
// 3.4), clamped to the triangle so rounding outside an edge cannot extrapolate the witnesses.
void barycentric(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p, Real out[3]) {
  const Vec3 e0 = b - a, e1 = c - a, e2 = p - a;
  const Real d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const Real d20 = e2.dot(e0), d21 = e2.dot(e1);
  const Real den = d00 * d11 - d01 * d01;
  if (!(den > 0)) {
    out[0] = 1, out[1] = 0, out[2] = 0;
    return;
  }
  Real v = (d11 * d20 - d01 * d21) / den;
  Real w = (d00 * d21 - d01 * d20) / den;
  Real u = 1 - v - w;
  u = std::max(u, Real(0)), v = std::max(v, Real(0)), w = std::max(w, Real(0));
  const Real sum = u + v + w;
  out[0] = u / sum, out[1] = v / sum, out[2] = w / sum;
}

// Result for a Minkowski difference of zero volume (flat cores, e.g. two points or parallel
// segments): the origin lies in its affine hull, so depth 0 along the hull's normal.
EpaResult flat_result(const Simplex& s, int count, const Vec3& normal) {
  EpaResult r;
  r.ok = true;
  r.depth = 0;
  r.normal = normal;
  for (int i = 0; i < count; ++i) r.point_a += s.lambda[i] * s.v[i].a;
  for (int i = 0; i < count; ++i) r.point_b += s.lambda[i] * s.v[i].b;
  return r;
}

// EPA over any support of the Minkowski difference: minkowski(d) is the SimplexVertex of A's
// support along d and B's along -d.
// `extent`: a bound on the difference's distance from the origin (the centres' distance plus the
// bounding radii), the scale of the rounding floors. perf: the bound costs no support; the
// difference's own extent along the axes would cost six.
template <class Support>
EpaResult run_epa(const Support& minkowski, const Simplex& simplex, Real extent) {
  Polytope p;
  Real scale = extent;
  for (int i = 0; i < simplex.count; ++i) scale = std::max(scale, simplex.v[i].w.norm());
  // Blow GJK's simplex up to a tetrahedron: each new support point must leave the affine hull
  // of the current ones. The origin is in (or on) GJK's simplex, hence in the tetrahedron.
  Simplex base = simplex;
  if (base.count == 0) {
    base.count = 1, base.lambda[0] = 1;
    base.v[0] = minkowski(Vec3::UnitY());
  }
  for (int i = 0; i < std::min(base.count, 4); ++i) p.vert[p.vertex_count++] = base.v[i];
  static const Vec3 kAxes[6] = {Vec3::UnitX(),  -Vec3::UnitX(), Vec3::UnitY(),
                                -Vec3::UnitY(), Vec3::UnitZ(),  -Vec3::UnitZ()};
  const Real tol_dim = Real(1e3) * kEpaEps * std::max(scale, std::numeric_limits<Real>::min());
  while (p.vertex_count < 4) {
    const Vec3 o = p.vert[0].w;
    Vec3 dirs[6];
    int dir_count = 0;
    Vec3 flat_normal = Vec3::UnitY();
    if (p.vertex_count == 1) {
      for (const Vec3& d : kAxes) dirs[dir_count++] = d;
    } else if (p.vertex_count == 2) {
      const Vec3 t = p.vert[1].w - o;
      const Vec3 u = any_perpendicular(t);
      const Vec3 v = t.normalized().cross(u);
      dirs[0] = u, dirs[1] = -u, dirs[2] = v, dirs[3] = -v;
      dir_count = 4;
      flat_normal = u;
    } else {
      const Vec3 n = (p.vert[1].w - o).cross(p.vert[2].w - o).normalized();
      dirs[0] = n, dirs[1] = -n;
      dir_count = 2;
      flat_normal = n;
    }
    // Distance of w from the affine hull of the current vertices.
    auto offset = [&](const Vec3& w) {
      const Vec3 r = w - o;
      if (p.vertex_count == 1) return r.norm();
      if (p.vertex_count == 2) {
        const Vec3 t = (p.vert[1].w - o).normalized();
        return (r - t * t.dot(r)).norm();
      }
      return std::abs(r.dot(dirs[0]));
    };
    int best = -1;
    Real best_off = tol_dim;
    SimplexVertex cand[6];
    for (int i = 0; i < dir_count; ++i) {
      cand[i] = minkowski(dirs[i]);
      const Real off = offset(cand[i].w);
      if (off > best_off) best_off = off, best = i;
    }
    if (best < 0) return flat_result(simplex, simplex.count, flat_normal);
    p.vert[p.vertex_count++] = cand[best];
  }

  const Vec3 centre = (p.vert[0].w + p.vert[1].w + p.vert[2].w + p.vert[3].w) / 4;
  set_face(p, 0, 0, 1, 2, &centre);
  set_face(p, 1, 0, 3, 1, &centre);
  set_face(p, 2, 0, 2, 3, &centre);
  set_face(p, 3, 1, 3, 2, &centre);
  p.face_count = 4;

  // The answer is read from a copy of the closest face, taken before the expansion kills it and
  // may reuse its slot: when a budget ends the loop halfway through an expansion, the answer is
  // still a face of the last whole polytope (finite distance, unit normal), not whatever the
  // slot holds by then.
  Face answer{{0, 0, 0}, Vec3::UnitY(), kInf, false};
  bool have_answer = false;
  // The least support h(n) = max over the difference of n . w seen along a chosen face normal:
  // moving B by h(n) along n separates the shapes, so h(n) bounds the depth from above, as the
  // closest face's distance bounds it from below.
  Real upper_d = kInf;
  Vec3 upper_n = Vec3::UnitY();
  Vec3 upper_a = Vec3::Zero(), upper_b = Vec3::Zero();  // A's and B's supports along upper_n
  bool broken = false;
  int edges[kMaxEdges][2];
  for (int iter = 0; iter < kEpaMaxIterations; ++iter) {
    // determinism: lowest slot wins ties. Slivers (d = kInf) are never chosen.
    int best = -1;
    Real best_d = kInf;
    for (int i = 0; i < p.face_count; ++i) {
      if (p.face[i].alive && p.face[i].d < best_d) best_d = p.face[i].d, best = i;
    }
    if (best < 0) break;
    answer = p.face[best];
    have_answer = true;
    const Face& f = answer;
    const SimplexVertex w = minkowski(f.n);
    const Real upper = w.w.dot(f.n);
    if (upper < upper_d) upper_d = upper, upper_n = f.n, upper_a = w.a, upper_b = w.b;
    const Real gap = upper - f.d;
    if (gap <= kEpaRelTol * std::abs(f.d) + 16 * kEpaEps * scale) break;
    if (p.vertex_count == kMaxVertices) break;
    const int wi = p.vertex_count++;
    p.vert[wi] = w;
    // Remove every face that sees w; the edges bordering the removed region (the horizon) are
    // those listed once, as a shared edge is listed in both directions and cancels.
    int edge_count = 0;
    for (int i = 0; i < p.face_count; ++i) {
      Face& g = p.face[i];
      if (!g.alive) continue;
      if (i != best && !(g.n.dot(w.w - p.vert[g.v[0]].w) > 0)) continue;
      g.alive = false;
      for (int e = 0; e < 3; ++e) {
        const int u = g.v[e], v = g.v[(e + 1) % 3];
        int found = -1;
        for (int k = 0; k < edge_count; ++k) {
          if (edges[k][0] == v && edges[k][1] == u) found = k;
        }
        if (found >= 0) {
          edges[found][0] = edges[edge_count - 1][0];
          edges[found][1] = edges[edge_count - 1][1];
          --edge_count;
        } else if (edge_count < kMaxEdges) {
          edges[edge_count][0] = u, edges[edge_count][1] = v, ++edge_count;
        } else {
          broken = true;  // a horizon edge lost: the polytope would not be closed
        }
      }
    }
    bool full = false;
    bool inverted = false;
    for (int k = 0; k < edge_count; ++k) {
      const int slot = free_face_slot(p);
      if (slot < 0) {
        full = true;
        break;
      }
      // Horizon edges keep their winding, so the new faces stay outward.
      set_face(p, slot, edges[k][0], edges[k][1], wi, nullptr);
      // ... unless rounding decided the visibility of a face nearly coplanar with w (the flat
      // cap of a cylinder gives many): then the horizon is wrong and a new face turns towards
      // `centre`, which stays inside the growing polytope. Such a polytope is no longer convex
      // (its faces' distances no longer bound the depth from below), so the expansion stops and
      // the answer is the face closest before it.
      const Face& g = p.face[slot];
      inverted = inverted || g.n.dot(centre - p.vert[g.v[0]].w) > 0;
    }
    if (inverted) break;
    if (full) broken = true;
    if (broken) break;
  }
  if (!have_answer) return flat_result(simplex, simplex.count, Vec3::UnitY());
  if (broken && upper_d < kInf) {
    // The face or edge buffer ran out: rounding made the horizon of some expansion other than one
    // simple loop, the polytope is no longer closed, and its closest face need not bound the depth
    // from below. The least upper bound found is still a correct answer: a unit normal along which
    // B moves out by a finite depth, with A's and B's supports along it as witnesses.
    EpaResult r;
    r.ok = true;
    r.depth = std::max(upper_d, Real(0));
    r.normal = upper_n;
    r.point_a = upper_a;
    r.point_b = upper_b;
    return r;
  }

  const Face& f = answer;
  EpaResult r;
  r.ok = true;
  r.depth = std::max(f.d, Real(0));
  r.normal = f.n;
  Real l[3];
  barycentric(p.vert[f.v[0]].w, p.vert[f.v[1]].w, p.vert[f.v[2]].w, f.n * f.d, l);
  r.point_a = l[0] * p.vert[f.v[0]].a + l[1] * p.vert[f.v[1]].a + l[2] * p.vert[f.v[2]].a;
  r.point_b = l[0] * p.vert[f.v[0]].b + l[1] * p.vert[f.v[1]].b + l[2] * p.vert[f.v[2]].b;
  return r;
}

}  // namespace

EpaResult epa_placed(const PlacedShape& a, const PlacedShape& b, const Simplex& simplex) {
  const Real extent =
      (b.position - a.position).norm() + a.shape->bounding_radius + b.shape->bounding_radius;
  return run_epa([&](const Vec3& d) { return support_minkowski(a, b, d); }, simplex, extent);
}

EpaResult epa_triangle(const PlacedShape& a, const Vec3 (&triangle)[3], const Simplex& simplex) {
  Real corner = 0;
  for (const Vec3& c : triangle) corner = std::max(corner, (c - a.position).norm());
  return run_epa([&](const Vec3& d) { return support_minkowski_triangle(a, triangle, d); }, simplex,
                 corner + a.shape->bounding_radius);
}

EpaResult epa_penetration(const Shape& a, const Transform& xa, const Shape& b,
                          const Transform& xb) {
  // Work on the cores: rounded shapes are exact there (depth = core depth + radii) and EPA does
  // not have to tessellate a sphere.
  const PlacedShape pa = place(a, xa, false);
  const PlacedShape pb = place(b, xb, false);
  Simplex s;
  const GjkResult g = gjk_placed(pa, pb, xb.position - xa.position, s);
  return epa_after_gjk(pa, pb, g, s);
}

EpaResult epa_after_gjk(const PlacedShape& pa, const PlacedShape& pb, const GjkResult& g,
                        const Simplex& s) {
  const Shape& a = *pa.shape;
  const Shape& b = *pb.shape;
  const Real radii = core_radius(a) + core_radius(b);
  const Real scale = std::max((g.point_a - pa.position).norm(), (g.point_b - pb.position).norm());
  EpaResult r;
  if (!g.overlap && g.distance > 16 * kEpaEps * scale) {
    // Cores apart: the rounded shapes overlap by radii - distance along the core normal.
    r.normal = (g.point_b - g.point_a) / g.distance;
    r.ok = g.distance < radii;
    r.depth = r.ok ? radii - g.distance : Real(0);
    r.point_a = g.point_a + core_radius(a) * r.normal;
    r.point_b = g.point_b - core_radius(b) * r.normal;
    return r;
  }
  r = epa_placed(pa, pb, s);
  r.depth += radii;
  r.point_a += core_radius(a) * r.normal;
  r.point_b -= core_radius(b) * r.normal;
  return r;
}

}  // namespace elan::detail
