// SPDX-License-Identifier: MIT
// The public World API: ids, validation of definitions, getters and setters, and step.
#include "elan/world.hpp"

#include <tbb/info.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/base/id_slots.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/range_checks.hpp"
#include "core/base/state_hash.hpp"
#include "core/base/tbb_hand_off.hpp"
#include "core/world/events.hpp"
#include "core/world/joints.hpp"
#include "core/world/recorder_hooks.hpp"
#include "core/world/sensors.hpp"
#include "core/world/step.hpp"
#include "core/world/thread_pool_access.hpp"
#include "core/world/world_access.hpp"
#include "core/world/world_state.hpp"

namespace elan {

using detail::WorldState;

using detail::check_arg;
using detail::check_coordinates;
using detail::check_length;
using detail::check_range;
using detail::index_of;

namespace {

// "must be in LO..HI", the wording every range check of the settings uses.
std::string in_range(int lo, int hi) {
  return "must be in " + std::to_string(lo) + ".." + std::to_string(hi);
}

bool finite(const Vec3& v) {
  return v.allFinite();
}

void validate(const WorldDef& def) {
  check_arg(finite(def.gravity), "gravity", "must be finite");
  check_length(def.gravity, limits::kMaxGravity, "gravity", "m/s^2");
  check_arg(def.substeps >= 1 && def.substeps <= kMaxSubsteps, "substeps",
            in_range(1, kMaxSubsteps));
  check_arg(def.iterations >= 1 && def.iterations <= kMaxIterations, "iterations",
            in_range(1, kMaxIterations));
  check_arg(def.threads >= 0 && def.threads <= kMaxThreads, "threads", in_range(0, kMaxThreads));
}

int resolve_threads(int threads) {
  return threads > 0 ? threads : std::max(1, tbb::info::default_concurrency());
}

}  // namespace

World::World(const WorldDef& def) : state_(std::make_unique<WorldState>()) {
  validate(def);
  state_->def = def;
  state_->kernels = &detail::select_solver_kernels(def.simd);
  if (def.thread_pool) {
    state_->threads = def.thread_pool->threads();
  } else {
    state_->threads = resolve_threads(def.threads);
    state_->arena = std::make_unique<tbb::task_arena>(state_->threads);
  }
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

void World::reserve(std::size_t bodies, std::size_t shapes) {
  // Shape indices are 32-bit, UINT32_MAX marking "none"; dense body indices fit in a manifold's
  // 29 bits.
  constexpr std::size_t kMax = std::size_t(UINT32_MAX) - 1;
  check_arg(bodies <= detail::kMaxBodyCount, "bodies", "more than 2^29");
  check_arg(shapes <= kMax, "shapes", "more than 2^32 - 2");
  WorldState& s = *state_;
  s.bodies.reserve(bodies);
  s.slot_index.reserve(bodies);
  s.slot_generation.reserve(bodies);
  s.shapes.reserve(shapes);
}

ShapeId World::create_shape(const ShapeDef& def) {
  ELAN_RECORDED(CreateShape, create_shape(def), def);
  WorldState& s = *state_;
  s.shapes.push_back(detail::make_shape(def));
  s.api.shape_user_data.resize(s.shapes.size() - 1);
  s.api.shape_user_data.push_back(def.user_data);
  return ShapeId{uint32_t(state_->shapes.size() - 1)};
}

void World::destroy_shape(ShapeId id) {
  ELAN_RECORDED(DestroyShape, destroy_shape(id), id);
  WorldState& s = *state_;
  check_arg(detail::shape_live(s, id), "shape", "invalid or destroyed shape id");
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    check_arg(s.bodies.shape[i] != id.index, "shape", "still used by a body");
  }
  // Indices are not reused (ShapeId has no generation), so a stale id can never alias.
  s.api.shape_destroyed.resize(s.shapes.size(), 0);
  s.api.shape_destroyed[id.index] = 1;
  s.shapes[id.index] = detail::Shape{};
  if (id.index < s.api.shape_defs.size()) s.api.shape_defs[id.index].reset();
}

bool World::is_valid(ShapeId id) const {
  return detail::shape_live(*state_, id);
}

BodyId World::create_body(const BodyDef& def) {
  ELAN_RECORDED(CreateBody, create_body(def), def);
  WorldState& s = *state_;
  check_arg(s.bodies.size() < detail::kMaxBodyCount, "body",
            "too many bodies: a world holds at most " + std::to_string(detail::kMaxBodyCount));
  check_arg(detail::shape_live(s, def.shape), "shape", "invalid or destroyed shape id");
  const detail::Shape& shape = s.shapes[def.shape.index];
  check_arg(finite(def.position), "position", "must be finite");
  check_coordinates(def.position, limits::kMaxPosition, "position", "m");
  check_arg(def.orientation.coeffs().allFinite(), "orientation", "must be finite");
  check_arg(def.orientation.norm() > Real(1e-12), "orientation", "zero quaternion");
  check_arg(finite(def.linear_velocity), "linear_velocity", "must be finite");
  check_length(def.linear_velocity, limits::kMaxLinearSpeed, "linear_velocity", "m/s");
  check_arg(finite(def.angular_velocity), "angular_velocity", "must be finite");
  check_length(def.angular_velocity, limits::kMaxAngularSpeed, "angular_velocity", "rad/s");
  check_arg(std::isfinite(def.friction) && def.friction >= 0, "friction",
            "must be finite and >= 0");
  check_arg(std::isfinite(def.restitution) && def.restitution >= 0, "restitution",
            "must be finite and >= 0");
  check_range(def.friction, 0, limits::kMaxFriction, "friction", "");
  check_range(def.restitution, 0, limits::kMaxRestitution, "restitution", "");
  check_arg(std::isfinite(def.linear_damping) && def.linear_damping >= 0, "linear_damping",
            "must be finite and >= 0");
  check_arg(std::isfinite(def.angular_damping) && def.angular_damping >= 0, "angular_damping",
            "must be finite and >= 0");
  check_arg(std::isfinite(def.gravity_scale), "gravity_scale", "must be finite");
  check_range(def.gravity_scale, -limits::kMaxGravityScale, limits::kMaxGravityScale,
              "gravity_scale", "");
  if (def.mass) {
    check_arg(std::isfinite(*def.mass) && *def.mass > 0, "mass", "must be finite and positive");
    check_range(*def.mass, limits::kMinMass, limits::kMaxMass, "mass", "kg");
  }
  check_arg(std::isfinite(def.density) && def.density > 0, "density",
            "must be finite and positive");
  check_range(def.density, limits::kMinDensity, limits::kMaxDensity, "density", "kg/m^3");
  if (shape.type == ShapeType::Plane) {
    check_arg(def.motion == MotionType::Static, "motion", "a plane must be static");
  }
  if (shape.type == ShapeType::Mesh) {
    check_arg(def.motion == MotionType::Static, "motion", "a mesh must be static");
  }
  if (shape.type == ShapeType::Heightfield) {
    check_arg(def.motion == MotionType::Static, "motion", "a heightfield must be static");
  }

  // Mass properties, checked before anything is stored.
  Real inv_mass = 0;
  Vec3 inv_inertia = Vec3::Zero();
  if (def.motion == MotionType::Dynamic) {
    const Real mass = def.mass ? *def.mass : detail::checked_mass(def.density, shape.volume);
    inv_mass = 1 / mass;
    inv_inertia = detail::inverse_inertia(mass, shape.unit_inertia);
  }

  const Quat q_user = def.orientation.normalized();
  const std::size_t i = s.bodies.push_back();
  detail::BodyStore& b = s.bodies;
  // The store keeps the principal frame: centre of mass and principal axes.
  b.set_position(i, def.position + q_user * shape.frame_position);
  b.set_orientation(i, (q_user * shape.frame_rotation).normalized());
  const bool moving = def.motion != MotionType::Static;
  b.set_linear_velocity(i, moving ? def.linear_velocity : Vec3::Zero());
  b.set_angular_velocity(i, moving ? def.angular_velocity : Vec3::Zero());
  if (def.motion == MotionType::Dynamic) {
    b.inv_mass[i] = inv_mass;
    b.inv_ix[i] = inv_inertia.x();
    b.inv_iy[i] = inv_inertia.y();
    b.inv_iz[i] = inv_inertia.z();
  }
  detail::BodyTraits traits;
  traits.friction = def.friction;
  traits.restitution = def.restitution;
  traits.linear_damping = def.linear_damping;
  traits.angular_damping = def.angular_damping;
  traits.gravity_scale = def.gravity_scale;
  traits.category = def.category_bits;
  traits.mask = def.mask_bits;
  traits.flags = def.sensor ? detail::kTraitSensor : 0;
  b.set_traits(i, traits);
  b.shape[i] = def.shape.index;
  b.motion[i] = uint8_t(def.motion);
  b.flags[i] =
      (def.motion == MotionType::Static || (def.motion == MotionType::Dynamic && !def.awake))
          ? 0
          : detail::kAwake;
  if (def.motion == MotionType::Dynamic) {
    b.flags[i] |= detail::kPlaced;
    s.bodies_placed = true;
  }

  const uint32_t slot =
      detail::take_slot(s.slot_index, s.slot_generation, s.free_slots, uint32_t(i));
  b.slot[i] = slot;
  detail::BodyExtra& extra = detail::body_extra(s, slot);
  extra.user_data = def.user_data;
  extra.density = def.density;
  extra.given_mass = def.mass ? *def.mass : 0;
  detail::query_tree_update(s, uint32_t(i));
  return BodyId{slot, s.slot_generation[slot]};
}

void World::destroy_body(BodyId id) {
  ELAN_RECORDED(DestroyBody, destroy_body(id), id);
  WorldState& s = *state_;
  const uint32_t i = uint32_t(index_of(s, id));
  const uint32_t last = uint32_t(s.bodies.size() - 1);
  // Joints: removed with the body (an event each), their other bodies woken.
  if (!s.joints.empty()) {
    detail::remove_joints_of(s, id.slot);
    // The last body's index changes: the pairs kept from colliding are keyed by index.
    ++s.joints.version;
  }
  // Contacts: drop the body's own (an end event for each touching one, partners woken); the
  // last body takes index i, so the store renames its manifolds.
  s.contacts.remove_body(i, last, [&](const detail::ManifoldHead& m) {
    if (m.point_count > 0) {
      s.api.end_events.push_back(
          {detail::body_id_at(s, m.body_a), detail::body_id_at(s, m.body_b)});
    }
    const uint32_t other = m.body_a == i ? m.body_b : m.body_a;
    if (s.bodies.is_dynamic(other)) detail::wake_index(s, other);
  });
  // Sensor overlaps: the body's end (an event each), the last body's are renamed.
  detail::sensor_remove_body(s, i, last);
  // The sweep-and-prune's kept order is a permutation of 0..n-1 re-sorted every update (a full
  // sort when the count changes), and its output is canonical, so it needs no fix-up.
  detail::query_tree_remove(s, i);
  s.bodies.swap_remove(i);
  if (i != last) s.slot_index[s.bodies.slot[i]] = i;
  detail::release_slot(s.slot_index, s.slot_generation, s.free_slots, id.slot);
}

uint32_t World::step(Real dt) {
  WorldState& s = *state_;
  if (!(dt >= Real(limits::kMinTimestep) && dt <= Real(limits::kMaxTimestep))) {
    s.stats.status = kStepBadTimestep;
    return kStepBadTimestep;
  }
  uint32_t status = 0;
  tbb::task_arena& arena = s.def.thread_pool ? detail::arena_of(*s.def.thread_pool) : *s.arena;
  // threading: the arena runs the step on this thread when it has a free slot, else on a worker
  // while this thread waits; the hand-off tells TSan of the second case's ordering.
  detail::TbbHandOff hand_off;
  const auto step = [&] {
    detail::TbbHandOff::TaskScope task(hand_off);
    status = detail::run_step(s, dt);
  };
  hand_off.spawn(step);
  arena.execute(step);
  hand_off.joined();
  if (s.recorder) [[unlikely]]
    detail::record_step(*this, dt);
  return status;
}

bool World::is_valid(BodyId id) const {
  const WorldState& s = *state_;
  return detail::slot_live(s.slot_index, s.slot_generation, id.slot, id.generation);
}

std::size_t World::body_count() const {
  return state_->bodies.size();
}

BodyId World::body_at(std::size_t index) const {
  const WorldState& s = *state_;
  if (index >= s.bodies.size()) throw Error("index", "body index out of range");
  const uint32_t slot = s.bodies.slot[index];
  return BodyId{slot, s.slot_generation[slot]};
}

Vec3 World::position(BodyId id) const {
  const WorldState& s = *state_;
  const std::size_t i = index_of(s, id);
  const detail::Shape& shape = s.shapes[s.bodies.shape[i]];
  return s.bodies.position(i) - orientation(id) * shape.frame_position;
}

Quat World::orientation(BodyId id) const {
  const WorldState& s = *state_;
  const std::size_t i = index_of(s, id);
  const detail::Shape& shape = s.shapes[s.bodies.shape[i]];
  return (s.bodies.orientation(i) * shape.frame_rotation.conjugate()).normalized();
}

Vec3 World::linear_velocity(BodyId id) const {
  return state_->bodies.linear_velocity(index_of(*state_, id));
}
Vec3 World::angular_velocity(BodyId id) const {
  return state_->bodies.angular_velocity(index_of(*state_, id));
}
Vec3 World::center_of_mass(BodyId id) const {
  return state_->bodies.position(index_of(*state_, id));
}
Real World::mass(BodyId id) const {
  const Real inv = state_->bodies.inv_mass[index_of(*state_, id)];
  return inv > 0 ? 1 / inv : 0;
}
MotionType World::motion_type(BodyId id) const {
  return MotionType(state_->bodies.motion[index_of(*state_, id)]);
}
bool World::is_awake(BodyId id) const {
  const std::size_t i = index_of(*state_, id);
  return state_->bodies.is_dynamic(i) && state_->bodies.is_awake(i);
}

SimdPath World::simd_path() const {
  return state_->kernels->path;
}

const WorldDef& World::settings() const {
  return state_->def;
}

void World::set_substeps(int substeps) {
  ELAN_RECORDED(SetSubsteps, set_substeps(substeps), substeps);
  check_arg(substeps >= 1 && substeps <= kMaxSubsteps, "substeps", in_range(1, kMaxSubsteps));
  state_->def.substeps = substeps;
}
void World::set_iterations(int iterations) {
  ELAN_RECORDED(SetIterations, set_iterations(iterations), iterations);
  check_arg(iterations >= 1 && iterations <= kMaxIterations, "iterations",
            in_range(1, kMaxIterations));
  state_->def.iterations = iterations;
}
void World::set_sleep_enabled(bool enabled) {
  ELAN_RECORDED(SetSleepEnabled, set_sleep_enabled(enabled), enabled);
  WorldState& s = *state_;
  if (s.def.allow_sleep == enabled) return;
  s.def.allow_sleep = enabled;
  if (enabled) return;
  // Off: nothing may stay asleep, and no timer may carry time rested before (the step does not
  // advance the timers while sleep is off, so they restart from zero when it is back on).
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    if (s.bodies.is_dynamic(i)) detail::wake_index(s, i);
  }
}
bool World::sleep_enabled() const {
  return state_->def.allow_sleep;
}
void World::set_broadphase(BroadphaseType type) {
  state_->def.broadphase = type;
}
void World::set_threads(int threads) {
  check_arg(threads >= 0 && threads <= kMaxThreads, "threads", in_range(0, kMaxThreads));
  state_->def.threads = threads;
  state_->def.thread_pool = nullptr;
  state_->threads = resolve_threads(threads);
  state_->arena = std::make_unique<tbb::task_arena>(state_->threads);
}

const StepStats& World::last_step() const {
  return state_->stats;
}

uint64_t World::state_hash() const {
  return detail::hash_bodies(state_->bodies);
}

Real World::kinetic_energy() const {
  const detail::BodyStore& b = state_->bodies;
  double e = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (!b.is_dynamic(i) || b.inv_mass[i] == 0) continue;
    const Vec3 w_body = b.orientation(i).conjugate() * b.angular_velocity(i);
    const double rot = double(w_body.x()) * w_body.x() / b.inv_ix[i] +
                       double(w_body.y()) * w_body.y() / b.inv_iy[i] +
                       double(w_body.z()) * w_body.z() / b.inv_iz[i];
    e += 0.5 * double(b.linear_velocity(i).squaredNorm()) / b.inv_mass[i] + 0.5 * rot;
  }
  return Real(e);
}

Vec3 World::linear_momentum() const {
  const detail::BodyStore& b = state_->bodies;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (!b.is_dynamic(i)) continue;
    p += b.linear_velocity(i).cast<double>() / double(b.inv_mass[i]);
  }
  return p.cast<Real>();
}

Vec3 World::angular_momentum() const {
  const detail::BodyStore& b = state_->bodies;
  Eigen::Vector3d l = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (!b.is_dynamic(i)) continue;
    const double m = 1.0 / double(b.inv_mass[i]);
    const Eigen::Vector3d x = b.position(i).cast<double>();
    const Eigen::Vector3d v = b.linear_velocity(i).cast<double>();
    const Eigen::Quaterniond q = b.orientation(i).cast<double>();
    const Eigen::Vector3d w_body = q.conjugate() * b.angular_velocity(i).cast<double>();
    const Eigen::Vector3d l_body(w_body.x() / b.inv_ix[i], w_body.y() / b.inv_iy[i],
                                 w_body.z() / b.inv_iz[i]);
    l += m * x.cross(v) + q * l_body;
  }
  return l.cast<Real>();
}

}  // namespace elan
