// SPDX-License-Identifier: MIT
// Sutherland-Hodgman clipping of an incident polygon against a reference face's side planes,
// tracking for every output vertex the two lines (incident edges or side planes) that meet there,
// which is what makes contact feature ids stable.
#pragma once

#include <array>
#include <cstdint>

#include "elan/math.hpp"

namespace elan::detail {

inline constexpr int kMaxClipVertices = 512;
// Line labels: incident edge k is (k & 63); side plane k is 64 + (k & 63).
inline constexpr uint8_t kSidePlaneLabel = 64;

struct ClipPolygon {
  int count = 0;
  std::array<Vec3, kMaxClipVertices> points;
  std::array<uint8_t, kMaxClipVertices> out_label;  // label of the edge leaving the vertex
};

// Keeps the part of `in` with dot(plane_normal, x - plane_point) <= 0 into `out`; `label` names
// the plane. The polygon is convex (or a segment, count 2, or a point).
void clip_polygon(const ClipPolygon& in, const Vec3& plane_normal, const Vec3& plane_point,
                  uint8_t label, ClipPolygon& out);

// 14-bit id of vertex k of a clipped polygon: the labels of the lines meeting there.
inline uint32_t clip_vertex_id(const ClipPolygon& p, int k) {
  const int prev = k == 0 ? p.count - 1 : k - 1;
  return (uint32_t(p.out_label[prev] & 0x7F) << 7) | uint32_t(p.out_label[k] & 0x7F);
}

}  // namespace elan::detail
