// Stage 3, collide_pairs(): manifolds for every broadphase pair in parallel over fixed blocks,
// warm-start impulses matched by key and feature id, touching manifolds compacted in key order.
#include <algorithm>

#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"
#include "narrowphase/collide.hpp"

namespace elan::detail {

namespace {

// perf: a block of pairs is one task; big enough to amortise scheduling, small enough to balance
// pairs of very different cost (box-box next to hull-hull).
constexpr std::size_t kPairGrain = 64;

// Copies impulses from the previous step's manifold with the same key into `m`, point by point
// where the feature ids agree. A point whose id has no match takes the impulses of the previous
// point nearest to it within kMatchDistance: when two faces tie for reference (a box resting
// level on a large ground) the clipper may swap reference and incident face from one step to
// the next, which renames the same physical points; matching them by position keeps the warm
// start (Jolt's contact cache matches by position alone). A manifold whose A/B order flipped (a
// motion type changed) or whose normal turned gets no warm start.
constexpr Real kMatchDistance = Real(0.02);  // m
constexpr Real kMatchNormalCos = Real(0.95);

void warm_start(const Manifold& old, Manifold& m) {
  if (old.body_a != m.body_a || old.normal.dot(m.normal) < kMatchNormalCos) return;
  m.tangent_impulse[0] = old.tangent_impulse[0];
  m.tangent_impulse[1] = old.tangent_impulse[1];
  m.twist_impulse = old.twist_impulse;
  for (int i = 0; i < m.point_count; ++i) {
    ContactPoint& p = m.points[i];
    int match = -1;
    Real best = kMatchDistance * kMatchDistance;
    for (int j = 0; j < old.point_count; ++j) {
      if (old.points[j].feature_id == p.feature_id) {
        match = j;
        break;
      }
      const Real d2 = (old.points[j].anchor_a - p.anchor_a).squaredNorm();
      if (d2 < best) {
        best = d2;
        match = j;
      }
    }
    if (match < 0) continue;
    p.normal_impulse = old.points[match].normal_impulse;
  }
}

}  // namespace

void collide_pairs(std::span<const uint64_t> pairs, const BodyStore& bodies,
                   std::span<const Shape> shapes, const CollideSettings& settings,
                   std::span<const Manifold> previous, std::vector<Manifold>& scratch_slots,
                   std::vector<Manifold>& out_contacts) {
  const std::size_t n = pairs.size();
  scratch_slots.resize(n);
  // determinism: slot i belongs to pair i, and each block's merge with `previous` starts at a
  // binary search on the block's first key, so nothing depends on which thread ran a block.
  for_blocks(n, kPairGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
    auto prev_it = std::lower_bound(previous.begin(), previous.end(), pairs[begin],
                                    [](const Manifold& m, uint64_t k) { return m.key < k; });
    for (std::size_t i = begin; i < end; ++i) {
      const uint64_t key = pairs[i];
      uint32_t a = pair_first(key), b = pair_second(key);
      // The static or kinematic body, if any, is B (architecture rule 4).
      if (!bodies.is_dynamic(a) && bodies.is_dynamic(b)) std::swap(a, b);
      Manifold& m = scratch_slots[i];
      m.key = key;
      m.body_a = a;
      m.body_b = b;
      m.point_count = 0;
      const Transform xa{bodies.position(a), bodies.orientation(a)};
      const Transform xb{bodies.position(b), bodies.orientation(b)};
      const Real approach =
          (bodies.linear_velocity(a) - bodies.linear_velocity(b)).norm() * settings.dt;
      collide(shapes[bodies.shape[a]], xa, shapes[bodies.shape[b]], xb,
              settings.speculative_distance + approach, m);
      for (int k = 0; k < m.point_count; ++k) {
        ContactPoint& p = m.points[k];
        p.normal_impulse = 0;
        p.max_normal_impulse = 0;
      }
      m.tangent_impulse[0] = m.tangent_impulse[1] = 0;
      m.twist_impulse = 0;
      while (prev_it != previous.end() && prev_it->key < key) ++prev_it;
      if (m.point_count > 0 && prev_it != previous.end() && prev_it->key == key) {
        warm_start(*prev_it, m);
      }
    }
  });
  // perf: compaction is one serial pass of copies; the slots are already in key order.
  out_contacts.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (scratch_slots[i].point_count > 0) out_contacts.push_back(scratch_slots[i]);
  }
}

}  // namespace elan::detail
