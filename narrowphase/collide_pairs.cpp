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

// Body pair cache (Jolt's): while B's pose relative to A stays within 1 mm and 2 degrees of the
// pose the points were computed at, the previous manifold is carried along with the bodies
// instead of running the exact test again. The tolerance is measured against the pose of the
// exact test, not the last reuse, so the error cannot accumulate.
constexpr Real kCacheDistance = Real(2e-4);            // m
constexpr Real kCacheCosHalfAngle = Real(0.99999048);  // cos(0.25 degree): 0.5 degree

bool reuse_manifold(const Manifold& old, const Transform& xa, const Transform& xb, Manifold& m) {
  const Vec3 relative = xa.rotation.conjugate() * (xb.position - xa.position);
  if ((relative - old.relative_position).squaredNorm() > kCacheDistance * kCacheDistance) {
    return false;
  }
  const Quat rel_now = xa.rotation.conjugate() * xb.rotation;
  const Quat rel_then = old.orientation_a.conjugate() * old.orientation_b;
  if (std::abs(rel_now.dot(rel_then)) < kCacheCosHalfAngle) return false;
  const Quat turn_a = xa.rotation * old.orientation_a.conjugate();  // since the exact test
  const Quat turn_b = xb.rotation * old.orientation_b.conjugate();
  const Vec3 normal_in_a = old.orientation_a.conjugate() * old.normal;
  m = old;  // key, bodies, impulses for the warm start, and the poses of the exact test
  m.normal = (xa.rotation * normal_in_a).normalized();
  for (int k = 0; k < m.point_count; ++k) {
    ContactPoint& p = m.points[k];
    const ContactPoint& q = old.points[k];
    p.anchor_a = turn_a * q.anchor_a;
    p.anchor_b = turn_b * q.anchor_b;
    // The two material points, seen from A: their gap along A's normal changed by as much as
    // their separation vector did.
    const Vec3 gap_then =
        old.relative_position + old.orientation_a.conjugate() * (q.anchor_b - q.anchor_a);
    const Vec3 gap_now = relative + xa.rotation.conjugate() * (p.anchor_b - p.anchor_a);
    p.separation = q.separation + normal_in_a.dot(gap_now - gap_then);
    p.max_normal_impulse = 0;
  }
  return true;
}

}  // namespace

void collide_pairs(std::span<const uint64_t> pairs, const BodyStore& bodies,
                   std::span<const Shape> shapes, const CollideSettings& settings,
                   std::span<const Manifold> previous, CollideScratch& scratch,
                   std::vector<Manifold>& out_contacts) {
  const std::size_t n = pairs.size();
  if (scratch.size() < block_count(n, kPairGrain)) scratch.resize(block_count(n, kPairGrain));
  // determinism: block b owns scratch[b] and writes its pairs' manifolds there in pair order;
  // its merge with `previous` starts at a binary search on the block's first key, so nothing
  // depends on which thread ran a block (rule 1: joined in block order below).
  for_blocks(n, kPairGrain, [&](std::size_t begin, std::size_t end, std::size_t block) {
    std::vector<Manifold>& touching = scratch[block];
    touching.clear();
    Manifold m;
    auto prev_it = std::lower_bound(previous.begin(), previous.end(), pairs[begin],
                                    [](const Manifold& x, uint64_t k) { return x.key < k; });
    for (std::size_t i = begin; i < end; ++i) {
      const uint64_t key = pairs[i];
      uint32_t a = pair_first(key), b = pair_second(key);
      // The static or kinematic body, if any, is B (architecture rule 4).
      if (!bodies.is_dynamic(a) && bodies.is_dynamic(b)) std::swap(a, b);
      m.key = key;
      m.body_a = a;
      m.body_b = b;
      m.point_count = 0;
      const Transform xa{bodies.position(a), bodies.orientation(a)};
      const Transform xb{bodies.position(b), bodies.orientation(b)};
      while (prev_it != previous.end() && prev_it->key < key) ++prev_it;
      const Manifold* old =
          (prev_it != previous.end() && prev_it->key == key && prev_it->body_a == a) ? &*prev_it
                                                                                     : nullptr;
      if (old != nullptr && old->point_count > 0 && reuse_manifold(*old, xa, xb, m)) {
        touching.push_back(m);
        continue;
      }
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
      m.orientation_a = xa.rotation;
      m.orientation_b = xb.rotation;
      m.relative_position = xa.rotation.conjugate() * (xb.position - xa.position);
      if (m.point_count > 0 && old != nullptr) warm_start(*old, m);
      if (m.point_count > 0) touching.push_back(m);
    }
  });
  // perf: one serial pass of copies; blocks are already in key order.
  out_contacts.clear();
  for (std::size_t b = 0; b < block_count(n, kPairGrain); ++b) {
    out_contacts.insert(out_contacts.end(), scratch[b].begin(), scratch[b].end());
  }
}

}  // namespace elan::detail
