// SPDX-License-Identifier: MIT
// Supporting features and their clipping (see supporting_feature.hpp).
#include "narrowphase/supporting_feature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/base/fixed_math.hpp"

namespace elan::detail {
namespace {

// The cap polygon's corners on the unit circle, at angles 2 pi k / kCapSides. perf: made once
// (the same values each call would give), not eight series per cap feature.
struct CapCorners {
  Real cos[kCapSides];
  Real sin[kCapSides];
};

const CapCorners& cap_corners() {
  static const CapCorners corners = [] {
    CapCorners c;
    for (int k = 0; k < kCapSides; ++k) {
      const Real t = Real(2 * M_PI) * Real(k) / Real(kCapSides);
      const FixedSinCos sc = fixed_sin_cos(t);
      c.cos[k] = Real(sc.cos);
      c.sin[k] = Real(sc.sin);
    }
    return c;
  }();
  return corners;
}

}  // namespace

void supporting_feature(const Shape& s, const Transform& x, const Vec3& d, const Vec3& origin,
                        Feature& f, FeatureMemo* memo) {
  const Vec3 dl = x.rotation.conjugate() * d;
  const Vec3 rel = x.position - origin;
  const auto put = [&](int k, const Vec3& local) { f.points[k] = x.rotation * local + rel; };
  // Face `key` (from 1, one numbering per shape): the kept one, or made by `make` and kept.
  const auto face = [&](uint32_t key, const auto& make) {
    if (memo != nullptr && memo->key == key) {
      f.count = memo->feature.count;
      f.id = memo->feature.id;
      std::copy_n(memo->feature.points, f.count, f.points);
      return;
    }
    make();
    if (memo != nullptr) {
      memo->key = key;
      memo->feature.count = f.count;
      memo->feature.id = f.id;
      std::copy_n(f.points, f.count, memo->feature.points);
    }
  };
  switch (s.type) {
    case ShapeType::Box: {
      int axis = 0;
      dl.cwiseAbs().maxCoeff(&axis);
      const Real sign = dl[axis] >= 0 ? Real(1) : Real(-1);
      const uint32_t id = uint32_t(2 * axis + (sign < 0 ? 1 : 0));
      face(1 + id, [&] {
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
        f.id = id;
      });
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
      const HullFace& hull_face = h.faces[best];
      if (bd < kFaceCos * dl.norm() || hull_face.count > kMaxFeature) break;
      face(1 + uint32_t(best), [&] {
        for (uint32_t k = 0; k < hull_face.count; ++k)
          put(int(k), h.vertices[h.face_vertices[hull_face.first + k]]);
        f.count = int(hull_face.count);
        f.id = uint32_t(best) & 0x7F;
      });
      return;
    }
    case ShapeType::Cylinder: {
      const Real radial = std::sqrt(dl.x() * dl.x() + dl.z() * dl.z());
      if (std::abs(dl.y()) >= radial) {
        const uint32_t id = dl.y() >= 0 ? 0u : 1u;
        face(1 + id, [&] {
          const Real y = id == 0 ? s.half_height : -s.half_height;
          const CapCorners& cap = cap_corners();
          for (int k = 0; k < kCapSides; ++k) {
            put(k, Vec3(s.radius * cap.cos[k], y, -s.radius * cap.sin[k]));
          }
          f.count = kCapSides;
          f.id = id;
        });
        return;
      }
      if (radial > kFaceCos * dl.norm()) {
        const Real cx = s.radius * dl.x() / radial, cz = s.radius * dl.z() / radial;
        put(0, Vec3(cx, -s.half_height, cz));
        put(1, Vec3(cx, s.half_height, cz));
        f.count = 2;
        const Real angle = Real(fixed_atan2(dl.z(), dl.x())) + Real(M_PI);
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

namespace {

template <int N>
void clip_features(const Feature& ref, const Feature& inc, ClipBuffer<N>& out) {
  ClipBuffer<N> tmp;
  ClipBuffer<N>* cur = &out;
  ClipBuffer<N>* other = &tmp;
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
    const Vec3& v1 = ref.points[k + 1 < ref.count ? k + 1 : 0];
    Vec3 side = (v1 - v0).cross(nref);
    if (side.dot(centroid - v0) > 0) side = -side;
    const auto beyond = [&](const Vec3& x) { return side.dot(x - v0); };
    clip_by(*cur, beyond, uint8_t(kSidePlaneLabel + k), *other);
    std::swap(cur, other);
  }
}

}  // namespace

void clip_against(const Feature& ref, const Feature& inc, FeatureClip& out) {
  clip_features(ref, inc, out);
}

void clip_against(const Feature& ref, const Feature& inc, TriangleClip& out) {
  clip_features(ref, inc, out);
}

Real plane_gap(const Feature& ref, const Vec3& n, const Vec3& p, bool ref_is_a) {
  return ref_plane(ref, n, ref_is_a).gap(p);
}

RefPlane ref_plane(const Feature& ref, const Vec3& n, bool ref_is_a) {
  Vec3 nf = (ref.points[1] - ref.points[0]).cross(ref.points[2] - ref.points[0]);
  if (nf.dot(n) < 0) nf = -nf;
  return {nf, ref.points[0], nf.dot(n), ref_is_a};
}

}  // namespace elan::detail
