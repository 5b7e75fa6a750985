// Stage 3, collide_pairs(): manifolds for every broadphase pair in parallel over fixed blocks,
// warm-start impulses matched by key and feature id, touching manifolds compacted in key order.
#include <tbb/task_arena.h>

#include <algorithm>
#include <span>

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
  carry_tangent_impulse(old.normal, old.tangent_impulse, m.normal, m.tangent_impulse);
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

// Body pair cache (Jolt's): while B's pose relative to A stays within 0.2 mm and 0.5 degrees of
// the pose of the last exact test, the manifold is carried along with the bodies instead of
// running the exact test again. Each step carries it from the poses of the step before; the
// tolerance is measured against the exact test, so a string of reuses cannot drift from it.
constexpr Real kCacheDistance = Real(2e-4);            // m
constexpr Real kCacheCosHalfAngle = Real(0.99999048);  // cos(0.25 degree): 0.5 degree

// A round body's contact point does not travel with its material as it turns (a rolling
// sphere touches the ground under its centre). Carried with the body, a cached point would
// drift off the line of centres by r * angle, and the normal force there would turn the sphere
// further the way it already turned (torque lambda r sin(angle)): a pump that kept spheres and
// capsules in a deep pile rocking. Their exact tests are the cheap closed forms anyway.
bool rolls(const Shape& s) {
  return s.type == ShapeType::Sphere || s.type == ShapeType::Capsule ||
         s.type == ShapeType::Cylinder;
}

bool reuse_manifold(const Manifold& old, const Transform& xa, const Transform& xb, Manifold& m) {
  const Vec3 relative = xa.rotation.conjugate() * (xb.position - xa.position);
  if ((relative - old.exact_position).squaredNorm() > kCacheDistance * kCacheDistance) {
    return false;
  }
  const Quat rel_now = xa.rotation.conjugate() * xb.rotation;
  if (std::abs(rel_now.dot(old.exact_rotation)) < kCacheCosHalfAngle) return false;
  const Quat turn_a = xa.rotation * old.orientation_a.conjugate();  // since the last update
  const Quat turn_b = xb.rotation * old.orientation_b.conjugate();
  const Vec3 normal_in_a = old.orientation_a.conjugate() * old.normal;
  const Vec3 centres = xb.position - xa.position;
  m = old;  // key, bodies, impulses for the warm start, the exact test's pose
  m.normal = (xa.rotation * normal_in_a).normalized();
  carry_tangent_impulse(old.normal, old.tangent_impulse, m.normal, m.tangent_impulse);
  for (int k = 0; k < m.point_count; ++k) {
    ContactPoint& p = m.points[k];
    const ContactPoint& q = old.points[k];
    const Vec3 on_a = turn_a * q.anchor_a;  // the material points, from each centre now
    const Vec3 on_b = turn_b * q.anchor_b;
    // Seen from A, the two material points' gap along A's normal changed by as much as their
    // separation vector did.
    const Vec3 gap_then =
        old.relative_position + old.orientation_a.conjugate() * (q.anchor_b - q.anchor_a);
    const Vec3 gap_now = relative + xa.rotation.conjugate() * (on_b - on_a);
    p.separation = q.separation + normal_in_a.dot(gap_now - gap_then);
    // Both arms reach one world point, midway between the material points: once the bodies
    // have slid or turned they part (a 1 m cube turned 0.5 degree moves its corner 4 mm), and
    // the two halves of an impulse acting at different points would form a couple.
    p.anchor_a = Real(0.5) * (on_a + centres + on_b);
    p.anchor_b = p.anchor_a - centres;
    p.max_normal_impulse = 0;
  }
  m.orientation_a = xa.rotation;
  m.orientation_b = xb.rotation;
  m.relative_position = relative;
  return true;
}

// The join's move of one part: its live manifolds, merged in key order with its added ones, to
// their place from `at`. Through `bounce`, since the part's old and new places may overlap.
void place_part(std::vector<Manifold>& contacts, std::size_t from, std::size_t to,
                std::span<const Manifold> added, std::vector<Manifold>& bounce, std::size_t at) {
  bounce.clear();
  auto next_added = added.begin();
  for (std::size_t i = from; i < to; ++i) {
    if (contacts[i].point_count == 0) continue;
    for (; next_added != added.end() && next_added->key < contacts[i].key; ++next_added) {
      bounce.push_back(*next_added);
    }
    bounce.push_back(contacts[i]);
  }
  bounce.insert(bounce.end(), next_added, added.end());
  std::copy(bounce.begin(), bounce.end(), contacts.begin() + std::ptrdiff_t(at));
}

}  // namespace

void collide_pairs(std::span<const uint64_t> pairs, const BodyStore& bodies,
                   std::span<const Shape> shapes, const CollideSettings& settings,
                   std::span<const uint8_t> idle, CollideScratch& scratch,
                   std::vector<Manifold>& contacts) {
  const std::size_t n = pairs.size();
  // With no pairs there is one (empty) part, to carry what the list holds.
  const std::size_t parts = std::max<std::size_t>(block_count(n, kPairGrain), 1);
  // One buffer of new keys per thread of the arena, not per block: a block's new manifolds are
  // one run in its thread's buffer, so only a step's new keys are held, not each block's most.
  const std::size_t threads = std::size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  if (scratch.added.size() < threads) scratch.added.resize(threads);
  for (std::vector<Manifold>& buffer : scratch.added) buffer.clear();
  scratch.added_run.resize(parts);
  scratch.start.resize(parts + 1);
  scratch.live.resize(parts);
  // Part p owns the keys from its first pair's up to the next part's first pair's (the first
  // part from 0, the last to the end). Its range of the list is found before any part writes.
  scratch.start[0] = 0;
  scratch.start[parts] = contacts.size();
  for (std::size_t part = 1; part < parts; ++part) {
    scratch.start[part] =
        std::size_t(std::lower_bound(contacts.begin(), contacts.end(), pairs[part * kPairGrain],
                                     [](const Manifold& x, uint64_t k) { return x.key < k; }) -
                    contacts.begin());
  }
  auto carried = [&](const Manifold& m) {
    return !idle.empty() && m.point_count > 0 && idle[m.body_a] && idle[m.body_b];
  };
  // determinism: part p writes only its range of the list and one run of its thread's buffer. A
  // manifold whose key is in the list is updated where it is; a key new to the list goes to the
  // run (which thread's buffer holds it changes nothing: the join reads runs in part order); one
  // that neither touches nor is carried is marked dead (point_count 0, which no live manifold has).
  // Nothing depends on which thread ran a part.
  for_blocks(parts, 1, [&](std::size_t part, std::size_t, std::size_t) {
    // Outside any arena (a serial call from a thread TBB has not seen) the index is negative.
    const int thread = tbb::this_task_arena::current_thread_index();
    const std::size_t slot = thread < 0 ? 0 : std::size_t(thread);
    std::vector<Manifold>& added = scratch.added[slot];
    const std::size_t first_added = added.size();
    const std::size_t begin = std::min(n, part * kPairGrain);
    const std::size_t end = std::min(n, begin + kPairGrain);
    Manifold* prev_it = contacts.data() + scratch.start[part];
    Manifold* const prev_end = contacts.data() + scratch.start[part + 1];
    std::size_t dead = 0;
    PolyhedronCache polyhedron_cache;
    auto keep_if_carried = [&](Manifold& old) {
      if (!carried(old)) {
        old.point_count = 0;
        ++dead;
      }
    };
    Manifold m;
    for (std::size_t i = begin; i < end; ++i) {
      const uint64_t key = pairs[i];
      for (; prev_it != prev_end && prev_it->key < key; ++prev_it) keep_if_carried(*prev_it);
      uint32_t a = pair_first(key), b = pair_second(key);
      // The static or kinematic body, if any, is B (architecture rule 4).
      if (!bodies.is_dynamic(a) && bodies.is_dynamic(b)) std::swap(a, b);
      m.key = key;
      m.body_a = a;
      m.body_b = b;
      m.point_count = 0;
      const Transform xa{bodies.position(a), bodies.orientation(a)};
      const Transform xb{bodies.position(b), bodies.orientation(b)};
      Manifold* same_key = (prev_it != prev_end && prev_it->key == key) ? prev_it++ : nullptr;
      const Manifold* old = (same_key != nullptr && same_key->body_a == a) ? same_key : nullptr;
      const bool cacheable = !rolls(shapes[bodies.shape[a]]) && !rolls(shapes[bodies.shape[b]]);
      if (old != nullptr && old->point_count > 0 && cacheable && reuse_manifold(*old, xa, xb, m)) {
        *same_key = m;
        continue;
      }
      const Real approach =
          (bodies.linear_velocity(a) - bodies.linear_velocity(b)).norm() * settings.dt;
      collide(shapes[bodies.shape[a]], xa, shapes[bodies.shape[b]], xb,
              settings.speculative_distance + approach, m, polyhedron_cache);
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
      m.exact_rotation = xa.rotation.conjugate() * xb.rotation;
      m.exact_position = m.relative_position;
      if (m.point_count > 0 && old != nullptr) warm_start(*old, m);
      if (same_key == nullptr) {
        if (m.point_count > 0) added.push_back(m);
      } else if (m.point_count > 0) {
        *same_key = m;
      } else {
        keep_if_carried(*same_key);
      }
    }
    for (; prev_it != prev_end; ++prev_it) keep_if_carried(*prev_it);
    scratch.live[part] = scratch.start[part + 1] - scratch.start[part] - dead;
    scratch.added_run[part] = {uint32_t(slot), first_added, added.size() - first_added};
  });

  // The join, serial: each part's live and added manifolds move to their final place, a prefix
  // sum of the parts' counts, in one pass over the list with no second copy of it. Part p moves
  // from [start[p], start[p+1]) to [at[p], at[p+1]); it can overwrite its left neighbour's old
  // range only if it moves left (at[p] < start[p]), and its right neighbour's only if that one
  // moves right (at[p+1] > start[p+1]), so each boundary says which side goes first, and the
  // order is a chain: parts waiting for their right neighbour are stacked until it has moved.
  std::vector<std::size_t>& at = scratch.at;
  at.resize(parts + 1);
  at[0] = 0;
  for (std::size_t p = 0; p < parts; ++p)
    at[p + 1] = at[p] + scratch.live[p] + scratch.added_run[p].count;
  const std::size_t total = at[parts];
  // Doubling, as std::vector grows: each growth holds the old list and the new at once, and the
  // freed lists leave the allocator's heap in pieces, so fewer growths mean a lower peak. On
  // pile10k, growing by a quarter gave 52.8 MB of peak RSS against 43.2 MB for doubling.
  if (total > contacts.capacity()) contacts.reserve(2 * total);
  if (total > contacts.size()) contacts.resize(total);
  auto place = [&](std::size_t p) {
    const std::size_t from = scratch.start[p], to = scratch.start[p + 1];
    const CollideScratch::Run& run = scratch.added_run[p];
    if (at[p] == from && scratch.live[p] == to - from && run.count == 0) return;
    const std::span<const Manifold> added(scratch.added[run.thread].data() + run.first, run.count);
    place_part(contacts, from, to, added, scratch.bounce, at[p]);
  };
  std::vector<std::size_t>& waiting = scratch.waiting;
  waiting.clear();
  for (std::size_t p = 0; p < parts; ++p) {
    waiting.push_back(p);
    if (p + 1 < parts && at[p + 1] > scratch.start[p + 1]) continue;
    for (; !waiting.empty(); waiting.pop_back()) place(waiting.back());
  }
  contacts.resize(total);
}

}  // namespace elan::detail
