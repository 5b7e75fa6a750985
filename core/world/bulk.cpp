// SPDX-License-Identifier: MIT
// Bulk access of the public API: zero-copy column views, whole-column setters, event arrays,
// the pair filter, and stepping many worlds at once.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "core/base/range_checks.hpp"
#include "core/base/tbb_hand_off.hpp"
#include "core/world/events.hpp"
#include "core/world/recorder_hooks.hpp"
#include "core/world/step.hpp"
#include "core/world/thread_pool_access.hpp"
#include "core/world/world_access.hpp"
#include "elan/world.hpp"

namespace elan {

using detail::check_arg;
using detail::WorldState;

namespace {

template <class C>
std::span<const Real> view(const C& column) {
  return {column.data(), column.size()};
}

// Each element finite; a position within the supported coordinates (`length` false), a velocity
// within the supported speed (`length` true), both up to `max` in `unit`.
void check_columns(const WorldState& s, const char* field, std::span<const Real> x,
                   std::span<const Real> y, std::span<const Real> z, double max, bool length,
                   const char* unit) {
  const std::size_t n = s.bodies.size();
  check_arg(x.size() == n && y.size() == n && z.size() == n, field,
            "each span must have body_count() elements");
  for (std::size_t i = 0; i < n; ++i) {
    check_arg(std::isfinite(x[i]) && std::isfinite(y[i]) && std::isfinite(z[i]), field,
              "must be finite");
    const Vec3 v(x[i], y[i], z[i]);
    if (length) {
      detail::check_length(v, max, field, unit);
    } else {
      detail::check_coordinates(v, max, field, unit);
    }
  }
}

}  // namespace

World::BodyColumns World::body_columns() const {
  const detail::BodyStore& b = state_->bodies;
  return {view(b.px), view(b.py), view(b.pz), view(b.qw), view(b.qx), view(b.qy), view(b.qz),
          view(b.vx), view(b.vy), view(b.vz), view(b.wx), view(b.wy), view(b.wz)};
}

std::span<const BodyId> World::body_ids() const {
  WorldState& s = *state_;
  const std::size_t n = s.bodies.size();
  s.api.body_ids.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.api.body_ids[i] = detail::body_id_at(s, uint32_t(i));
  return s.api.body_ids;
}

void World::set_center_of_mass_positions(std::span<const Real> x, std::span<const Real> y,
                                         std::span<const Real> z) {
  ELAN_RECORDED(SetCenterOfMassPositions, set_center_of_mass_positions(x, y, z), x, y, z);
  WorldState& s = *state_;
  check_columns(s, "positions", x, y, z, limits::kMaxPosition, false, "m");
  detail::BodyStore& b = s.bodies;
  for (std::size_t i = 0; i < b.size(); ++i) {
    b.px[i] = x[i];
    b.py[i] = y[i];
    b.pz[i] = z[i];
    detail::wake_index(s, i);
  }
  detail::query_tree_refit_all(s);
}

void World::set_linear_velocities(std::span<const Real> x, std::span<const Real> y,
                                  std::span<const Real> z) {
  ELAN_RECORDED(SetLinearVelocities, set_linear_velocities(x, y, z), x, y, z);
  WorldState& s = *state_;
  check_columns(s, "linear_velocities", x, y, z, limits::kMaxLinearSpeed, true, "m/s");
  detail::BodyStore& b = s.bodies;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.is_static(i)) continue;
    b.vx[i] = x[i];
    b.vy[i] = y[i];
    b.vz[i] = z[i];
    detail::wake_index(s, i);
  }
}

void World::set_angular_velocities(std::span<const Real> x, std::span<const Real> y,
                                   std::span<const Real> z) {
  ELAN_RECORDED(SetAngularVelocities, set_angular_velocities(x, y, z), x, y, z);
  WorldState& s = *state_;
  check_columns(s, "angular_velocities", x, y, z, limits::kMaxAngularSpeed, true, "rad/s");
  detail::BodyStore& b = s.bodies;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.is_static(i)) continue;
    b.wx[i] = x[i];
    b.wy[i] = y[i];
    b.wz[i] = z[i];
    detail::wake_index(s, i);
  }
}

std::span<const ContactBeginEvent> World::contact_begin_events() const {
  return state_->api.begin_events;
}

std::span<const ContactEndEvent> World::contact_end_events() const {
  return state_->api.end_events;
}

void World::set_pair_filter(PairFilter filter) {
  state_->api.pair_filter = std::move(filter);
}

uint32_t step_all(std::span<World* const> worlds, Real dt, ThreadPool* pool) {
  if (!(std::isfinite(dt) && dt > 0)) {
    for (World* w : worlds) detail::state_of(*w).stats.status = kStepBadTimestep;
    return kStepBadTimestep;
  }
  std::vector<uint32_t> status(worlds.size(), 0);
  // determinism: worlds share nothing, and each world's step is thread-count independent, so
  // running them side by side in one pool gives each the bits it gets alone.
  detail::TbbHandOff hand_off;
  auto step_worlds = [&] {
    detail::TbbHandOff::TaskScope outer(hand_off);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, worlds.size(), 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        detail::TbbHandOff::TaskScope task(hand_off);
                        for (std::size_t k = r.begin(); k != r.end(); ++k) {
                          // perf: the worlds already fill the pool, so each solve runs on
                          // its caller alone instead of spinning up stage workers.
                          detail::WorldState& w = detail::state_of(*worlds[k]);
                          const int threads = w.threads;
                          w.threads = 1;
                          status[k] = detail::run_step(w, dt);
                          w.threads = threads;
                        }
                      });
  };
  hand_off.spawn(step_worlds);
  if (pool) {
    detail::arena_of(*pool).execute(step_worlds);
  } else {
    step_worlds();
  }
  hand_off.joined();
  for (World* w : worlds) {
    if (detail::state_of(*w).recorder) [[unlikely]]
      detail::record_step(*w, dt);
  }
  uint32_t all = 0;
  for (uint32_t f : status) all |= f;
  return all;
}

}  // namespace elan
