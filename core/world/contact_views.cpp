// SPDX-License-Identifier: MIT
// Contact access of the public API between steps: the contact store's manifolds as ContactViews,
// in pair-key order; the hit threshold.
#include <algorithm>
#include <cmath>

#include "core/world/events.hpp"
#include "core/world/recorder_hooks.hpp"
#include "core/world/world_access.hpp"
#include "elan/world.hpp"

namespace elan {

namespace {

// The view of one manifold. Points: A's centre of mass now plus the arm the step's solve used
// (an arm is world-aligned, so a body that turned since is off by the arm's turn: |w| dt |r|).
// Friction acts once per manifold at its centre (contact.hpp); each point is given the share of
// its magnitude that its normal impulse is of the manifold's. The store keeps the impulses each
// substep accumulates (the next step's warm start), so the step's are those times the substep
// count: exact for a steady load (a resting box: m g dt).
ContactView view_of(const detail::WorldState& s, const detail::Manifold& m) {
  const Real substeps = Real(s.def.substeps);
  ContactView v;
  v.body_a = detail::body_id_at(s, m.body_a);
  v.body_b = detail::body_id_at(s, m.body_b);
  v.normal = m.normal;
  v.point_count = int(m.point_count);
  const Vec3 centre_a = s.bodies.position(m.body_a);
  const Real tangent = substeps * std::hypot(m.tangent_impulse[0], m.tangent_impulse[1]);
  Real normal_sum = 0;
  for (uint32_t k = 0; k < m.point_count; ++k) normal_sum += m.points[k].normal_impulse;
  for (uint32_t k = 0; k < m.point_count; ++k) {
    const detail::ContactPoint& p = m.points[k];
    ContactPointView& out = v.points[k];
    out.point = centre_a + p.anchor_a;
    out.separation = p.separation;
    out.normal_impulse = substeps * p.normal_impulse;
    out.tangent_impulse =
        normal_sum > 0 ? tangent * (p.normal_impulse / normal_sum) : tangent / Real(m.point_count);
  }
  return v;
}

// The whole manifold of head k: its tail found by key (tails are sorted by key, a subset of the
// heads' keys).
detail::Manifold manifold_at(const detail::WorldState& s, std::size_t k) {
  const detail::ManifoldHead& h = s.contacts.heads()[k];
  const detail::ManifoldTail* tail = nullptr;
  if (h.point_count > 1) {
    const auto tails = s.contacts.tails();
    const auto it =
        std::lower_bound(tails.begin(), tails.end(), h.key(),
                         [](const detail::ManifoldTail& t, uint64_t key) { return t.key < key; });
    if (it != tails.end() && it->key == h.key()) tail = &*it;
  }
  return detail::whole(h, tail);
}

}  // namespace

std::size_t World::contact_count() const {
  return state_->contacts.size();
}

ContactView World::contact(std::size_t index) const {
  const detail::WorldState& s = *state_;
  detail::check_arg(index < s.contacts.size(), "index", "contact index out of range");
  return view_of(s, manifold_at(s, index));
}

void World::contacts_of(BodyId body, std::vector<ContactView>& out) const {
  const detail::WorldState& s = *state_;
  const uint32_t i = uint32_t(detail::index_of(s, body));
  out.clear();
  const auto heads = s.contacts.heads();
  const auto tails = s.contacts.tails();
  std::size_t cursor = 0;
  for (const detail::ManifoldHead& h : heads) {
    if (h.body_a != i && h.body_b != i) continue;
    out.push_back(view_of(s, detail::whole_at(h, tails, cursor)));
  }
}

void World::set_hit_event_threshold(Real speed) {
  ELAN_RECORDED(SetHitEventThreshold, set_hit_event_threshold(speed), speed);
  detail::check_arg(std::isfinite(speed) && speed >= 0, "speed", "must be finite and >= 0");
  state_->api.hit_threshold = speed;
}

std::span<const ContactHitEvent> World::contact_hit_events() const {
  return state_->api.hit_events;
}
std::span<const SensorBeginEvent> World::sensor_begin_events() const {
  return state_->api.sensor_begin_events;
}
std::span<const SensorEndEvent> World::sensor_end_events() const {
  return state_->api.sensor_end_events;
}

}  // namespace elan
