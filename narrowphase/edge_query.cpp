// SPDX-License-Identifier: MIT
// The edge query of two polyhedra by their Gauss maps (Gregorius, GDC 2013), compiled once per
// instruction set (narrowphase/CMakeLists.txt): the crossing test runs over B's edges in SIMD
// lanes, as wide as the level allows.
#include "narrowphase/edge_query.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace elan::detail {
ELAN_ISA_BEGIN

namespace {

// Per-edge data of B for the edge query, computed once per call instead of once per edge pair,
// as columns so that the query runs over B's edges in SIMD lanes.
// Padded with zero arcs, which never cross, to a whole number of SIMD blocks: no scalar epilogue.
constexpr int kArcBlock = 16;
struct EdgeArcs {
  // -B's face normals c, d (its Gauss-map arc on -B) and the arc's plane normal d x c.
  alignas(64) std::array<Real, kMaxPolyEdges + kArcBlock> cx, cy, cz, dx, dy, dz, nx, ny, nz;
  int padded_count = 0;
};

// Bit k of the result is set when B's edge first + k and A's edge (its faces' normals a and b,
// bxa the normal of the plane of their arc) build a face of the Minkowski difference: the arcs
// (a, b) of A's Gauss map and (c, d) of -B's cross exactly then (Gregorius 2013).
uint32_t crossing_arcs(const Vec3& a, const Vec3& b, const Vec3& bxa, const EdgeArcs& e,
                       int first) {
  const Real ax = a.x(), ay = a.y(), az = a.z(), bx = b.x(), by = b.y(), bz = b.z();
  const Real sx = bxa.x(), sy = bxa.y(), sz = bxa.z();
  uint32_t hits = 0;
#pragma omp simd reduction(| : hits)
  for (int q = 0; q < kArcBlock; ++q) {
    const int k = first + q;
    const Real cba = e.cx[k] * sx + e.cy[k] * sy + e.cz[k] * sz;
    const Real dba = e.dx[k] * sx + e.dy[k] * sy + e.dz[k] * sz;
    const Real adc = ax * e.nx[k] + ay * e.ny[k] + az * e.nz[k];
    const Real bdc = bx * e.nx[k] + by * e.ny[k] + bz * e.nz[k];
    const bool crosses = (cba * dba < 0) & (adc * bdc < 0) & (cba * bdc > 0);
    hits |= uint32_t(crosses) << q;
  }
  return hits;
}

// The edge pairs whose arcs cross, waiting for their separations: A's edge (first vertex, its
// direction, that squared length, and the first vertex from A's centre) and B's edge (first
// vertex, direction, squared length), as columns.
constexpr int kCandidates = 64;
struct EdgeCandidates {
  alignas(64) std::array<Real, kCandidates> pax, pay, paz, vax, vay, vaz, va_len2, oax, oay, oaz;
  alignas(64) std::array<Real, kCandidates> pbx, pby, pbz, vbx, vby, vbz, vb_len2, separation;
  std::array<int, kCandidates> edge_a, edge_b;
  int count = 0;
};

// Row i of three columns from a vector.
template <class Column>
void put(Column& x, Column& y, Column& z, int i, const Vec3& v) {
  x[i] = v.x();
  y[i] = v.y();
  z[i] = v.z();
}

// Each candidate's separation along ua x ub, out of A at its edge, or kLowest where the edges
// are nearly parallel (no axis).
// perf: a hull pair has hundreds of edge pairs and only about one per A edge crosses. The
// crossing test is four dot products in SIMD lanes over all of them; the separation, with its
// square roots and divisions, runs only for those that cross. Each lane's arithmetic is the
// scalar Eigen expression's, in the same order (sums as x + (y + z)), so the bits are too.
void candidate_separations(EdgeCandidates& c) {
#pragma omp simd
  for (int k = 0; k < c.count; ++k) {
    Real nx = c.vay[k] * c.vbz[k] - c.vaz[k] * c.vby[k];
    Real ny = c.vaz[k] * c.vbx[k] - c.vax[k] * c.vbz[k];
    Real nz = c.vax[k] * c.vby[k] - c.vay[k] * c.vbx[k];
    const Real len = std::sqrt(nx * nx + (ny * ny + nz * nz));
    const bool parallel = len <= kParallelSine * std::sqrt(c.va_len2[k] * c.vb_len2[k]);
    nx /= len;
    ny /= len;
    nz /= len;
    // Out of A at its edge: a flipped axis gives the same separation negated, exactly.
    const Real s =
        nx * (c.pbx[k] - c.pax[k]) + (ny * (c.pby[k] - c.pay[k]) + nz * (c.pbz[k] - c.paz[k]));
    const Real out = nx * c.oax[k] + (ny * c.oay[k] + nz * c.oaz[k]);
    c.separation[k] = parallel ? kLowest : (out < 0 ? -s : s);
  }
}

// The candidates' separations, the first largest kept in q; the list is then empty. Candidates
// come in (A edge, B edge) order, so q is the first largest in that order.
void flush_candidates(EdgeCandidates& c, EdgeQuery& q) {
  candidate_separations(c);
  for (int k = 0; k < c.count; ++k) {
    if (c.separation[k] > q.separation) {
      q.separation = c.separation[k];
      q.edge_a = c.edge_a[k];
      q.edge_b = c.edge_b[k];
    }
  }
  c.count = 0;
}

}  // namespace

EdgeQuery query_gauss_edges(const Polyhedron& a, const Polyhedron& b) {
  EdgeArcs arcs;
  arcs.padded_count = (b.edge_count + kArcBlock - 1) / kArcBlock * kArcBlock;
  for (int eb = 0; eb < arcs.padded_count; ++eb) {
    const bool real = eb < b.edge_count;
    const Vec3 c = real ? Vec3(-b.normals[b.edge_faces[eb][0]]) : Vec3::Zero();
    const Vec3 d = real ? Vec3(-b.normals[b.edge_faces[eb][1]]) : Vec3::Zero();
    put(arcs.cx, arcs.cy, arcs.cz, eb, c);
    put(arcs.dx, arcs.dy, arcs.dz, eb, d);
    put(arcs.nx, arcs.ny, arcs.nz, eb, d.cross(c));
  }
  EdgeCandidates cand;
  EdgeQuery q;
  for (int ea = 0; ea < a.edge_count; ++ea) {
    const Vec3& na = a.normals[a.edge_faces[ea][0]];
    const Vec3& nb = a.normals[a.edge_faces[ea][1]];
    const Vec3 bxa = nb.cross(na);
    for (int first = 0; first < arcs.padded_count; first += kArcBlock) {
      uint32_t hits = crossing_arcs(na, nb, bxa, arcs, first);
      if (hits == 0) continue;
      if (cand.count > kCandidates - kArcBlock) flush_candidates(cand, q);
      const Vec3& pa = a.vertices[a.edges[ea][0]];
      const Vec3 ua = a.vertices[a.edges[ea][1]] - pa;
      const Vec3 outwards = pa - a.centre;
      for (; hits != 0; hits &= hits - 1) {
        const int eb = first + std::countr_zero(hits);
        const int i = cand.count++;
        const Vec3& pb = b.vertices[b.edges[eb][0]];
        const Vec3 ub = b.vertices[b.edges[eb][1]] - pb;
        put(cand.pax, cand.pay, cand.paz, i, pa);
        put(cand.vax, cand.vay, cand.vaz, i, ua);
        cand.va_len2[i] = ua.squaredNorm();
        put(cand.oax, cand.oay, cand.oaz, i, outwards);
        put(cand.pbx, cand.pby, cand.pbz, i, pb);
        put(cand.vbx, cand.vby, cand.vbz, i, ub);
        cand.vb_len2[i] = ub.squaredNorm();
        cand.edge_a[i] = ea;
        cand.edge_b[i] = eb;
      }
    }
  }
  flush_candidates(cand, q);
  if (q.edge_a >= 0) {
    const Vec3& pa = a.vertices[a.edges[q.edge_a][0]];
    const Vec3 ua = a.vertices[a.edges[q.edge_a][1]] - pa;
    const Vec3 ub = b.vertices[b.edges[q.edge_b][1]] - b.vertices[b.edges[q.edge_b][0]];
    Vec3 axis = ua.cross(ub);
    axis /= axis.norm();
    q.normal = axis.dot(pa - a.centre) < 0 ? Vec3(-axis) : axis;
  }
  return q;
}

ELAN_ISA_END
}  // namespace elan::detail
