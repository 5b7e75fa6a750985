// SPDX-License-Identifier: MIT
// Composite pairs: the walk over pieces and the merge into one manifold (see composite.hpp).
#include "narrowphase/composite.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "core/base/compound.hpp"
#include "core/base/heightfield.hpp"
#include "core/base/splitmix.hpp"
#include "core/base/triangle_mesh.hpp"
#include "narrowphase/collide.hpp"
#include "narrowphase/manifold_reduce.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase/triangle_contact.hpp"

namespace elan::detail {
namespace {

// perf: a fixed stack buffer of candidates (32 bytes each); past it a deeper candidate replaces
// the shallowest, so the deepest points always survive. A box on a fine mesh meets a few dozen
// triangles, each giving at most four points.
constexpr int kMaxCandidates = 128;
// Candidates whose normal is within this cosine (about 25 degrees) of the manifold's join it:
// near enough that the one normal the solver pushes along still holds them apart (a box across
// a gentle fold of a heightfield), far enough from a crease (a floor meeting a wall) that the
// wall's point does not push along the floor's normal.
constexpr Real kSameNormalCos = Real(0.9);
// Candidates closer than this are one point, m: the solver gains nothing from a second one there.
constexpr Real kSamePoint = Real(1e-3);
// Candidates within this gap of the deepest carry the body, m: a resting body sinks into its
// contacts and rocks on them by tenths of a millimetre, so a point a few tenths off is one it
// leans on, and one more than this off is clear of the surface. The support polygon is made of
// these first; on a curved surface the widest polygon of all candidates is mostly of points
// hovering a centimetre up, and a body held up by some of its touching points and not others
// tips on them for ever. A wider band lets points that carry nothing displace ones that do.
constexpr Real kSupportBand = Real(0.002);
// The feature id of a candidate that came from no triangle.
constexpr uint32_t kNoTriangle = 0xFFFFFFFFu;

struct Candidate {
  Vec3 point;   // m, world, from A's centre of mass
  Vec3 normal;  // unit, world, A to B
  Real separation;
  uint32_t id;
};

struct Candidates {
  Candidate c[kMaxCandidates];
  int count = 0;

  void push(const Candidate& x) { push_keeping_deepest(c, count, kMaxCandidates, x); }
};

// 32 bits from the pieces (parts of A and B, 0 for none), the triangle and the piece's own id:
// splitmix64's finaliser over the packed words, so that ids of different pieces rarely collide.
uint32_t feature_id(uint32_t parts, uint32_t triangle, uint32_t local) {
  const uint64_t h = (uint64_t(parts) << 32 | triangle) ^ (uint64_t(local) * 0x9E3779B97F4A7C15ull);
  return uint32_t(splitmix64_finalize(h));
}

Transform compose(const Transform& outer, const Transform& inner) {
  return {outer.rotation * inner.position + outer.position, outer.rotation * inner.rotation};
}

// The box of shape `s` at pose `xs`, in the frame `frame`, grown by `grow`; a plane's is
// everything.
void box_in(const Shape& s, const Transform& xs, const Transform& frame, Real grow, Vec3& lo,
            Vec3& hi) {
  if (s.type == ShapeType::Plane) {
    lo = Vec3::Constant(std::numeric_limits<Real>::lowest());
    hi = Vec3::Constant(std::numeric_limits<Real>::max());
    return;
  }
  const Quat to_frame = frame.rotation.conjugate();
  const Mat3 r = (to_frame * xs.rotation).toRotationMatrix();
  const Vec3 centre =
      r * (Real(0.5) * (s.local_min + s.local_max)) + to_frame * (xs.position - frame.position);
  const Vec3 half = r.cwiseAbs() * (Real(0.5) * (s.local_max - s.local_min));
  lo = centre - half - Vec3::Constant(grow);
  hi = centre + half + Vec3::Constant(grow);
}

struct Walk {
  const Transform& xa;  // A's body pose: the candidates' points are from its centre
  Real speculative;
  Candidates& out;
  // Against a surface: the speculative distance without the motion, and A's displacement
  // relative to B (world); `base` equals `speculative` and the displacement is zero when no
  // motion was given.
  Real base;
  Vec3 displacement;
  // perf: A's piece as a polyhedron, kept while the walk meets B's parts one by one (the same
  // piece, pose and frame every time, so the same bits as building it anew).
  PolyhedronCache& polyhedron;
};

// A convex piece p (A's side, or a plane) against a piece q of B's side: convex, plane or surface.
void collide_pieces(const Shape& p, const Transform& xp, const Shape& q, const Transform& xq,
                    uint32_t parts, Walk& w) {
  const Vec3 offset = xp.position - w.xa.position;
  if (is_surface(q)) {
    if (p.type == ShapeType::Plane) return;
    // The piece in the surface's frame; the triangles under its box.
    const Quat to_q = xq.rotation.conjugate();
    const Transform local{to_q * (xp.position - xq.position), to_q * xp.rotation};
    const Vec3 motion = to_q * w.displacement;
    Vec3 lo, hi;
    box_in(p, local, Transform{}, w.base, lo, hi);
    lo += motion.cwiseMin(Vec3::Zero());
    hi += motion.cwiseMax(Vec3::Zero());
    // perf: what depends on the piece alone is derived once for all its triangles.
    TriangleQuery query = make_triangle_query(p, local, w.base);
    query.motion = motion;
    TriangleReach reach;
    TriangleContact tc;
    const auto contact = [&](const MeshTriangle& t) {
      if (!collide_reached_triangle(query, t, reach, tc)) return;
      const Vec3 n = xq.rotation * tc.normal;
      for (int k = 0; k < tc.count; ++k) {
        w.out.push({xq.rotation * tc.points[k] + offset, n, tc.separation[k],
                    feature_id(parts, t.index, tc.feature[k])});
      }
    };
    if (q.type == ShapeType::Mesh) {
      // perf: a triangle is copied out of the mesh only once in reach. Copied first, its corners
      // were read back in wider pieces than the copy wrote them (a failed store forwarding).
      const TriangleMesh& mesh = *q.mesh;
      for_each_triangle_in_place(mesh, lo, hi,
                                 [&](uint32_t t, const Vec3& a, const Vec3& b, const Vec3& c) {
                                   if (reach_triangle(query, a, b, c, true, reach))
                                     contact(mesh.triangle(t));
                                 });
    } else {
      // perf: a heightfield triangle's active edges (a normal per neighbour) only where a
      // contact needs them.
      const HeightField& field = *q.heightfield;
      query.field = &field;
      query.down = support_world(query.full, Vec3(0, -1, 0));
      // perf: a cell's two triangles lie in its box (x and z between its samples, y between its
      // least and greatest height): a cell the piece is clear of by more than any triangle's
      // speculative distance can be (the base plus the whole motion) holds no contact, found for
      // one support instead of the two triangles' tests.
      const Real cell_speculative = w.base + motion.norm();
      for_each_cell(
          field, lo, hi, [&](uint32_t i, uint32_t j, Real low, Real high, uint32_t triangles) {
            const Vec3 box_lo = Vec3(Real(i) * field.spacing_x, low, Real(j) * field.spacing_z);
            const Vec3 box_hi =
                Vec3(Real(i + 1) * field.spacing_x, high, Real(j + 1) * field.spacing_z);
            MeshTriangle pair[2];
            field.cell_corners(i, j, pair);
            // The cell's triangles that are there (a hole takes one or both away).
            const std::span<const MeshTriangle> there(pair + (triangles == 2u ? 1 : 0),
                                                      triangles == 3u ? 2 : 1);
            if (clear_of_box(query, box_lo, box_hi, cell_speculative, there)) return;
            for (const MeshTriangle& t : there) {
              if (reach_triangle(query, t, reach)) contact(t);
            }
          });
    }
    return;
  }
  Manifold m;
  Separation unused;
  if (!collide(p, xp, q, xq, w.speculative, m, w.polyhedron, unused)) return;
  for (int k = 0; k < int(m.point_count); ++k) {
    const ContactPoint& c = m.points[k];
    w.out.push({c.anchor_a + offset, m.normal, c.separation,
                feature_id(parts, kNoTriangle, c.feature_id)});
  }
}

// Adds to keep[0, kept) the points of pos that widen the kept polygon most seen along the normal,
// as reduce_to_four does from its deepest point (farthest, largest triangle, largest
// quadrilateral), until there are four or none adds any width. Returns the new count.
int widen(const Vec3* pos, int count, bool* taken, const Vec3& normal, int* keep, int kept) {
  const auto area = [&normal](const Vec3& a, const Vec3& b, const Vec3& q) {
    return (b - a).cross(q - a).dot(normal);
  };
  while (kept < kMaxManifoldPoints) {
    int t[3] = {keep[0], kept > 1 ? keep[1] : 0, kept > 2 ? keep[2] : 0};
    if (kept == 3 && area(pos[t[0]], pos[t[1]], pos[t[2]]) < 0) std::swap(t[1], t[2]);
    // determinism: a strict comparison, so ties keep the lower index.
    int best_i = -1;
    Real best = 0;
    for (int i = 0; i < count; ++i) {
      if (taken[i]) continue;
      const Vec3 d = pos[i] - pos[t[0]];
      Real gain = 0;
      if (kept == 1) {
        gain = (d - normal * normal.dot(d)).squaredNorm();
      } else if (kept == 2) {
        gain = std::abs(area(pos[t[0]], pos[t[1]], pos[i]));
      } else {
        for (int e = 0; e < 3; ++e) {
          gain = std::max(gain, -area(pos[t[e]], pos[t[(e + 1) % 3]], pos[i]));
        }
      }
      if (gain > best) best = gain, best_i = i;
    }
    if (best_i < 0) break;
    taken[best_i] = true;
    keep[kept++] = best_i;
  }
  return kept;
}

// Four of the merged points: the support polygon of the points within kSupportBand of the
// deepest (reduce_to_four over them: the deepest, then the widest), then, while there are fewer
// than four of those, the points that widen it most, whose speculative rows stop the body
// tipping onto them.
int choose_four(const Vec3* pos, const Real* sep, int count, const Vec3& normal, int* keep) {
  if (count <= kMaxManifoldPoints) {
    return reduce_to_four(std::span<const Vec3>(pos, std::size_t(count)),
                          std::span<const Real>(sep, std::size_t(count)), normal, keep);
  }
  Real deepest = sep[0];
  for (int i = 1; i < count; ++i) deepest = std::min(deepest, sep[i]);
  Vec3 spos[kMaxCandidates];
  Real ssep[kMaxCandidates];
  int sfrom[kMaxCandidates];
  int n = 0;
  for (int i = 0; i < count; ++i) {
    if (sep[i] > deepest + kSupportBand) continue;
    spos[n] = pos[i], ssep[n] = sep[i], sfrom[n] = i;
    ++n;
  }
  int local[kMaxManifoldPoints];
  int kept = reduce_to_four(std::span<const Vec3>(spos, std::size_t(n)),
                            std::span<const Real>(ssep, std::size_t(n)), normal, local);
  bool taken[kMaxCandidates] = {};
  for (int k = 0; k < kept; ++k) {
    keep[k] = sfrom[local[k]];
    taken[keep[k]] = true;
  }
  if (kept < kMaxManifoldPoints) kept = widen(pos, count, taken, normal, keep, kept);
  return kept;
}

// A piece p of A's side against the whole of B's side.
void collide_piece_with(const Shape& p, const Transform& xp, uint32_t part_a, const Shape& b,
                        const Transform& xb, Walk& w) {
  if (b.type != ShapeType::Compound) {
    collide_pieces(p, xp, b, xb, part_a, w);
    return;
  }
  Vec3 lo, hi;
  box_in(p, xp, xb, w.speculative, lo, hi);
  for_each_part(*b.compound, lo, hi, [&](uint32_t k, const CompoundPart& part) {
    collide_pieces(p, xp, part.shape, compose(xb, part.pose), part_a | ((k + 1) << 16), w);
  });
}

// The merge: the deepest candidate's normal (the point the solver must push apart first; its
// normal is the one that resolves it, and choose_four keeps that point too), the candidates
// near that normal with their gap re-measured along it (to their own plane: s / cos), then four.
bool merge(const Candidates& cands, Real speculative, Manifold& out) {
  if (cands.count == 0) return false;
  int deepest = 0;
  for (int i = 1; i < cands.count; ++i) {
    if (cands.c[i].separation < cands.c[deepest].separation) deepest = i;
  }
  const Vec3 normal = cands.c[deepest].normal;
  Vec3 pos[kMaxCandidates];
  Real sep[kMaxCandidates];
  uint32_t ids[kMaxCandidates];
  int count = 0;
  for (int i = 0; i < cands.count; ++i) {
    const Candidate& c = cands.c[i];
    const Real cosine = c.normal.dot(normal);
    if (!(cosine >= kSameNormalCos)) continue;
    // A candidate along the manifold's own normal keeps its bits (a lone part is its shape).
    const Real s = c.normal == normal ? c.separation : c.separation / cosine;
    if (s > speculative) continue;
    // Neighbouring triangles report a point on their shared edge or corner each (a sphere over
    // an inactive edge, a box corner over a vertex): one point there is enough, the deepest. Its
    // id is the least of theirs, not the deepest one's: which of two triangles is deeper there
    // flips with the body's rocking, and a point whose id changes loses its warm start.
    int same = -1;
    for (int j = 0; j < count && same < 0; ++j) {
      if ((pos[j] - c.point).squaredNorm() <= kSamePoint * kSamePoint) same = j;
    }
    if (same >= 0) {
      if (s < sep[same]) pos[same] = c.point, sep[same] = s;
      ids[same] = std::min(ids[same], c.id);
      continue;
    }
    pos[count] = c.point;
    sep[count] = s;
    ids[count] = c.id;
    ++count;
  }
  int keep[kMaxManifoldPoints];
  const int kept = choose_four(pos, sep, count, normal, keep);
  out.normal = normal;
  for (int k = 0; k < kept; ++k) {
    ContactPoint& p = out.points[k];
    p.anchor_a = pos[keep[k]];
    p.separation = sep[keep[k]];
    p.feature_id = ids[keep[k]];
  }
  out.point_count = uint32_t(kept);
  return kept > 0;
}

}  // namespace

bool collide_composite(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                       Real speculative_distance, Manifold& out, const SurfaceMotion* motion) {
  out.point_count = 0;
  if (is_surface(a) && is_surface(b)) return false;
  if (is_surface(a)) {
    // The surface as B: run the pair the other way, then flip the normal and measure the points
    // from A's centre, as collide()'s dispatch does.
    SurfaceMotion flipped;
    if (motion != nullptr) flipped = {-motion->displacement, motion->base_speculative};
    if (!collide_composite(b, xb, a, xa, speculative_distance, out,
                           motion != nullptr ? &flipped : nullptr)) {
      return false;
    }
    out.normal = -out.normal;
    const Vec3 b_from_a = xb.position - xa.position;
    for (int k = 0; k < int(out.point_count); ++k) out.points[k].anchor_a += b_from_a;
    return true;
  }
  Candidates cands;
  PolyhedronCache polyhedron;  // default-initialised: only its key is set, not its arrays
  Walk w{xa, speculative_distance, cands, speculative_distance, Vec3::Zero(), polyhedron};
  if (motion != nullptr) w.base = motion->base_speculative, w.displacement = motion->displacement;
  if (a.type == ShapeType::Compound) {
    Vec3 lo, hi;
    box_in(b, xb, xa, speculative_distance, lo, hi);
    for_each_part(*a.compound, lo, hi, [&](uint32_t k, const CompoundPart& part) {
      collide_piece_with(part.shape, compose(xa, part.pose), k + 1, b, xb, w);
    });
  } else {
    collide_piece_with(a, xa, 0, b, xb, w);
  }
  return merge(cands, speculative_distance, out);
}

}  // namespace elan::detail
