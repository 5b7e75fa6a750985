// SPDX-License-Identifier: MIT
// Internal to GJK/EPA: support of the Minkowski difference A - B of two placed shapes (core or
// full), the simplex GJK hands to EPA, and the core-based penetration query.
#pragma once

#include <limits>
#include <span>

#include "core/base/shape.hpp"
#include "narrowphase/gjk.hpp"

namespace elan::detail {

// Machine epsilon of Real: the narrowphase's relative tolerances are multiples of it.
inline constexpr Real kEps = std::numeric_limits<Real>::epsilon();

// A shape placed in the world, rotation as a matrix so each support costs two mat-vec products.
struct PlacedShape {
  const Shape* shape;
  Mat3 rotation;
  Vec3 position;
  bool include_radius;
};

PlacedShape place(const Shape& s, const Transform& x, bool include_radius);

// Radius that rounds the core (sphere: point, capsule: segment); 0 for other shapes.
Real core_radius(const Shape& s);

// Support of the shape's core in its principal frame: a sphere's centre, a capsule's segment, any
// other shape itself.
inline Vec3 core_support(const Shape& s, const Vec3& d) {
  switch (s.type) {
    case ShapeType::Sphere:
      return Vec3::Zero();
    case ShapeType::Capsule:
      return Vec3(0, d.y() >= 0 ? s.half_height : -s.half_height, 0);
    default:
      return support(s, d);
  }
}

// support_world's body, with the direction and the result in registers (Xyz, shape.hpp).
Xyz support_world_xyz(const PlacedShape& p, Real dx, Real dy, Real dz);

// World support point of the placed shape in world direction d (need not be unit).
inline Vec3 support_world(const PlacedShape& p, const Vec3& d) {
  const Xyz s = support_world_xyz(p, d.x(), d.y(), d.z());
  return Vec3(s.x, s.y, s.z);
}

struct SimplexVertex {
  Vec3 w;  // a - b: point of the Minkowski difference
  Vec3 a;  // world support point on A
  Vec3 b;  // world support point on B
};

struct Simplex {
  SimplexVertex v[4];
  Real lambda[4];  // barycentric weights of the closest point
  int count = 0;
};

inline SimplexVertex support_minkowski(const PlacedShape& a, const PlacedShape& b, const Vec3& d) {
  SimplexVertex s;
  s.a = support_world(a, d);
  s.b = support_world(b, -d);
  s.w = s.a - s.b;
  return s;
}

// Support of a triangle (three points, as placed): the corner farthest along d; ties go to the
// lower corner.
inline Vec3 support_triangle(const Vec3 (&t)[3], const Vec3& d) {
  const Real h0 = t[0].dot(d), h1 = t[1].dot(d), h2 = t[2].dot(d);
  if (h0 >= h1 && h0 >= h2) return t[0];
  return h1 >= h2 ? t[1] : t[2];
}

inline SimplexVertex support_minkowski_triangle(const PlacedShape& a, const Vec3 (&t)[3],
                                                const Vec3& d) {
  SimplexVertex s;
  s.a = support_world(a, d);
  s.b = support_triangle(t, -d);
  s.w = s.a - s.b;
  return s;
}

// GJK on two placed shapes; leaves the terminating simplex in `out_simplex`.
GjkResult gjk_placed(const PlacedShape& a, const PlacedShape& b, const Vec3& initial_direction,
                     Simplex& out_simplex);
// gjk_placed for a contact: it stops as soon as its lower bound shows the shapes farther apart
// than `reject_beyond` (result.beyond, with that bound in result.lower_bound), and searches only
// to a contact's precision: it also stops once the distance is known to within 1e-4 of itself plus
// 1e-5 of the simplex's size (its longest vertex), the band a stalled search stops in anyway
// (gjk.cpp), inside the fuzz oracle's. Only a search that ends apart can stop earlier: one that
// ends in overlap is gjk_placed's, bit for bit. perf: on a cylinder's rim GJK converges linearly,
// about halving the gap per support, and two cylinders touching can take tens of supports to reach
// 1e-5 of their distance. A contact's points come from the features along its normal. That normal
// is within acos(d / (d + gap)) of the exact one at a distance d (every point of the difference
// lies beyond the exact normal's plane at d), within sqrt(2 gap / R) on a smooth side of radius R:
// about 0.3 degree on a rim of 0.3 m, for shapes of half a metre. Within a millimetre or so the
// full search's float solvers often stall in the same band.
GjkResult gjk_contact(const PlacedShape& a, const PlacedShape& b, const Vec3& initial_direction,
                      Simplex& out_simplex, Real reject_beyond);

// What conservative advancement (toi.cpp) asks of a distance: whether the shapes stay farther
// apart than `reach` while A moves by `delta` relative to B and any surface point turns by at most
// `spin` (both over what remains of the interval). Along any axis n the gap closes no faster than
// delta.n + spin, so a lower bound g on the gap along n with g - reach > delta.n + spin answers
// yes; the advancement then finds no impact, whatever the distance.
struct SweepBound {
  Vec3 delta = Vec3::Zero();  // m, A's motion relative to B
  Real spin = 0;              // m
  Real reach = 0;             // m
};

// gjk_placed, stopping as soon as its lower bound along the search axis shows the shapes staying
// apart over the motion `bound` describes (result.beyond, with that bound in result.lower_bound);
// otherwise the same search, bit for bit. perf: conservative advancement needs the distance only
// where it may stop; GJK's convergence on a rounded or curved shape takes many more supports than
// its first bound that clears the motion.
GjkResult gjk_placed(const PlacedShape& a, const PlacedShape& b, const Vec3& initial_direction,
                     Simplex& out_simplex, const SweepBound& bound);

// GJK between a point or a segment (`core`: one point, or the two ends) and the core of `b`, all
// in B's principal frame, as are the result's points. perf: B's support then needs no rotation
// and the segment's is a choice of end; rotating directions and points would otherwise be much of
// the GJK work of the sphere and capsule pairs with hulls and boxes.
GjkResult gjk_core_in_frame_of_b(std::span<const Vec3> core, const Shape& b, Simplex& s);

// GJK between the convex hulls of two point sets in one frame, from `direction` (A towards B),
// stopping once its lower bound passes `reject_beyond` (result.beyond). The SAT's check of a
// separation that only bounds the distance from below (sat.cpp).
GjkResult gjk_point_sets(std::span<const Vec3> a, std::span<const Vec3> b, const Vec3& direction,
                         Real reject_beyond);

// epa_penetration's answer from its GJK already run: `g` and `s` are gjk_placed(pa, pb,
// pb.position - pa.position) on the cores (a shape with no core radius is its own core, whether
// placed with its radius or not). perf: a caller whose own GJK was that search (collide_general
// on two shapes with no radius) does not run it twice.
EpaResult epa_after_gjk(const PlacedShape& pa, const PlacedShape& pb, const GjkResult& g,
                        const Simplex& s);

// EPA on the placed shapes from GJK's terminating simplex (origin in or on it).
EpaResult epa_placed(const PlacedShape& a, const PlacedShape& b, const Simplex& simplex);

// GJK and EPA of a placed shape A against a triangle (B: its corners, in A's placement frame).
// perf: the same routines as the shape pairs, instantiated on the triangle's support, so a mesh
// needs no hull per triangle. GJK stops as soon as its lower bound shows the two farther apart
// than `reject_beyond` (result.beyond): a caller that rejects such a triangle needs no more.
GjkResult gjk_triangle(const PlacedShape& a, const Vec3 (&triangle)[3],
                       const Vec3& initial_direction, Simplex& s,
                       Real reject_beyond = std::numeric_limits<Real>::infinity());
// gjk_triangle to a contact's precision (gjk_contact).
GjkResult gjk_triangle_contact(const PlacedShape& a, const Vec3 (&triangle)[3],
                               const Vec3& initial_direction, Simplex& s, Real reject_beyond);
// gjk_triangle with gjk_placed's sweep bound.
GjkResult gjk_triangle(const PlacedShape& a, const Vec3 (&triangle)[3],
                       const Vec3& initial_direction, Simplex& s, const SweepBound& bound);
EpaResult epa_triangle(const PlacedShape& a, const Vec3 (&triangle)[3], const Simplex& simplex);

}  // namespace elan::detail
