// SPDX-License-Identifier: MIT
// cap_push_out_velocity(): see push_out_cap.hpp.
#include "solver/push_out_cap.hpp"

#include <algorithm>
#include <cmath>

#include "core/base/grow.hpp"
#include "solver/contact_solver.hpp"

namespace elan::detail {

void find_capped(const BodyStore& bodies, std::span<const ManifoldHead> contacts, bool marked,
                 SolverState& st) {
  st.capped.clear();
  if (!marked && st.most_deep <= kPushShare) return;
  const uint32_t end = st.half_start[kHalves];  // the written (awake dynamic) packets
  grow_fill(st.capped, end, uint8_t{0});
  for (uint32_t k = 1; k < end; ++k) {
    const bool carries = (bodies.flags[st.masses[k].body] & kSeparating) != 0;
    st.capped[k] = carries || st.deep_count[k] > 0 ? 1 : 0;
  }
  if (!marked) return;
  auto carries = [&](uint32_t i) {
    return bodies.is_dynamic(i) && (bodies.flags[i] & kSeparating) != 0;
  };
  auto cap = [&](uint32_t i) {
    const uint32_t p = st.packet_of[i];
    if (p != 0 && p < end && st.capped[p] == 0) st.capped[p] = 2;
  };
  for (const ManifoldHead& m : contacts) {
    if (m.point_count == 0 || !(carries(m.body_a) || carries(m.body_b))) continue;
    cap(m.body_a);
    cap(m.body_b);
  }
}

std::size_t cap_push_out_velocity(const BodyStore& bodies, std::span<const Shape> shapes,
                                  const SolveSettings& settings, SolverState& st) {
  if (st.capped.empty()) return 0;
  const Real cap = settings.max_push_velocity;
  const uint32_t end = st.half_start[kHalves];  // the written (awake dynamic) packets
  std::size_t slowed = 0;
  for (uint32_t k = 1; k < end; ++k) {
    if (st.capped[k] == 0) continue;
    const uint32_t i = st.masses[k].body;
    SolverBody& p = st.packets[k];
    const Vec3 g = bodies.traits_of(i).gravity_scale * settings.gravity;
    const Real v0 = std::max(bodies.linear_velocity(i).norm(), cap);
    const Real v_max = std::sqrt(v0 * v0 + std::max(Real(2) * g.dot(p.dp), Real(0)));
    const Real v = p.v.norm();
    bool slow = false;
    if (v > v_max) {
      p.v *= v_max / v;
      slow = true;
    }
    const Real radius = shapes[bodies.shape[i]].bounding_radius;
    const Real w0 = bodies.angular_velocity(i).norm();
    const Real w_max = radius > 0 ? std::max(w0, cap / radius) : w0;
    const Real w = p.w.norm();
    if (w > w_max && w_max > 0) {
      p.w *= w_max / w;
      slow = true;
    }
    slowed += slow ? 1 : 0;
  }
  return slowed;
}

void cap_push_out_substep(const BodyStore& bodies, const SolveSettings& settings, SolverState& st,
                          uint32_t begin, uint32_t end) {
  const Real cap = settings.max_push_velocity;
  for (uint32_t k = begin; k < end; ++k) {
    if (st.capped[k] != 1) continue;  // marked or deep, not a neighbour
    const uint32_t i = st.masses[k].body;
    SolverBody& p = st.packets[k];
    const Real fall = std::abs(bodies.traits_of(i).gravity_scale) * settings.gravity.norm();
    const Real v_max = std::max(bodies.linear_velocity(i).norm(), cap) + fall * settings.dt;
    const Real v = p.v.norm();
    if (v > v_max) p.v *= v_max / v;
  }
}

}  // namespace elan::detail
