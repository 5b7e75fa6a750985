// SPDX-License-Identifier: MIT
// GJK distance (Gilbert, Johnson, Keerthi 1988) on the support of the Minkowski difference, with
// the signed-volumes sub-algorithm of Montanari, Petrella, Mezzetti (2017) for the simplex.
#include "narrowphase/gjk.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "narrowphase/closest_on_triangle.hpp"
#include "narrowphase/minkowski.hpp"

namespace elan::detail {
namespace {

// Relative gap ||v||^2 - v.w <= kRelTol ||v||^2 bounds the distance's relative error by kRelTol
// (van den Bergen 2003, 4.3.4); a few hundred ulps above the rounding of the dot products.
constexpr Real kRelTol = sizeof(Real) == 4 ? Real(1e-5) : Real(1e-10);
// Origin within this fraction of the simplex's size counts as on it: overlap (touching).
constexpr Real kOnSimplex = 8 * kEps;
constexpr int kMaxIterations = 64;
// Times a search may go on from its simplex's own closest point solved in double (run_gjk). A
// sliver near a curved side (a sphere's) stalls the float solvers again after each: the
// fuzz findings of docs/fuzzing.md needed up to 8.
constexpr int kMaxRefines = 8;
// A search whose float solvers make no progress while the distance may still be off by more
// than kStuckRelGap of itself plus kStuckAbsGap of the simplex's size (its longest vertex) is
// solved again in double (run_gjk). The first is 10 times the convergence tolerance, and within
// the fuzz oracle's band; the second is about 100 float roundings of a support. perf: below them
// the rounding that stops the search is the float solvers' ordinary noise near convergence (two
// bodies touching: v at a hundred micrometres, supports at metres), which most scenes meet every
// step, and going on buys nothing. The same band is a contact's precision (gjk_contact).
constexpr Real kStuckRelGap = sizeof(Real) == 4 ? Real(1e-4) : Real(1e-9);
constexpr Real kStuckAbsGap = sizeof(Real) == 4 ? Real(1e-5) : Real(1e-14);

bool same_sign(Real a, Real b) {
  return (a > 0 && b > 0) || (a < 0 && b < 0);
}

int largest_axis(const Vec3& v) {
  const Vec3 a = v.cwiseAbs();
  return a.x() >= a.y() ? (a.x() >= a.z() ? 0 : 2) : (a.y() >= a.z() ? 1 : 2);
}

// Closest point of a sub-simplex to the origin: indices into the caller's vertices and weights.
struct SubSimplex {
  int count = 0;
  int index[4] = {0, 0, 0, 0};
  Real lambda[4] = {0, 0, 0, 0};
  Vec3 v = Vec3::Zero();
};

// The solvers read the simplex's vertices in place (`v[i].w`). perf: copied into an array of
// Vec3 first, GCC moved them eight bytes at a time, so every other one straddled two stores and
// its load waited for both (a failed store forwarding).
void set_vertex(SubSimplex& r, const SimplexVertex* v, int i) {
  r.count = 1;
  r.index[0] = i;
  r.lambda[0] = 1;
  r.v = v[i].w;
}

// Segment: barycentric weights from the 1D coordinates along the axis of largest extent, which
// keeps the signs of the weights exact enough to pick the right Voronoi region (Montanari S1D).
void solve_segment(const SimplexVertex* v, int i0, int i1, SubSimplex& r) {
  const Vec3& s1 = v[i0].w;
  const Vec3& s2 = v[i1].w;
  const Vec3 t = s2 - s1;
  const Real tt = t.squaredNorm();
  if (!(tt > 0)) return set_vertex(r, v, i0);
  const Vec3 p0 = s1 - t * (s1.dot(t) / tt);
  const int k = largest_axis(t);
  const Real mu = s1[k] - s2[k];
  const Real c1 = p0[k] - s2[k];  // weight of s1, times mu
  const Real c2 = s1[k] - p0[k];  // weight of s2, times mu
  if (same_sign(mu, c1) && same_sign(mu, c2)) {
    r.count = 2;
    r.index[0] = i0;
    r.index[1] = i1;
    r.lambda[0] = c1 / mu;
    r.lambda[1] = c2 / mu;
    r.v = r.lambda[0] * s1 + r.lambda[1] * s2;
    return;
  }
  set_vertex(r, v, same_sign(mu, c2) ? i1 : i0);
}

// Triangle: project the origin on the plane, then signed areas in the coordinate plane where the
// triangle's projection is largest (Montanari S2D). Regions outside an edge recurse to that edge;
// a degenerate triangle tries all three edges.
void solve_triangle(const SimplexVertex* v, int i0, int i1, int i2, SubSimplex& r) {
  const Vec3& s1 = v[i0].w;
  const Vec3& s2 = v[i1].w;
  const Vec3& s3 = v[i2].w;
  const Vec3 n = (s2 - s1).cross(s3 - s1);
  const Real nn = n.squaredNorm();
  Real c[3] = {0, 0, 0};
  Real mu = 0;
  if (nn > 0) {
    const Vec3 p0 = n * (s1.dot(n) / nn);
    const int k = largest_axis(n);
    const int x = (k + 1) % 3;
    const int y = (k + 2) % 3;
    // Twice the signed area of (p, q, s) projected on axes (x, y); cyclic axes keep the sign of
    // n[k].
    auto area = [x, y](const Vec3& p, const Vec3& q, const Vec3& s) {
      return (q[x] - p[x]) * (s[y] - p[y]) - (q[y] - p[y]) * (s[x] - p[x]);
    };
    mu = area(s1, s2, s3);
    c[0] = area(p0, s2, s3);
    c[1] = area(s1, p0, s3);
    c[2] = area(s1, s2, p0);
    if (same_sign(mu, c[0]) && same_sign(mu, c[1]) && same_sign(mu, c[2])) {
      r.count = 3;
      r.index[0] = i0;
      r.index[1] = i1;
      r.index[2] = i2;
      for (int j = 0; j < 3; ++j) r.lambda[j] = c[j] / mu;
      r.v = r.lambda[0] * s1 + r.lambda[1] * s2 + r.lambda[2] * s3;
      return;
    }
  }
  const int ids[3] = {i0, i1, i2};
  Real best = std::numeric_limits<Real>::infinity();
  for (int j = 0; j < 3; ++j) {
    if (nn > 0 && same_sign(mu, c[j])) continue;
    SubSimplex e;
    solve_segment(v, ids[(j + 1) % 3], ids[(j + 2) % 3], e);
    const Real d = e.v.squaredNorm();
    if (d < best) best = d, r = e;
  }
}

// Tetrahedron: signed volumes with the origin replacing each vertex give the barycentric weights
// (Montanari S3D). All of one sign: origin inside. Otherwise the closest point lies on a face
// whose weight has the wrong sign; a flat tetrahedron tries all four faces.
void solve_tetrahedron(const SimplexVertex* v, SubSimplex& r) {
  const Vec3 &s1 = v[0].w, &s2 = v[1].w, &s3 = v[2].w, &s4 = v[3].w;
  const Real c[4] = {s2.dot(s3.cross(s4)), -s1.dot((s3 - s1).cross(s4 - s1)),
                     (s2 - s1).dot((-s1).cross(s4 - s1)), (s2 - s1).dot((s3 - s1).cross(-s1))};
  const Real mu = c[0] + c[1] + c[2] + c[3];
  if (same_sign(mu, c[0]) && same_sign(mu, c[1]) && same_sign(mu, c[2]) && same_sign(mu, c[3])) {
    r.count = 4;
    for (int j = 0; j < 4; ++j) r.index[j] = j, r.lambda[j] = c[j] / mu;
    r.v = Vec3::Zero();
    return;
  }
  Real best = std::numeric_limits<Real>::infinity();
  for (int j = 0; j < 4; ++j) {
    if (same_sign(mu, c[j])) continue;
    SubSimplex f;
    solve_triangle(v, (j + 1) % 4, (j + 2) % 4, (j + 3) % 4, f);
    const Real d = f.v.squaredNorm();
    if (d < best) best = d, r = f;
  }
}

// The closest point of simplex `s` to the origin, in double: the segment's, the triangle's, or the
// least over a tetrahedron's faces (the origin inside it: all four, count 4). The fallback of
// run_gjk where the float solvers, on a sliver, round their way back to the old closest point or
// leave it off its simplex. Vertices of zero weight are dropped, as the solvers drop them.
SubSimplex closest_in_double(const Simplex& s, double& distance2) {
  Eigen::Vector3d w[4];
  for (int i = 0; i < s.count; ++i) w[i] = s.v[i].w.cast<double>();
  SubSimplex best;
  set_vertex(best, s.v, 0);
  double best_d = std::numeric_limits<double>::infinity();
  const auto keep = [&](const Eigen::Vector3d& p, const int* ids, const double* weight, int n) {
    const double d = p.squaredNorm();
    if (!(d < best_d)) return;
    best_d = d;
    best.count = 0;
    for (int k = 0; k < n; ++k) {
      if (!(weight[k] > 0)) continue;
      best.index[best.count] = ids[k];
      best.lambda[best.count] = Real(weight[k]);
      ++best.count;
    }
    best.v = p.cast<Real>();
    distance2 = d;
  };
  distance2 = std::numeric_limits<double>::infinity();
  if (s.count == 1) {
    const int ids[1] = {0};
    const double weight[1] = {1};
    keep(w[0], ids, weight, 1);
    return best;
  }
  if (s.count == 2) {
    const Eigen::Vector3d ab = w[1] - w[0];
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp(-w[0].dot(ab) / len2, 0.0, 1.0) : 0.0;
    const int ids[2] = {0, 1};
    const double weight[2] = {1 - t, t};
    keep(w[0] + t * ab, ids, weight, 2);
    return best;
  }
  if (s.count == 4) {
    // Inside: the origin on the inner side of every face (signed volumes of one sign).
    const double vol[4] = {w[1].dot(w[2].cross(w[3])), -w[0].dot(w[2].cross(w[3])),
                           w[0].dot(w[1].cross(w[3])), -w[0].dot(w[1].cross(w[2]))};
    const double total = vol[0] + vol[1] + vol[2] + vol[3];
    if (total != 0 && vol[0] * total > 0 && vol[1] * total > 0 && vol[2] * total > 0 &&
        vol[3] * total > 0) {
      best.count = 4;
      for (int j = 0; j < 4; ++j) best.index[j] = j, best.lambda[j] = Real(vol[j] / total);
      best.v = Vec3::Zero();
      distance2 = 0;
      return best;
    }
  }
  for (int i = 0; i < s.count; ++i) {
    for (int j = i + 1; j < s.count; ++j) {
      for (int k = j + 1; k < s.count; ++k) {
        const int ids[3] = {i, j, k};
        const TriangleClosest<Eigen::Vector3d> c = closest_on_triangle_to_origin(w[i], w[j], w[k]);
        keep(c.point, ids, c.weight, 3);
      }
    }
  }
  return best;
}

SubSimplex solve_simplex(const Simplex& s) {
  SubSimplex r;
  switch (s.count) {
    case 1:
      set_vertex(r, s.v, 0);
      break;
    case 2:
      solve_segment(s.v, 0, 1, r);
      break;
    case 3:
      solve_triangle(s.v, 0, 1, 2, r);
      break;
    default:
      solve_tetrahedron(s.v, r);
      break;
  }
  return r;
}

void witness_points(const Simplex& s, Vec3& pa, Vec3& pb) {
  pa = Vec3::Zero();
  pb = Vec3::Zero();
  for (int i = 0; i < s.count; ++i) pa += s.lambda[i] * s.v[i].a, pb += s.lambda[i] * s.v[i].b;
}

}  // namespace

PlacedShape place(const Shape& s, const Transform& x, bool include_radius) {
  return PlacedShape{&s, x.rotation.toRotationMatrix(), x.position, include_radius};
}

Real core_radius(const Shape& s) {
  return s.type == ShapeType::Sphere || s.type == ShapeType::Capsule ? s.radius : Real(0);
}

Xyz support_world_xyz(const PlacedShape& p, Real dx, Real dy, Real dz) {
  const Vec3 d(dx, dy, dz);
  const Shape& s = *p.shape;
  Vec3 out = p.rotation * core_support(s, p.rotation.transpose() * d) + p.position;
  // A rounded shape is its core swept by a sphere: the sphere's support adds r d/|d|.
  if (p.include_radius && core_radius(s) > 0) {
    const Real len = d.norm();
    if (len > 0) out += d * (s.radius / len);
  }
  return {out.x(), out.y(), out.z()};
}

namespace {

// GJK over any support of the Minkowski difference: support(d) is the SimplexVertex of A's
// support along d and B's along -d. `d` points from A towards B: v is the current closest point
// of the simplex to the origin and GJK searches along -v, which for separated shapes is about
// the direction from A to B (v ~ a - b), so d seeds the search.
// Whether the last search's bound (every point c of the difference has v.c >= vw) already shows
// the shapes farther apart than `reject_beyond`.
struct RejectBeyond {
  Real reject_beyond = std::numeric_limits<Real>::infinity();
  bool operator()(Real vw, Real vv, const Vec3&) const {
    return vw > 0 && vw * vw > reject_beyond * reject_beyond * vv;
  }
};

// Whether the last search's bound shows the shapes staying apart over the motion `bound`
// describes (SweepBound in minkowski.hpp): along n = -v / |v| the gap g = vw / |v| closes no
// faster than delta.n + spin, so if g - reach exceeds that, the gap stays above `reach` over the
// whole motion. Multiplied through by |v| > 0.
struct SweepReject {
  const SweepBound& bound;
  bool operator()(Real vw, Real vv, const Vec3& v) const {
    if (!(vw > 0)) return false;
    const Real len = std::sqrt(vv);
    const Real slack = vw - bound.reach * len;
    return slack > 0 && slack > bound.spin * len - bound.delta.dot(v);
  }
};

// `contact`: the search may also stop once the distance is known to a contact's precision
// (gjk_contact).
template <class Support, class Reject = RejectBeyond>
GjkResult run_gjk(const Support& support, Vec3 d, Simplex& s, const Reject& reject = {},
                  bool contact = false) {
  GjkResult result;
  if (!(d.squaredNorm() > 0) || !d.allFinite()) d = Vec3::UnitY();
  s.count = 1;
  s.v[0] = support(d);
  s.lambda[0] = 1;
  Vec3 v = s.v[0].w;
  Real vv = v.squaredNorm();
  // The last search: every point c of the Minkowski difference has v.c >= v.w, so the shapes
  // are at least v.w / |v| apart.
  Real searched_vw = 0, searched_vv = 0;
  int refined = 0;  // times the search went on from a point solved in double
  for (int iter = 0; iter < kMaxIterations; ++iter) {
    result.iterations = iter + 1;
    Real max_ww = 0;
    for (int i = 0; i < s.count; ++i) max_ww = std::max(max_ww, s.v[i].w.squaredNorm());
    if (vv <= kOnSimplex * kOnSimplex * max_ww) {
      result.overlap = true;
      break;
    }
    const SimplexVertex w = support(Vec3(-v));
    searched_vw = v.dot(w.w);
    searched_vv = vv;
    // Every point of the difference is at least v.w / |v| from the origin: past the caller's
    // bound it wants no distance.
    if (reject(searched_vw, vv, v)) {
      result.beyond = true;
      result.lower_bound = searched_vw / std::sqrt(vv);
      return result;
    }
    if (vv - searched_vw <= kRelTol * vv) break;
    // The distance is off by at most (vv - v.w) / |v| (the search's bound): beyond the float
    // solvers' rounding, a search that stops here would stop short. perf: a full search asks
    // only where it would stop, not every iteration.
    auto far = [&] {
      const Real len = std::sqrt(vv);
      return vv - searched_vw > len * (kStuckRelGap * len + kStuckAbsGap * std::sqrt(max_ww));
    };
    if (contact && !far()) break;
    // Up to kMaxRefines times, the search goes on from the simplex's own closest point, solved
    // in double: the float one lay off its simplex (a sliver) and pointed the search wrong.
    auto go_on_from_own_point = [&](const SubSimplex& own) {
      ++refined;
      const Simplex old = s;
      s.count = own.count;
      for (int i = 0; i < own.count; ++i) s.v[i] = old.v[own.index[i]], s.lambda[i] = own.lambda[i];
      v = own.v;
      vv = v.squaredNorm();
    };
    bool repeated = false;
    for (int i = 0; i < s.count; ++i) repeated = repeated || s.v[i].w == w.w;
    if (repeated) {
      // A vertex already held, far beyond v's plane: v is off the simplex.
      if (refined == kMaxRefines || !far()) break;
      double own_d = 0;
      go_on_from_own_point(closest_in_double(s, own_d));
      continue;
    }
    Simplex next = s;
    next.v[next.count++] = w;
    SubSimplex r = solve_simplex(next);
    // Rounding can make the new closest point no closer, on a sliver simplex, where the old one
    // may also lie off its simplex. Far from convergence, both simplices are then solved again
    // in double: the new one goes on if it is closer than the old one, measured alike; else the
    // previous simplex stands.
    if (r.count < 4 && !(r.v.squaredNorm() < vv)) {
      if (!far()) break;
      double old_d = 0, new_d = 0;
      const SubSimplex old_r = closest_in_double(s, old_d);
      r = closest_in_double(next, new_d);
      if (!(new_d < old_d)) {
        if (refined == kMaxRefines) break;
        go_on_from_own_point(old_r);
        continue;
      }
    }
    s.count = r.count;
    for (int i = 0; i < r.count; ++i) s.v[i] = next.v[r.index[i]], s.lambda[i] = r.lambda[i];
    v = r.v;
    vv = v.squaredNorm();
    if (r.count == 4) {
      result.overlap = true;
      break;
    }
  }
  witness_points(s, result.point_a, result.point_b);
  // The distance is measured between the witnesses (not |v|), so that (b - a) / distance is a
  // unit normal to rounding even far from the origin; witnesses that meet mean touching.
  result.distance = result.overlap ? Real(0) : (result.point_b - result.point_a).norm();
  if (!(result.distance > 0)) result.overlap = true, result.distance = 0;
  if (!result.overlap && searched_vw > 0) {
    result.lower_bound = std::min(result.distance, searched_vw / std::sqrt(searched_vv));
  }
  return result;
}

// A search's first direction: the caller's, else from A's centre to B's.
Vec3 placed_start(const PlacedShape& a, const PlacedShape& b, const Vec3& direction) {
  if (direction.squaredNorm() > 0 && direction.allFinite()) return direction;
  return b.position - a.position;
}

// A triangle search's first direction: the caller's, else from A's centre to the centroid.
Vec3 triangle_start(const PlacedShape& a, const Vec3 (&triangle)[3], const Vec3& direction) {
  if (direction.squaredNorm() > 0 && direction.allFinite()) return direction;
  return (triangle[0] + triangle[1] + triangle[2]) / 3 - a.position;
}

}  // namespace

GjkResult gjk_placed(const PlacedShape& a, const PlacedShape& b, const Vec3& initial_direction,
                     Simplex& s) {
  const Vec3 d = placed_start(a, b, initial_direction);
  return run_gjk([&](const Vec3& x) { return support_minkowski(a, b, x); }, d, s);
}

GjkResult gjk_contact(const PlacedShape& a, const PlacedShape& b, const Vec3& initial_direction,
                      Simplex& s, Real reject_beyond) {
  const Vec3 d = placed_start(a, b, initial_direction);
  return run_gjk([&](const Vec3& x) { return support_minkowski(a, b, x); }, d, s,
                 RejectBeyond{reject_beyond}, true);
}

GjkResult gjk_placed(const PlacedShape& a, const PlacedShape& b, const Vec3& initial_direction,
                     Simplex& s, const SweepBound& bound) {
  const Vec3 d = placed_start(a, b, initial_direction);
  return run_gjk([&](const Vec3& x) { return support_minkowski(a, b, x); }, d, s,
                 SweepReject{bound});
}

GjkResult gjk_triangle(const PlacedShape& a, const Vec3 (&triangle)[3],
                       const Vec3& initial_direction, Simplex& s, Real reject_beyond) {
  const Vec3 d = triangle_start(a, triangle, initial_direction);
  return run_gjk([&](const Vec3& x) { return support_minkowski_triangle(a, triangle, x); }, d, s,
                 RejectBeyond{reject_beyond});
}

GjkResult gjk_triangle_contact(const PlacedShape& a, const Vec3 (&triangle)[3],
                               const Vec3& initial_direction, Simplex& s, Real reject_beyond) {
  const Vec3 d = triangle_start(a, triangle, initial_direction);
  return run_gjk([&](const Vec3& x) { return support_minkowski_triangle(a, triangle, x); }, d, s,
                 RejectBeyond{reject_beyond}, true);
}

GjkResult gjk_triangle(const PlacedShape& a, const Vec3 (&triangle)[3],
                       const Vec3& initial_direction, Simplex& s, const SweepBound& bound) {
  const Vec3 d = triangle_start(a, triangle, initial_direction);
  return run_gjk([&](const Vec3& x) { return support_minkowski_triangle(a, triangle, x); }, d, s,
                 SweepReject{bound});
}

GjkResult gjk_core_in_frame_of_b(std::span<const Vec3> core, const Shape& b, Simplex& s) {
  const Vec3 end = core[core.size() - 1] - core[0];
  auto support_core = [&](const Vec3& d) {
    SimplexVertex v;
    v.a = d.dot(end) > 0 ? core[core.size() - 1] : core[0];
    v.b = core_support(b, -d);
    v.w = v.a - v.b;
    return v;
  };
  // From the core's middle towards B's centre.
  return run_gjk(support_core, Vec3(Real(-0.5) * (core[0] + core[core.size() - 1])), s);
}

GjkResult gjk_point_sets(std::span<const Vec3> a, std::span<const Vec3> b, const Vec3& direction,
                         Real reject_beyond) {
  // determinism: the first point of the greatest projection wins ties.
  auto farthest = [](std::span<const Vec3> points, const Vec3& d) {
    std::size_t best = 0;
    Real most = points[0].dot(d);
    for (std::size_t i = 1; i < points.size(); ++i) {
      const Real p = points[i].dot(d);
      if (p > most) most = p, best = i;
    }
    return points[best];
  };
  auto support = [&](const Vec3& d) {
    SimplexVertex v;
    v.a = farthest(a, d);
    v.b = farthest(b, -d);
    v.w = v.a - v.b;
    return v;
  };
  Simplex s;
  return run_gjk(support, direction, s, RejectBeyond{reject_beyond});
}

GjkResult gjk_distance(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                       bool include_radius, const Vec3* initial_direction) {
  Simplex s;
  return gjk_placed(place(a, xa, include_radius), place(b, xb, include_radius),
                    initial_direction ? *initial_direction : Vec3::Zero(), s);
}

}  // namespace elan::detail
