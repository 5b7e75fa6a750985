// SPDX-License-Identifier: MIT
// Contact begin/end events from the collide stage's changes to the contact list, and the pair
// filter.
#include "core/world/events.hpp"

#include <algorithm>
#include <cassert>

#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"

namespace elan::detail {

namespace {
constexpr std::size_t kFilterGrain = 1024;

// `start`: the bodies at the step's start, whose poses the manifold's points were computed at.
ContactBeginEvent begin_event(const WorldState& w, const BodyStore& start, const Manifold& m) {
  assert(m.point_count > 0);
  ContactBeginEvent e;
  e.body_a = body_id_at(w, m.body_a);
  e.body_b = body_id_at(w, m.body_b);
  e.normal = m.normal;
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < m.point_count; ++k) {
    sum += m.points[k].anchor_a;
    e.normal_impulse += m.points[k].normal_impulse;
  }
  e.point = start.position(m.body_a) + sum / Real(m.point_count);
  return e;
}
// A contact that began is a hit when its approach speed, the relative normal velocity at its
// deepest point at the step's start (before the solve), -dot(v_b(p) - v_a(p), n) with
// v(p) = v + w x (p - c), reaches the threshold (Box2D's b2ContactHitEvent). `start` holds the
// step's start poses and velocities, at which the points were made.
void add_hit_event(WorldState& w, const BodyStore& start, const Manifold& m) {
  int deepest = 0;
  for (int k = 1; k < int(m.point_count); ++k) {
    if (m.points[k].separation < m.points[deepest].separation) deepest = k;
  }
  const Vec3 centre_a = start.position(m.body_a);
  const Vec3 point = centre_a + m.points[deepest].anchor_a;
  const Vec3 va =
      start.linear_velocity(m.body_a) + start.angular_velocity(m.body_a).cross(point - centre_a);
  const Vec3 vb = start.linear_velocity(m.body_b) +
                  start.angular_velocity(m.body_b).cross(point - start.position(m.body_b));
  const Real approach = -(vb - va).dot(m.normal);
  if (!(approach >= w.api.hit_threshold) || !(approach > 0)) return;
  w.api.hit_events.push_back(
      {body_id_at(w, m.body_a), body_id_at(w, m.body_b), point, m.normal, approach});
}

}  // namespace

void filter_pairs(WorldState& w) {
  const PairFilter& filter = w.api.pair_filter;
  if (!filter) return;
  const std::size_t n = w.pairs.size();
  w.api.pair_keep.resize(n);
  // determinism: one flag per pair, then a serial compaction in pair order (rule 1).
  // threading: the caller's filter runs on worker threads (documented on PairFilter).
  for_blocks(n, kFilterGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t k = begin; k < end; ++k) {
      const uint64_t key = w.pairs[k];
      w.api.pair_keep[k] =
          filter(body_id_at(w, pair_first(key)), body_id_at(w, pair_second(key))) ? 1 : 0;
    }
  });
  std::size_t kept = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (w.api.pair_keep[k]) w.pairs[kept++] = w.pairs[k];
  }
  w.pairs.resize(kept);
}

void compute_contact_events(WorldState& w, const BodyStore& start) {
  std::vector<ContactBeginEvent>& begins = w.api.begin_events;
  std::vector<ContactEndEvent>& ends = w.api.end_events;
  begins.clear();
  ends.clear();
  w.api.hit_events.clear();
  // determinism: both lists are in pair-key order, so the events are too (rule 4). perf: each
  // began key is looked up, not merged along the whole list: a settled pile of thousands of
  // manifolds begins and ends a few dozen a step.
  const std::span<const ManifoldHead> contacts = w.contacts.heads();
  const std::span<const ManifoldTail> tails = w.contacts.tails();
  auto next = contacts.begin();
  auto next_tail = tails.begin();
  for (const uint64_t key : w.contacts.began()) {
    next = std::lower_bound(next, contacts.end(), key,
                            [](const ManifoldHead& m, uint64_t k) { return m.key() < k; });
    assert(next != contacts.end() && next->key() == key && "a began key is in the list");
    const ManifoldTail* tail = nullptr;
    if (next->point_count > 1) {
      next_tail = std::lower_bound(next_tail, tails.end(), key,
                                   [](const ManifoldTail& t, uint64_t k) { return t.key < k; });
      assert(next_tail != tails.end() && next_tail->key == key && "its tail is in the list");
      tail = &*next_tail;
    }
    const Manifold m = whole(*next, tail);
    begins.push_back(begin_event(w, start, m));
    add_hit_event(w, start, m);
  }
  for (const ContactRecord& r : w.contacts.ended()) {
    ends.push_back({body_id_at(w, r.body_a), body_id_at(w, r.body_b)});
  }
  trim_spike(begins, w.api.begin_trim);
  trim_spike(ends, w.api.end_trim);
}

}  // namespace elan::detail
