// SPDX-License-Identifier: MIT
// Union-find islands over touching contacts, and island sleep/wake.
#include "solver/islands.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace elan::detail {

namespace {
uint32_t find_root(ScratchVector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];  // path halving
    i = parent[i];
  }
  return i;
}
}  // namespace

std::size_t update_islands(BodyStore& bodies, std::span<const ManifoldHead> contacts,
                           std::span<const JointLink> joints, const IslandSettings& settings,
                           IslandScratch& s, StepScratch& step_scratch) {
  const std::size_t n = bodies.size();
  take_from(s.parent, step_scratch, n);
  for (std::size_t i = 0; i < n; ++i) s.parent[i] = uint32_t(i);
  auto link = [&](uint32_t a, uint32_t b) {
    const uint32_t ra = find_root(s.parent, a);
    const uint32_t rb = find_root(s.parent, b);
    // determinism: link toward the lower index, so the root is the island's lowest body
    // whatever the contact order.
    if (ra < rb)
      s.parent[rb] = ra;
    else if (rb < ra)
      s.parent[ra] = rb;
  };
  for (const ManifoldHead& m : contacts) {
    if (m.point_count == 0) continue;
    if (!bodies.is_dynamic(m.body_a) || !bodies.is_dynamic(m.body_b)) continue;
    link(m.body_a, m.body_b);
  }
  for (const JointLink& j : joints) {
    if (j.a == UINT32_MAX || j.b == UINT32_MAX) continue;
    if (!bodies.is_dynamic(j.a) || !bodies.is_dynamic(j.b)) continue;
    link(j.a, j.b);
  }

  take_from(s.island_sleep_time, step_scratch);
  s.island_sleep_time.assign(n, std::numeric_limits<Real>::max());
  take_from(s.island_awake, step_scratch);
  s.island_awake.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!bodies.is_dynamic(i) || (bodies.flags[i] & kFrozen)) continue;
    const uint32_t r = find_root(s.parent, uint32_t(i));
    s.parent[i] = r;
    if (bodies.is_awake(i)) {
      s.island_awake[r] = 1;
      s.island_sleep_time[r] = std::min(s.island_sleep_time[r], bodies.sleep_time[i]);
    }
  }
  // A moving kinematic body keeps what it touches awake. perf: the bodies are checked for one
  // first, a pass over a byte and six floats a body, so a scene without one does not read the
  // contact list a second time (a cache line a manifold, at 2 threads most of them last written
  // by the other thread).
  auto moving = [&](uint32_t k) {
    return bodies.motion[k] == uint8_t(MotionType::Kinematic) &&
           (bodies.vx[k] != 0 || bodies.vy[k] != 0 || bodies.vz[k] != 0 || bodies.wx[k] != 0 ||
            bodies.wy[k] != 0 || bodies.wz[k] != 0);
  };
  bool any_moving = false;
  for (std::size_t k = 0; k < n && !any_moving; ++k) any_moving = moving(uint32_t(k));
  auto keep_awake = [&](uint32_t dynamic) {
    const uint32_t r = s.parent[dynamic];
    s.island_awake[r] = 1;
    s.island_sleep_time[r] = 0;
  };
  for (const ManifoldHead& m : any_moving ? contacts : std::span<const ManifoldHead>()) {
    if (m.point_count == 0) continue;
    // A kinematic body of a pair is B.
    if (!moving(m.body_b) || !bodies.is_dynamic(m.body_a)) continue;
    keep_awake(m.body_a);
  }
  for (const JointLink& j : any_moving ? joints : std::span<const JointLink>()) {
    if (j.a == UINT32_MAX || j.b == UINT32_MAX) continue;
    if (moving(j.b) && bodies.is_dynamic(j.a) && !(bodies.flags[j.a] & kFrozen)) keep_awake(j.a);
    if (moving(j.a) && bodies.is_dynamic(j.b) && !(bodies.flags[j.b] & kFrozen)) keep_awake(j.b);
  }

  std::size_t islands = 0;
  s.root.assign(n, UINT32_MAX);
  s.size.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!bodies.is_dynamic(i) || (bodies.flags[i] & kFrozen)) continue;
    const uint32_t r = s.parent[i];
    s.root[i] = r;
    ++s.size[r];
    if (r == i) ++islands;
    if (!s.island_awake[r]) continue;
    if (settings.allow_sleep && s.island_sleep_time[r] >= settings.time_to_sleep) {
      bodies.flags[i] &= uint8_t(~kAwake);
      bodies.vx[i] = bodies.vy[i] = bodies.vz[i] = 0;
      bodies.wx[i] = bodies.wy[i] = bodies.wz[i] = 0;
    } else if (!bodies.is_awake(i)) {
      bodies.flags[i] |= kAwake;  // woken by its island
      bodies.sleep_time[i] = 0;
    }
  }
  // The last taken first, so the block's next buffer starts where these did.
  release(s.island_awake);
  release(s.island_sleep_time);
  release(s.parent);
  return islands;
}

void update_sleep_timers(BodyStore& bodies, std::span<const Shape> shapes, Real dt,
                         Real threshold) {
  const std::size_t n = bodies.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!bodies.is_dynamic(i) || !bodies.is_awake(i)) continue;
    const Real v2 =
        bodies.vx[i] * bodies.vx[i] + bodies.vy[i] * bodies.vy[i] + bodies.vz[i] * bodies.vz[i];
    const Real w2 =
        bodies.wx[i] * bodies.wx[i] + bodies.wy[i] * bodies.wy[i] + bodies.wz[i] * bodies.wz[i];
    const Real r = shapes[bodies.shape[i]].bounding_radius;
    const Real speed2 = std::max(v2, w2 * r * r);
    bodies.sleep_time[i] = speed2 > threshold * threshold ? Real(0) : bodies.sleep_time[i] + dt;
  }
}

}  // namespace elan::detail
