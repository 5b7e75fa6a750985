// SPDX-License-Identifier: MIT
// Sutherland-Hodgman polygon clipping with line labels for feature ids (see clip.hpp).
#include "narrowphase/clip.hpp"

namespace elan::detail {

void clip_polygon(const ClipPolygon& in, const Vec3& plane_normal, const Vec3& plane_point,
                  uint8_t label, ClipPolygon& out) {
  const auto beyond = [&](const Vec3& x) { return plane_normal.dot(x - plane_point); };
  clip_by(in, beyond, label, out);
}

}  // namespace elan::detail
