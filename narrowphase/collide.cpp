// SPDX-License-Identifier: MIT
// collide(): one pair, dispatched on the shape types to the cheapest exact routine (closed forms,
// SAT with clipping, or the general GJK/EPA path); a mesh, heightfield or compound to the
// composite walk.
#include "narrowphase/collide.hpp"

#include <cstring>
#include <utility>

#include "narrowphase/box_box.hpp"
#include "narrowphase/capsule_polyhedron.hpp"
#include "narrowphase/composite.hpp"
#include "narrowphase/general.hpp"
#include "narrowphase/gjk.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase/round_pairs.hpp"
#include "narrowphase/sat.hpp"

namespace elan::detail {

namespace {

using PairFn = bool (*)(const Shape&, const Transform&, const Shape&, const Transform&, Real,
                        Manifold&, Separation*);

// A's polyhedron in the working frame, from `cache` when it holds A as it is.
const Polyhedron& polyhedron_of_a(const Shape& a, const Transform& xa, PolyhedronCache& cache) {
  if (cache.shape != &a ||
      std::memcmp(cache.rotation.coeffs().data(), xa.rotation.coeffs().data(), sizeof(Quat)) != 0) {
    make_polyhedron(a, xa.rotation, Vec3::Zero(), cache.polyhedron);
    cache.shape = &a;
    cache.rotation = xa.rotation;
  }
  return cache.polyhedron;
}

// Both in one working frame: world rotation, origin at A's centre of mass, so coordinates stay
// small far from the world origin. A's polyhedron comes from `cache` when it holds A as it is.
bool collide_sat_cached(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                        Real speculative_distance, Manifold& out, PolyhedronCache& cache,
                        Separation* separation) {
  const Polyhedron& pa = polyhedron_of_a(a, xa, cache);
  Polyhedron pb;
  make_polyhedron(b, xb.rotation, xb.position - xa.position, pb);
  return collide_polyhedra(pa, pb, speculative_distance, out, separation);
}

bool collide_sat(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                 Real speculative_distance, Manifold& out, Separation* separation) {
  PolyhedronCache a_only;
  return collide_sat_cached(a, xa, b, xb, speculative_distance, out, a_only, separation);
}

bool collide_capsule_poly(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                          Real speculative_distance, Manifold& out, Separation* separation) {
  const Vec3 axis = xa.rotation * Vec3(0, a.half_height, 0);
  const Vec3 offset = xb.position - xa.position;  // B's centre in the working frame
  Polyhedron pb;
  make_polyhedron(b, xb.rotation, offset, pb);
  // SAT measures the depth of an overlapping segment exactly; a segment apart from the box
  // (only the radius overlaps) needs the true closest points. B's faces bound the distance from
  // below, and give it exactly when the segment's nearer end stands over the face (a capsule
  // lying on a box); otherwise GJK gives it, in B's frame.
  // perf: most capsules of a pile rest on a face; those take no GJK.
  const SegmentFaceQuery face = query_segment_faces(-axis, axis, pb);
  if (face.separation - a.radius > speculative_distance) {
    report_separation(separation, Separation::Kind::FaceOfB, face.separation - a.radius);
    return false;
  }
  const Real touching = Real(1e-6) * (a.half_height + a.radius);
  if (face.foot_on_face && face.separation > touching) {
    const Vec3 normal = -pb.normals[face.face];
    return collide_segment_polyhedron_separated(-axis, axis, a.radius, pb, normal, face.nearest,
                                                face.nearest + face.separation * normal,
                                                speculative_distance, out);
  }
  const Quat to_b = xb.rotation.conjugate();
  const Vec3 centre = to_b * Vec3(-offset), half = to_b * axis;
  const Vec3 ends[2] = {centre - half, centre + half};
  Simplex simplex;
  const GjkResult g = gjk_core_in_frame_of_b(ends, b, simplex);
  if (g.overlap || g.distance <= touching) {
    return collide_segment_polyhedron(-axis, axis, a.radius, pb, speculative_distance, out);
  }
  if (g.distance - a.radius > speculative_distance) {
    report_separation(separation, Separation::Kind::Distance, g.lower_bound - a.radius);
    return false;
  }
  const Vec3 normal = xb.rotation * ((g.point_b - g.point_a) / g.distance);
  return collide_segment_polyhedron_separated(
      -axis, axis, a.radius, pb, normal, xb.rotation * g.point_a + offset,
      xb.rotation * g.point_b + offset, speculative_distance, out);
}

// The routine for (ta, tb) in that order, or null if only the (tb, ta) order exists.
PairFn pick(const Shape& a, const Shape& b) {
  const ShapeType ta = a.type, tb = b.type;
  if (tb == ShapeType::Plane) return ta == ShapeType::Plane ? nullptr : collide_convex_plane;
  if (ta == ShapeType::Plane) return nullptr;
  if (ta == ShapeType::Sphere) {
    switch (tb) {
      case ShapeType::Sphere:
        return collide_sphere_sphere;
      case ShapeType::Capsule:
        return collide_sphere_capsule;
      case ShapeType::Box:
        return collide_sphere_box;
      default:
        return collide_sphere_convex;
    }
  }
  if (tb == ShapeType::Sphere) return nullptr;
  if (ta == ShapeType::Capsule && tb == ShapeType::Capsule) return collide_capsule_capsule;
  if (ta == ShapeType::Capsule && is_sat_polyhedron(b)) return collide_capsule_poly;
  if (tb == ShapeType::Capsule && is_sat_polyhedron(a)) return nullptr;
  if (ta == ShapeType::Box && tb == ShapeType::Box) return collide_box_box;
  if (sat_is_affordable(a, b)) return collide_sat;
  return collide_general;
}

// One dispatch for both entry points; a box or hull pair reuses `cache` when there is one.
bool dispatch(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
              Real speculative_distance, Manifold& out, PolyhedronCache* cache,
              Separation* separation, const SurfaceMotion* motion) {
  out.point_count = 0;
  report_separation(separation, Separation::Kind::Unknown, 0);
  // A mesh, heightfield or compound: piece by piece, merged into one manifold (its separation
  // stays Unknown: no one measure of the pieces lasts).
  if (is_composite(a) || is_composite(b)) {
    return collide_composite(a, xa, b, xb, speculative_distance, out, motion);
  }
  if (PairFn f = pick(a, b)) {
    if (f == collide_sat && cache != nullptr) {
      return collide_sat_cached(a, xa, b, xb, speculative_distance, out, *cache, separation);
    }
    return f(a, xa, b, xb, speculative_distance, out, separation);
  }
  if (a.type == ShapeType::Plane && b.type == ShapeType::Plane) return false;
  // Only the (B, A) routine exists: run it, then flip the normal, measure the points from A's
  // centre instead of B's (and swap the frame of a face the rejection measured along).
  PairFn g = pick(b, a);
  if (!g || !g(b, xb, a, xa, speculative_distance, out, separation)) {
    out.point_count = 0;
    if (separation != nullptr) separation->kind = swap_sides(separation->kind);
    return false;
  }
  out.normal = -out.normal;
  const Vec3 b_from_a = xb.position - xa.position;
  for (int k = 0; k < out.point_count; ++k) out.points[k].anchor_a += b_from_a;
  return true;
}

}  // namespace

bool edge_pair_separates(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                         int edge_a, int edge_b, Real speculative_distance,
                         PolyhedronCache& cache) {
  if (a.type == ShapeType::Box && b.type == ShapeType::Box) {
    return box_edge_pair_separation(a, xa, b, xb, edge_a, edge_b) > speculative_distance;
  }
  if (!sat_is_affordable(a, b)) return false;
  // The polyhedra as collide_sat_cached places them, so the gap has the SAT's bits.
  const Polyhedron& pa = polyhedron_of_a(a, xa, cache);
  Polyhedron pb;
  make_polyhedron(b, xb.rotation, xb.position - xa.position, pb);
  return edge_pair_separation(pa, pb, edge_a, edge_b) > speculative_distance;
}

bool exact_test_is_closed_form(const Shape& a, const Shape& b) {
  if (is_composite(a) || is_composite(b)) return false;
  PairFn f = pick(a, b);
  if (f == nullptr) f = pick(b, a);
  return f == collide_sphere_sphere || f == collide_sphere_capsule ||
         f == collide_capsule_capsule || f == collide_sphere_box;
}

bool collide(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
             Real speculative_distance, Manifold& out) {
  return dispatch(a, xa, b, xb, speculative_distance, out, nullptr, nullptr, nullptr);
}

bool collide(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
             Real speculative_distance, Manifold& out, PolyhedronCache& cache,
             Separation& separation, const SurfaceMotion* motion) {
  return dispatch(a, xa, b, xb, speculative_distance, out, &cache, &separation, motion);
}

}  // namespace elan::detail
