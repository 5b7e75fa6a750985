// SPDX-License-Identifier: MIT
// A convex shape's supporting feature along a direction (face, segment or point) and the clipping
// of one feature against a polygon's side planes: how the general path and the triangle contacts
// turn one normal into a manifold (as Jolt's ManifoldBetweenTwoFaces does).
#pragma once

#include <cstdint>

#include "core/base/shape.hpp"
#include "narrowphase/clip.hpp"

namespace elan::detail {

// A cylinder cap is approximated by an inscribed regular polygon of this many sides.
inline constexpr int kCapSides = 8;
inline constexpr int kMaxFeature = 64;
// A face is used as the supporting feature only if its normal is this close to the contact
// normal (cosine); otherwise the support point alone.
inline constexpr Real kFaceCos = Real(0.7);

struct Feature {
  int count = 0;  // 1 point, 2 segment, >= 3 polygon
  Vec3 points[kMaxFeature];
  uint32_t id = 0;  // which feature of the shape (7 bits)
};

// The face a caller made last for one shape at one pose and origin: a box's face, a hull's face
// or a cylinder's cap depends on the direction only through which one it is, so a caller that
// asks again for the same one (a body over the triangles of a surface, each with its own normal)
// takes its points as they were made. `key` names the face (supporting_feature's numbering per
// shape, from 1); 0: none kept.
struct FeatureMemo {
  uint32_t key = 0;
  Feature feature;
};

// Supporting feature of `s` (pose x) in world direction d (unit), points in world relative to
// `origin`. With `memo` (every call with the same s, x and origin): the kept face when it is the
// one d picks, the same bits as making it again; a face made is kept.
void supporting_feature(const Shape& s, const Transform& x, const Vec3& d, const Vec3& origin,
                        Feature& f, FeatureMemo* memo = nullptr);

// A feature clipped against another: each side plane adds at most one vertex to the convex
// polygon it cuts, so two features give at most 2 kMaxFeature (one more: clip_by stops short of
// its capacity). perf: the stack buffers of a contact are a few cache lines, not ClipPolygon's
// 6.5 KB with its labels a page away from its points.
using FeatureClip = ClipBuffer<2 * kMaxFeature + 1>;
// A feature clipped against a triangle, or a triangle against a feature: kMaxFeature + 3 at most.
using TriangleClip = ClipBuffer<kMaxFeature + 4>;

// Clips `inc` against the side planes of polygon `ref` (both relative to one origin); writes
// the clipped points to `out`.
void clip_against(const Feature& ref, const Feature& inc, FeatureClip& out);
void clip_against(const Feature& ref, const Feature& inc, TriangleClip& out);

// Separation along n of point p (on the incident side) from the plane of polygon `ref`.
Real plane_gap(const Feature& ref, const Vec3& n, const Vec3& p, bool ref_is_a);

// plane_gap's plane made once for the many points of one clipping: gap(p) is plane_gap(ref, n, p,
// ref_is_a), bit for bit (the same operations on the same values).
struct RefPlane {
  Vec3 normal;  // ref's unnormalised normal, turned to n's side
  Vec3 origin;  // ref's first point
  Real along;   // normal . n
  bool ref_is_a;

  Real gap(const Vec3& p) const {
    const Real t = normal.dot(p - origin) / along;
    return ref_is_a ? t : -t;
  }
};
RefPlane ref_plane(const Feature& ref, const Vec3& n, bool ref_is_a);

}  // namespace elan::detail
