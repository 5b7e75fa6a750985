// SPDX-License-Identifier: MIT
// Sutherland-Hodgman polygon clipping with line labels for feature ids (see clip.hpp).
#include "narrowphase/clip.hpp"

namespace elan::detail {

void clip_polygon(const ClipPolygon& in, const Vec3& plane_normal, const Vec3& plane_point,
                  uint8_t label, ClipPolygon& out) {
  out.count = 0;
  const int n = in.count;
  if (n == 0) return;
  Real d_cur = plane_normal.dot(in.points[n - 1] - plane_point);
  int cur = n - 1;
  // A vertex leaving the half-space starts an edge along the plane; one entering continues the
  // incident edge it lies on (its label is the label of the edge being crossed).
  for (int next = 0; next < n && out.count < kMaxClipVertices - 1; ++next) {
    const Real d_next = plane_normal.dot(in.points[next] - plane_point);
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

}  // namespace elan::detail
