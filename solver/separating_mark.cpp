// SPDX-License-Identifier: MIT
// mark_separating(): see separating_mark.hpp.
#include "solver/separating_mark.hpp"

#include "core/base/grow.hpp"
#include "solver/contact_solver.hpp"

namespace elan::detail {

bool mark_separating(BodyStore& bodies, std::span<const ManifoldHead> contacts, bool marked,
                     SolverState& st) {
  const bool clique = st.most_deep > kPushShare;
  if (!marked && !clique) return false;
  const uint32_t end = st.half_start[kHalves];  // the written (awake dynamic) packets
  // The new marks, per packet, from the marks at the step's start (read from the flags, written
  // only below), so the order of the manifolds does not matter.
  grow_fill(st.separating, end, uint8_t{0});
  if (clique || marked) {
    for (uint32_t k = 1; k < end; ++k) st.separating[k] = st.deep_count[k] > 0 ? 1 : 0;
  }
  if (marked) {
    auto carries = [&](uint32_t i) {
      return bodies.is_dynamic(i) && (bodies.flags[i] & kSeparating) != 0;
    };
    auto keep = [&](uint32_t i) {
      const uint32_t p = st.packet_of[i];
      if (p != 0 && p < end) st.separating[p] = 1;
    };
    for (const ManifoldHead& m : contacts) {
      if (m.point_count == 0 || !(m.first.separation < -kSeparatingDepth)) continue;
      if (!carries(m.body_a) && !carries(m.body_b)) continue;
      keep(m.body_a);
      keep(m.body_b);
    }
  }
  for (uint8_t& f : bodies.flags) f &= uint8_t(~kSeparating);
  bool any = false;
  for (uint32_t k = 1; k < end; ++k) {
    if (st.separating[k] == 0) continue;
    bodies.flags[st.masses[k].body] |= kSeparating;
    any = true;
  }
  return any;
}

}  // namespace elan::detail
