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

// A convex polygon of at most N vertices, with the label of the line leaving each vertex.
template <int N>
struct ClipBuffer {
  static constexpr int kCapacity = N;
  int count = 0;
  std::array<Vec3, N> points;
  std::array<uint8_t, N> out_label;  // label of the edge leaving the vertex
};
using ClipPolygon = ClipBuffer<kMaxClipVertices>;

// Keeps the part of `in` where distance(x) <= 0 into `out`; `label` names the line. The polygon
// is convex (or a segment, count 2, or a point). A vertex leaving the half-space starts an edge
// along the line; one entering continues the incident edge it lies on (its label is the label of
// the edge being crossed). Stops short of N vertices, which a convex polygon never reaches.
template <int N, class Distance>
void clip_by(const ClipBuffer<N>& in, const Distance& distance, uint8_t label, ClipBuffer<N>& out) {
  out.count = 0;
  const int n = in.count;
  if (n == 0) return;
  Real d_cur = distance(in.points[n - 1]);
  int cur = n - 1;
  for (int next = 0; next < n && out.count < N - 1; ++next) {
    const Real d_next = distance(in.points[next]);
    const bool cur_in = d_cur <= 0;
    const bool next_in = d_next <= 0;
    if (cur_in != next_in) {
      const Real t = d_cur / (d_cur - d_next);
      out.points[out.count] = in.points[cur] + t * (in.points[next] - in.points[cur]);
      out.out_label[out.count] = cur_in ? label : in.out_label[cur];
      ++out.count;
    }
    if (next_in) {
      out.points[out.count] = in.points[next];
      out.out_label[out.count] = in.out_label[next];
      ++out.count;
    }
    cur = next;
    d_cur = d_next;
  }
}

// Keeps the part of `in` with dot(plane_normal, x - plane_point) <= 0 into `out`; `label` names
// the plane.
void clip_polygon(const ClipPolygon& in, const Vec3& plane_normal, const Vec3& plane_point,
                  uint8_t label, ClipPolygon& out);

// 14-bit id of vertex k of a clipped polygon: the labels of the lines meeting there.
template <int N>
uint32_t clip_vertex_id(const ClipBuffer<N>& p, int k) {
  const int prev = k == 0 ? p.count - 1 : k - 1;
  return (uint32_t(p.out_label[prev] & 0x7F) << 7) | uint32_t(p.out_label[k] & 0x7F);
}

}  // namespace elan::detail
