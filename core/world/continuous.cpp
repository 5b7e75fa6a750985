// SPDX-License-Identifier: MIT
// Continuous collision of fast bodies by time of impact (against meshes, heightfields and compounds
// too: time_of_impact walks their triangles and parts).
#include "core/world/continuous.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "broadphase/bounds.hpp"
#include "core/base/compound.hpp"
#include "core/base/fixed_math.hpp"
#include "core/base/fixed_slerp.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"
#include "narrowphase/collide.hpp"

namespace elan::detail {

namespace {

// A body is fast when its surface may have moved more than this fraction of its thinnest extent
// during the step (Box2D v3's safety factor).
constexpr Real kFastFraction = Real(0.5);
// perf: a step's times of impact are the few fast bodies' near pairs, bunched in the pair order
// (a body's pairs are adjacent): blocks of 64 pairs spread them over the threads where blocks of
// 256 left one thread most of them.
constexpr std::size_t kPairBlock = 64;
// At most this many static bodies are tested one by one rather than found through the tree.
constexpr std::size_t kFewStatics = 16;

// Half the thinnest side of the shape's box in its principal frame, m; a compound's thinnest
// part's, which is what may pass through something in one step.
Real min_extent(const Shape& s) {
  const Real extent = Real(0.5) * (s.local_max - s.local_min).minCoeff();
  return s.type == ShapeType::Compound ? std::min(extent, s.compound->thinnest) : extent;
}

Real rotation_angle(const Quat& dq) {
  return 2 * Real(fixed_acos(std::min(std::abs(dq.w()), Real(1))));
}

// Whether the bounding spheres of two bodies moving linearly over the step come within `gap`:
// the closest approach of c0 + t d over t in [0, 1], against the sum of the radii.
bool spheres_meet(const Vec3& c0, const Vec3& d, Real radii, Real gap) {
  const Real dd = d.squaredNorm();
  const Real t = dd > 0 ? std::clamp(-c0.dot(d) / dd, Real(0), Real(1)) : Real(0);
  const Real reach = radii + gap;
  return (c0 + t * d).squaredNorm() <= reach * reach;
}

Transform start_pose(const BodyStore& bodies, uint32_t i) {
  return {bodies.position(i), bodies.orientation(i)};
}

Transform end_pose(const BodyStore& bodies, uint32_t i, const SolverBody& p) {
  return {bodies.position(i) + p.dp, (p.dq * bodies.orientation(i)).normalized()};
}

}  // namespace

std::size_t solve_continuous(const BodyStore& bodies, std::span<const Shape> shapes,
                             std::span<const SeparatedPair> separated,
                             std::span<const uint64_t> apart_keys,
                             std::span<const ManifoldHead> touching, const DynamicTree& statics,
                             SolverState& st, Real dt) {
  const std::size_t count = st.packets.size();
  std::vector<uint8_t>& fast = st.fast;
  fast.assign(count, 0);
  bool any = false;
  for (std::size_t k = 1; k < count; ++k) {
    const uint32_t i = st.masses[k].body;
    if (!bodies.is_dynamic(i)) continue;
    const Shape& s = shapes[bodies.shape[i]];
    const SolverBody& p = st.packets[k];
    const Real moved = p.dp.norm() + rotation_angle(p.dq) * s.bounding_radius;
    fast[k] = moved > kFastFraction * min_extent(s);
    any = any || fast[k];
  }
  if (!any) return 0;

  // Impacts are few (a handful of fast bodies' near pairs), so each thread lists those it found
  // rather than every pair keeping a time (4 bytes a pair, most of them never set).
  // Room for a few hundred from the start (2 KiB a thread), so that a scene whose fast bodies
  // come in bursts does not grow the lists in a warm step.
  reset_thread_buffers(st.impacts, std::max<std::size_t>(largest_capacity(st.impacts), 256));
  // A pair with a manifold had its (speculative) contact in the solve, placed along the motion
  // predicted at the step's start: the contact solver has it in hand. So the candidates are the
  // pairs found apart, in either list: one range over both.
  const std::size_t kept = separated.size();
  auto key_at = [&](std::size_t n) { return n < kept ? separated[n].key : apart_keys[n - kept]; };
  for_blocks(
      kept + apart_keys.size(), kPairBlock, [&](std::size_t begin, std::size_t end, std::size_t) {
        std::vector<Impact>& found = st.impacts[thread_slot()];
        for (std::size_t n = begin; n < end; ++n) {
          const uint64_t key = key_at(n);
          const uint32_t a = pair_first(key), b = pair_second(key);
          const uint32_t pa = st.packet_of[a], pb = st.packet_of[b];
          const bool fast_a = fast[pa] != 0, fast_b = fast[pb] != 0;  // packet 0 is never fast
          // Two fast bodies are left to their contacts: moving both back would need a joint time.
          if (fast_a == fast_b) continue;
          const uint32_t mover = fast_a ? a : b, other = fast_a ? b : a;
          const uint32_t other_packet = fast_a ? pb : pa;
          const Shape& ms = shapes[bodies.shape[mover]];
          const Shape& os = shapes[bodies.shape[other]];
          // A half-space cannot be passed through: its contact exists wherever the body ends.
          if (os.type == ShapeType::Plane) continue;
          const SolverBody& mp = st.packets[st.packet_of[mover]];
          // perf: most pairs of a fast body are near misses of its grown bounding box, which the
          // positions alone show: the end orientations (a product and a normalisation each) are
          // made only for the rest. The end positions are end_pose's.
          const Vec3 o_start = bodies.position(other), m_start = bodies.position(mover);
          const Vec3 o_end =
              other_packet != 0 ? Vec3(o_start + st.packets[other_packet].dp) : o_start;
          const Vec3 m_end = m_start + mp.dp;
          if (!spheres_meet(o_start - m_start, (o_end - o_start) - (m_end - m_start),
                            ms.bounding_radius + os.bounding_radius, kContinuousTarget)) {
            continue;
          }
          const Transform o0 = start_pose(bodies, other);
          const Transform o1 =
              other_packet != 0 ? end_pose(bodies, other, st.packets[other_packet]) : o0;
          const Transform m0 = start_pose(bodies, mover);
          const Transform m1 = end_pose(bodies, mover, mp);
          const Real t = time_of_impact(ms, m0, m1, os, o0, o1, kContinuousTarget);
          // t = 0: already touching at the start, which the contact solver has in hand.
          if (t > 0 && t < 1) found.push_back({fast_a ? pa : pb, t});
        }
      });

  // determinism: the minimum is exact and does not depend on the order, so neither which thread
  // found an impact nor the order of the lists matters.
  std::vector<Real>& earliest = st.earliest_toi;
  earliest.assign(count, 1);
  for (const std::vector<Impact>& list : st.impacts) {
    for (const Impact& hit : list) earliest[hit.packet] = std::min(earliest[hit.packet], hit.t);
  }
  // The static bodies along the path each fast body took (continuous.hpp), fast body by fast
  // body in packet order; a static body that was a pair of it this step (in one of the three
  // key-sorted lists) was handled above or in the solve.
  auto was_pair = [&](uint64_t key) {
    const auto head =
        std::lower_bound(touching.begin(), touching.end(), key,
                         [](const ManifoldHead& m, uint64_t k) { return m.key() < k; });
    if (head != touching.end() && head->key() == key) return true;
    const auto sep = std::lower_bound(separated.begin(), separated.end(), key,
                                      [](const SeparatedPair& p, uint64_t k) { return p.key < k; });
    if (sep != separated.end() && sep->key == key) return true;
    return std::binary_search(apart_keys.begin(), apart_keys.end(), key);
  };
  // perf: a scene has few static bodies and many dynamic ones, all in the query tree; walking
  // the tree for each fast body's path visits the dynamic leaves around it to find the few
  // static ones. With at most kFewStatics static bodies in the tree, their leaves are tested
  // directly: the same leaves (those whose box meets the path), so the same impacts, and the
  // minimum does not depend on the order anyway.
  std::array<uint32_t, kFewStatics> few_statics;
  std::size_t static_count = 0;
  bool few = true;
  for (uint32_t i = 0; i < uint32_t(bodies.size()) && few; ++i) {
    if (!bodies.is_static(i) || i >= statics.item_count() || !statics.contains(i)) continue;
    if (static_count == kFewStatics) {
      few = false;
    } else {
      few_statics[static_count++] = i;
    }
  }
  const auto for_each_static = [&](const TreeBox& path, const auto& f) {
    if (!few) {
      statics.query(path, [&](uint32_t other) {
        if (bodies.is_static(other)) f(other);
        return true;
      });
      return;
    }
    for (std::size_t n = 0; n < static_count; ++n) {
      if (statics.fat_box(few_statics[n]).overlaps(path)) f(few_statics[n]);
    }
  };
  for (std::size_t k = 1; k < count; ++k) {
    if (!fast[k]) continue;
    const uint32_t mover = st.masses[k].body;
    const Vec3 off_path = st.packets[k].dp - bodies.linear_velocity(mover) * dt;
    if (off_path.cwiseAbs().maxCoeff() <= kPathSlack) continue;
    const Shape& ms = shapes[bodies.shape[mover]];
    const Transform m0 = start_pose(bodies, mover);
    const Transform m1 = end_pose(bodies, mover, st.packets[k]);
    Vec3 lo0, hi0, lo1, hi1;
    shape_bounds(ms, m0.position, m0.rotation, lo0, hi0);
    shape_bounds(ms, m1.position, m1.rotation, lo1, hi1);
    const Vec3 grow = Vec3::Constant(kContinuousTarget);
    const TreeBox path{lo0.cwiseMin(lo1) - grow, hi0.cwiseMax(hi1) + grow};
    for_each_static(path, [&](uint32_t other) {
      if (other == mover) return;
      const Shape& os = shapes[bodies.shape[other]];
      if (os.type == ShapeType::Plane || was_pair(make_pair_key(mover, other))) return;
      const Transform o0 = start_pose(bodies, other);
      const Real t = time_of_impact(ms, m0, m1, os, o0, o0, kContinuousTarget);
      if (t > 0 && t < 1) earliest[k] = std::min(earliest[k], t);
    });
  }

  std::size_t moved = 0;
  for (std::size_t k = 1; k < count; ++k) {
    const Real t = earliest[k];
    if (t >= 1) continue;
    SolverBody& p = st.packets[k];
    const Quat q0 = bodies.orientation(st.masses[k].body);
    const Quat q1 = (p.dq * q0).normalized();
    // The pose time_of_impact tested: position along the line, rotation slerped.
    p.dp *= t;
    p.dq = (fixed_slerp(q0, t, q1) * q0.conjugate()).normalized();
    ++moved;
  }
  return moved;
}

}  // namespace elan::detail
