// SPDX-License-Identifier: MIT
// GJK/EPA normal plus supporting-feature clipping (see general.hpp).
#include "narrowphase/general.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "narrowphase/gjk.hpp"
#include "narrowphase/manifold_reduce.hpp"
#include "narrowphase/minkowski.hpp"
#include "narrowphase/sat.hpp"
#include "narrowphase/supporting_feature.hpp"

namespace elan::detail {

bool collide_general(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                     Real speculative_distance, Manifold& out, Separation* separation) {
  out.point_count = 0;
  Vec3 n;
  Real sep;
  Vec3 pa, pb;  // world closest / deepest points on A and B
  // perf: most pairs of falling or scattered bodies whose boxes meet are apart by more than
  // the speculative distance; GJK stops once its lower bound shows them farther than that plus
  // kEarlyReject, whose bound the separation cache keeps (so the pair is skipped while it cannot
  // have closed that much). A pair nearer runs the whole search, as before.
  constexpr Real kEarlyReject = Real(0.03);
  // A rounded shape (sphere, capsule) is its core swept by a ball: the shapes are the cores'
  // distance less the radii apart, along the cores' normal. perf: GJK converges on the core (a
  // capsule's segment) in fewer searches than on the swept surface, which is curved everywhere.
  const Real radius_a = core_radius(a), radius_b = core_radius(b);
  const Real radii = radius_a + radius_b;
  Simplex simplex;
  const PlacedShape core_a = place(a, xa, false), core_b = place(b, xb, false);
  const GjkResult g = gjk_contact(core_a, core_b, Vec3::Zero(), simplex,
                                  speculative_distance + kEarlyReject + radii);
  if (g.beyond) {
    report_separation(separation, Separation::Kind::Distance, g.lower_bound - radii);
    return false;
  }
  if (!g.overlap && g.distance > Real(1e-6) * std::max(a.bounding_radius, b.bounding_radius)) {
    sep = g.distance - radii;
    if (sep > speculative_distance) {
      report_separation(separation, Separation::Kind::Distance, g.lower_bound - radii);
      return false;
    }
    n = (g.point_b - g.point_a) / g.distance;
    pa = g.point_a + radius_a * n;
    pb = g.point_b - radius_b * n;
  } else {
    // perf: the search above, when it ended in overlap, is epa_penetration's own GJK bit for bit
    // (the cores, the same start b - a): its simplex goes straight to EPA. Cores touching within
    // the contact's precision search again.
    const EpaResult e =
        g.overlap ? epa_after_gjk(core_a, core_b, g, simplex) : epa_penetration(a, xa, b, xb);
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

  FeatureClip clipped;
  const Feature* ref = fa.count >= 3 ? &fa : (fb.count >= 3 ? &fb : nullptr);
  const bool ref_is_a = ref == &fa;
  if (ref) clip_against(*ref, ref_is_a ? fb : fa, clipped);

  Vec3 points[FeatureClip::kCapacity];
  Real seps[FeatureClip::kCapacity];
  uint32_t ids[FeatureClip::kCapacity];
  int count = 0;
  const uint32_t base =
      kFeatureSegment | (1u << 28) | ((fa.id & 0x7F) << 21) | ((fb.id & 0x7F) << 14);
  if (ref) {
    const RefPlane plane = ref_plane(*ref, n, ref_is_a);
    for (int k = 0; k < clipped.count; ++k) {
      const Vec3& p = clipped.points[k];
      const Real s = plane.gap(p);
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
