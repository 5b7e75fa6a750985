// SPDX-License-Identifier: MIT
// Fuzz target: GJK, EPA and the contact routines (SAT, clipping, closed forms) on a random pair
// of convex shapes (sphere, box, capsule, cylinder, hull of up to 12 points) at random poses.
// Always: no crash, nothing non-finite, at most four points, a unit normal. Where a brute-force
// oracle exists (tests/stage/narrowphase_oracle.hpp, in double): GJK's distance agrees with it,
// GJK reports an overlap exactly when the oracle does (outside a tolerance band), and collide()
// gives points when the shapes overlap and none when they are farther apart than the
// speculative distance. The oracles: two round shapes (centre or segment distances minus the
// radii), and any pair of a sphere, a box and a hull (feature-pair distances of polytopes and
// the SAT depth over all face normals and edge-pair axes).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "core/base/contact.hpp"
#include "core/base/shape.hpp"
#include "elan/error.hpp"
#include "fuzz/fuzz_input.hpp"
#include "narrowphase/collide.hpp"
#include "narrowphase/gjk.hpp"
#include "stage/narrowphase_oracle.hpp"

namespace {

using namespace elan;
using namespace elan::detail;
using oracle::Poly;
using oracle::V3;

struct Piece {
  Shape shape;
  Transform pose;  // of the principal frame
};

std::optional<Piece> read_piece(fuzz::Bytes& in) {
  ShapeDef d;
  switch (in.u8() % 5) {
    case 0:
      d.type = ShapeType::Sphere;
      d.radius = in.in(Real(0.05), 2);
      break;
    case 1:
      d.type = ShapeType::Box;
      d.half_extents = Vec3{in.in(Real(0.05), 2), in.in(Real(0.05), 2), in.in(Real(0.05), 2)};
      break;
    case 2:
      d.type = ShapeType::Capsule;
      d.radius = in.in(Real(0.05), 1);
      d.half_height = in.in(Real(0.05), 2);
      break;
    case 3:
      d.type = ShapeType::Cylinder;
      d.radius = in.in(Real(0.05), 1);
      d.half_height = in.in(Real(0.05), 2);
      break;
    default: {
      d.type = ShapeType::ConvexHull;
      const int n = 4 + in.u8() % 9;
      for (int k = 0; k < n; ++k) d.points.push_back(in.in_box(2));
    }
  }
  Piece p;
  try {
    p.shape = make_shape(d);
  } catch (const Error& e) {
    fuzz::require_one_line(e.what());  // a flat or tiny hull
    return std::nullopt;
  }
  p.pose.position = in.in_box(3);
  p.pose.rotation = in.rotation();
  return p;
}

// A box or hull placed in the world as the oracle's polytope; a sphere as its centre (a
// polytope of one vertex: vertex-face distances alone measure it, to be reduced by the radius).
std::optional<Poly> polytope_of(const Piece& p) {
  const Transform& x = p.pose;
  if (p.shape.type == ShapeType::ConvexHull) return oracle::place_hull(p.shape, x);
  if (p.shape.type == ShapeType::Box) return oracle::place_box(p.shape.half_extents, x);
  if (p.shape.type != ShapeType::Sphere) return std::nullopt;
  Poly poly;
  poly.v.push_back(x.position.cast<double>());
  return poly;
}

// The segment of a capsule (or a sphere's centre twice) in the world.
std::pair<V3, V3> segment_of(const Piece& p) {
  const V3 c = p.pose.position.cast<double>();
  const V3 axis = (p.pose.rotation * Vec3::UnitY()).cast<double>() * double(p.shape.half_height);
  return {c - axis, c + axis};
}

bool round(const Piece& p) {
  return p.shape.type == ShapeType::Sphere || p.shape.type == ShapeType::Capsule;
}

// The exact distance of the full shapes (negative: some overlap, its magnitude not exact) when
// an oracle covers the pair.
std::optional<double> oracle_distance(const Piece& a, const Piece& b) {
  if (round(a) && round(b)) {
    const auto [p1, q1] = segment_of(a);
    const auto [p2, q2] = segment_of(b);
    return oracle::segment_distance(p1, q1, p2, q2) - double(a.shape.radius) -
           double(b.shape.radius);
  }
  const std::optional<Poly> pa = polytope_of(a), pb = polytope_of(b);
  if (!pa || !pb) return std::nullopt;
  const double radii = (a.shape.type == ShapeType::Sphere ? double(a.shape.radius) : 0.0) +
                       (b.shape.type == ShapeType::Sphere ? double(b.shape.radius) : 0.0);
  if (pa->v.size() > 1 && pb->v.size() > 1) {
    const double depth = oracle::sat_depth(*pa, *pb);
    if (depth > 0) return -depth;
  } else {
    // A sphere's centre inside the other polytope: overlapping by at least the radius.
    const Poly& poly = pa->v.size() > 1 ? *pa : *pb;
    const V3& centre = pa->v.size() > 1 ? pb->v[0] : pa->v[0];
    // Inside a convex polytope: below its support along every face normal.
    bool inside = true;
    for (const V3& n : poly.normals) {
      double support = -std::numeric_limits<double>::infinity();
      for (const V3& v : poly.v) support = std::max(support, v.dot(n));
      if (centre.dot(n) > support) inside = false;
    }
    if (inside) return -radii;
  }
  return oracle::point_set_distance(pa->v, pb->v) - radii;
}

std::string describe(const Piece& a, const Piece& b, double ref, const GjkResult& g) {
  return "types " + std::to_string(int(a.shape.type)) + "," + std::to_string(int(b.shape.type)) +
         " oracle " + std::to_string(ref) + " gjk " + std::to_string(double(g.distance)) +
         (g.overlap ? " (overlap)" : "");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  fuzz::Bytes in{data, size};
  const std::optional<Piece> a = read_piece(in), b = read_piece(in);
  if (!a || !b) return 0;
  const Real speculative = in.in(0, Real(0.1));

  const GjkResult g = gjk_distance(a->shape, a->pose, b->shape, b->pose);
  fuzz::require(std::isfinite(g.distance) && g.distance >= 0, "GJK's distance is finite, >= 0");
  fuzz::require(g.point_a.allFinite() && g.point_b.allFinite(), "GJK's points are finite");
  if (g.overlap) {
    const EpaResult e = epa_penetration(a->shape, a->pose, b->shape, b->pose);
    if (e.ok) {
      // Touching shapes may give a depth a rounding below zero.
      fuzz::require(std::isfinite(e.depth) && e.depth >= Real(-1e-4),
                    "EPA's depth is finite, >= 0:", std::to_string(double(e.depth)));
      fuzz::require(std::abs(e.normal.norm() - 1) < Real(1e-3), "EPA's normal is unit");
      fuzz::require(e.point_a.allFinite() && e.point_b.allFinite(), "EPA's points are finite");
    }
  }

  Manifold m;
  collide(a->shape, a->pose, b->shape, b->pose, speculative, m);
  fuzz::require(m.point_count <= kMaxManifoldPoints, "at most four points");
  fuzz::require(m.normal.allFinite(), "the normal is finite");
  if (m.point_count > 0) {
    fuzz::require(std::abs(m.normal.norm() - 1) < Real(1e-3), "the normal is unit");
  }
  for (uint32_t k = 0; k < m.point_count; ++k) {
    fuzz::require(m.points[k].anchor_a.allFinite() && std::isfinite(m.points[k].separation),
                  "every point is finite");
  }

  const std::optional<double> ref = oracle_distance(*a, *b);
  if (!ref) return 0;
  // Float GJK stops at a relative gap of 1e-5 (gjk.cpp); with coordinates up to about 8 m,
  // float rounding of the supports adds some 1e-6 m. The band leaves room for both.
  const double scale = 8;
  const double tol = 1e-4 * std::abs(*ref) + 2e-5 * scale;
  if (*ref > tol) {
    fuzz::require(!g.overlap, "GJK finds no overlap where the oracle separates",
                  describe(*a, *b, *ref, g));
    fuzz::require(std::abs(double(g.distance) - *ref) <= tol, "GJK's distance is the oracle's",
                  describe(*a, *b, *ref, g));
  }
  if (*ref < -tol) {
    fuzz::require(g.overlap || g.distance <= tol, "GJK finds the oracle's overlap",
                  describe(*a, *b, *ref, g));
    fuzz::require(m.point_count > 0, "overlapping shapes touch", describe(*a, *b, *ref, g));
  }
  if (*ref > double(speculative) + tol) {
    fuzz::require(m.point_count == 0, "no points beyond the speculative distance",
                  describe(*a, *b, *ref, g));
  }
  return 0;
}
