// SPDX-License-Identifier: MIT
// GJK/EPA normal plus supporting-feature clipping (see general.hpp).
#include "narrowphase/general.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "narrowphase/clip.hpp"
#include "narrowphase/gjk.hpp"
#include "narrowphase/manifold_reduce.hpp"
#include "narrowphase/sat.hpp"

namespace elan::detail {

namespace {

// A cylinder cap is approximated by an inscribed regular polygon of this many sides.
constexpr int kCapSides = 8;
constexpr int kMaxFeature = 64;
// A face is used as the supporting feature only if its normal is this close to the contact
// normal (cosine); otherwise the support point alone.
constexpr Real kFaceCos = Real(0.7);

struct Feature {
  int count = 0;  // 1 point, 2 segment, >= 3 polygon
  Vec3 points[kMaxFeature];
  uint32_t id = 0;  // which feature of the shape (7 bits)
};

// Supporting feature of `s` (pose x) in world direction d (unit), points in world relative to
// `origin`.
void supporting_feature(const Shape& s, const Transform& x, const Vec3& d, const Vec3& origin,
                        Feature& f) {
  const Vec3 dl = x.rotation.conjugate() * d;
  const Vec3 rel = x.position - origin;
  const auto put = [&](int k, const Vec3& local) { f.points[k] = x.rotation * local + rel; };
  switch (s.type) {
    case ShapeType::Box: {
      int axis = 0;
      dl.cwiseAbs().maxCoeff(&axis);
      const Real sign = dl[axis] >= 0 ? Real(1) : Real(-1);
      const Vec3& h = s.half_extents;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const Real su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
      for (int k = 0; k < 4; ++k) {
        Vec3 p;
        p[axis] = sign * h[axis];
        p[u] = su[k] * h[u];
        p[v] = sv[k] * h[v];
        put(k, p);
      }
      f.count = 4;
      f.id = uint32_t(2 * axis + (sign < 0 ? 1 : 0));
      return;
    }
    case ShapeType::ConvexHull: {
      const ConvexHull& h = *s.hull;
      int best = 0;
      Real bd = std::numeric_limits<Real>::lowest();
      for (std::size_t i = 0; i < h.faces.size(); ++i) {
        const Real dd = h.faces[i].normal.dot(dl);
        if (dd > bd) {
          bd = dd;
          best = int(i);
        }
      }
      const HullFace& face = h.faces[best];
      if (bd < kFaceCos * dl.norm() || face.count > kMaxFeature) break;
      for (uint32_t k = 0; k < face.count; ++k)
        put(int(k), h.vertices[h.face_vertices[face.first + k]]);
      f.count = int(face.count);
      f.id = uint32_t(best) & 0x7F;
      return;
    }
    case ShapeType::Cylinder: {
      const Real radial = std::sqrt(dl.x() * dl.x() + dl.z() * dl.z());
      if (std::abs(dl.y()) >= radial) {
        const Real y = dl.y() >= 0 ? s.half_height : -s.half_height;
        for (int k = 0; k < kCapSides; ++k) {
          const Real t = Real(2 * M_PI) * Real(k) / Real(kCapSides);
          put(k, Vec3(s.radius * std::cos(t), y, -s.radius * std::sin(t)));
        }
        f.count = kCapSides;
        f.id = dl.y() >= 0 ? 0u : 1u;
        return;
      }
      if (radial > kFaceCos * dl.norm()) {
        const Real cx = s.radius * dl.x() / radial, cz = s.radius * dl.z() / radial;
        put(0, Vec3(cx, -s.half_height, cz));
        put(1, Vec3(cx, s.half_height, cz));
        f.count = 2;
        const Real angle = std::atan2(dl.z(), dl.x()) + Real(M_PI);
        f.id = 2u + (uint32_t(angle * Real(8 / M_PI)) & 15u);
        return;
      }
      break;
    }
    case ShapeType::Capsule: {
      const Real along = dl.y();
      const Vec3 off = d * s.radius;
      if (std::abs(along) < (Real(1) - kFaceCos) * dl.norm()) {
        f.points[0] = x.rotation * Vec3(0, -s.half_height, 0) + rel + off;
        f.points[1] = x.rotation * Vec3(0, s.half_height, 0) + rel + off;
        f.count = 2;
        f.id = 2;
        return;
      }
      f.points[0] =
          x.rotation * Vec3(0, along >= 0 ? s.half_height : -s.half_height, 0) + rel + off;
      f.count = 1;
      f.id = along >= 0 ? 1u : 0u;
      return;
    }
    default:
      break;
  }
  f.points[0] = x.rotation * support(s, dl) + rel;
  f.count = 1;
  f.id = 0x7F;
}

// Clips `inc` against the side planes of polygon `ref` (both relative to one origin); writes
// the clipped points to `out`.
void clip_against(const Feature& ref, const Feature& inc, ClipPolygon& out) {
  ClipPolygon tmp;
  ClipPolygon* cur = &out;
  ClipPolygon* other = &tmp;
  // Use an even number of swaps so the result lands in `out`.
  if (ref.count % 2 == 1) std::swap(cur, other);
  for (int k = 0; k < inc.count; ++k) {
    cur->points[k] = inc.points[k];
    cur->out_label[k] = uint8_t(k);
  }
  cur->count = inc.count;
  Vec3 centroid = Vec3::Zero();
  for (int k = 0; k < ref.count; ++k) centroid += ref.points[k];
  centroid /= Real(ref.count);
  const Vec3 nref = (ref.points[1] - ref.points[0]).cross(ref.points[2] - ref.points[0]);
  for (int k = 0; k < ref.count; ++k) {
    const Vec3& v0 = ref.points[k];
    const Vec3& v1 = ref.points[(k + 1) % ref.count];
    Vec3 side = (v1 - v0).cross(nref);
    if (side.dot(centroid - v0) > 0) side = -side;
    clip_polygon(*cur, side, v0, uint8_t(kSidePlaneLabel + k), *other);
    std::swap(cur, other);
  }
}

// Separation along n of point p (on the incident side) from the plane of polygon `ref`.
Real plane_gap(const Feature& ref, const Vec3& n, const Vec3& p, bool ref_is_a) {
  Vec3 nf = (ref.points[1] - ref.points[0]).cross(ref.points[2] - ref.points[0]);
  if (nf.dot(n) < 0) nf = -nf;
  const Real along = nf.dot(n);
  const Real t = nf.dot(p - ref.points[0]) / along;
  return ref_is_a ? t : -t;
}

}  // namespace

bool collide_general(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                     Real speculative_distance, Manifold& out, Separation* separation) {
  out.point_count = 0;
  Vec3 n;
  Real sep;
  Vec3 pa, pb;  // world closest / deepest points on A and B
  const GjkResult g = gjk_distance(a, xa, b, xb, true);
  if (!g.overlap && g.distance > Real(1e-6) * std::max(a.bounding_radius, b.bounding_radius)) {
    if (g.distance > speculative_distance) {
      report_separation(separation, Separation::Kind::Distance, g.lower_bound);
      return false;
    }
    n = (g.point_b - g.point_a) / g.distance;
    sep = g.distance;
    pa = g.point_a;
    pb = g.point_b;
  } else {
    const EpaResult e = epa_penetration(a, xa, b, xb);
    n = e.normal;
    sep = -e.depth;
    pa = e.point_a;
    pb = e.point_b;
    if (!e.ok || !n.allFinite() || n.squaredNorm() < Real(0.5)) {
      const Vec3 d = xb.position - xa.position;
      n = d.squaredNorm() > 0 ? Vec3(d.normalized()) : Vec3::UnitY();
      pa = pb = Real(0.5) * (xa.position + xb.position);
    }
  }
  out.normal = n;
  const Vec3 origin = xa.position;
  Feature fa, fb;
  supporting_feature(a, xa, n, origin, fa);
  supporting_feature(b, xb, -n, origin, fb);

  ClipPolygon clipped;
  const Feature* ref = fa.count >= 3 ? &fa : (fb.count >= 3 ? &fb : nullptr);
  const bool ref_is_a = ref == &fa;
  if (ref) clip_against(*ref, ref_is_a ? fb : fa, clipped);

  Vec3 points[kMaxClipVertices];
  Real seps[kMaxClipVertices];
  uint32_t ids[kMaxClipVertices];
  int count = 0;
  const uint32_t base =
      kFeatureSegment | (1u << 28) | ((fa.id & 0x7F) << 21) | ((fb.id & 0x7F) << 14);
  if (ref) {
    for (int k = 0; k < clipped.count; ++k) {
      const Vec3& p = clipped.points[k];
      const Real s = plane_gap(*ref, n, p, ref_is_a);
      if (s > speculative_distance) continue;
      points[count] = ref_is_a ? Vec3(p - Real(0.5) * s * n) : Vec3(p + Real(0.5) * s * n);
      seps[count] = s;
      ids[count] = base | clip_vertex_id(clipped, k);
      ++count;
    }
  } else if (fa.count == 2 && fb.count == 2) {
    // Two segments: clip A's to B's extent along A's direction, measuring the gap along n.
    const Vec3 u = fa.points[1] - fa.points[0];
    const Real len2 = u.squaredNorm();
    Real t0 = (fb.points[0] - fa.points[0]).dot(u) / len2;
    Real t1 = (fb.points[1] - fa.points[0]).dot(u) / len2;
    if (t0 > t1) std::swap(t0, t1);
    t0 = std::max(t0, Real(0));
    t1 = std::min(t1, Real(1));
    const Vec3 v = fb.points[1] - fb.points[0];
    if (t0 < t1 && std::abs(u.normalized().dot(v.normalized())) > Real(0.99)) {
      for (int k = 0; k < 2; ++k) {
        const Vec3 p = fa.points[0] + (k == 0 ? t0 : t1) * u;
        const Vec3 q = fb.points[0] + v * ((p - fb.points[0]).dot(v) / v.squaredNorm());
        const Real s = n.dot(q - p);
        if (s > speculative_distance) continue;
        points[count] = Real(0.5) * (p + q);
        seps[count] = s;
        ids[count] = base | uint32_t(k);
        ++count;
      }
    }
  }
  if (count == 0) {
    if (sep > speculative_distance) return false;
    points[0] = Real(0.5) * (pa + pb) - origin;
    seps[0] = sep;
    ids[0] = base | 0x3FFFu;
    count = 1;
  }
  int keep[kMaxManifoldPoints];
  int n_keep = count;
  if (count > kMaxManifoldPoints) {
    n_keep = reduce_to_four(std::span<const Vec3>(points, std::size_t(count)),
                            std::span<const Real>(seps, std::size_t(count)), n, keep);
  } else {
    for (int k = 0; k < count; ++k) keep[k] = k;
  }
  for (int k = 0; k < n_keep; ++k) {
    ContactPoint& c = out.points[k];
    c.anchor_a = points[keep[k]];
    c.separation = seps[keep[k]];
    c.feature_id = ids[keep[k]];
  }
  out.point_count = n_keep;
  return n_keep > 0;
}

}  // namespace elan::detail
