// World: owns bodies, shapes and contacts and advances them in time with World::step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "elan/defs.hpp"
#include "elan/error.hpp"
#include "elan/ids.hpp"
#include "elan/math.hpp"
#include "elan/profile.hpp"

namespace elan {

namespace detail {
struct WorldState;
}

/// A physics world. Not thread-safe: call its methods from one thread at a time; the step
/// itself runs in parallel on the world's own TBB arena of `WorldDef::threads` workers.
/// Results are bit-identical for any thread count and broadphase on one build.
class World {
 public:
  /// Throws elan::Error for invalid settings (non-finite gravity, substeps < 1, ...).
  explicit World(const WorldDef& def = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Creates an immutable shape that any number of bodies may share. Throws elan::Error.
  ShapeId create_shape(const ShapeDef& def);
  /// Creates a body. Throws elan::Error naming the field for invalid input (a stale shape id,
  /// non-finite values, zero orientation, non-positive mass or density, a non-static plane).
  BodyId create_body(const BodyDef& def);

  /// Advances the world by `dt` seconds. Never throws; returns StepStatus flags.
  uint32_t step(Real dt);

  /// Is `id` a live body of this world?
  bool is_valid(BodyId id) const;
  std::size_t body_count() const;
  /// Id of the body at dense index `index` (creation order while nothing is destroyed).
  BodyId body_at(std::size_t index) const;

  /// Pose of the body's shape frame (as given at creation), world frame. Throw elan::Error on
  /// a stale id.
  Vec3 position(BodyId id) const;  ///< m
  Quat orientation(BodyId id) const;
  Vec3 linear_velocity(BodyId id) const;   ///< m/s, of the centre of mass
  Vec3 angular_velocity(BodyId id) const;  ///< rad/s, world
  Vec3 center_of_mass(BodyId id) const;    ///< m, world
  Real mass(BodyId id) const;              ///< kg (0 for static and kinematic)
  MotionType motion_type(BodyId id) const;
  bool is_awake(BodyId id) const;

  void set_linear_velocity(BodyId id, const Vec3& v);   ///< wakes the body
  void set_angular_velocity(BodyId id, const Vec3& w);  ///< wakes the body

  /// Settings that may change between steps.
  const WorldDef& settings() const;
  void set_substeps(int substeps);
  void set_iterations(int iterations);
  void set_broadphase(BroadphaseType type);
  /// Changes the worker count (1 or more; 0 = all cores).
  void set_threads(int threads);

  /// Counts and times of the last step.
  const StepStats& last_step() const;
  /// 64-bit hash of every body's stored position, orientation, linear and angular velocity,
  /// in body index order.
  uint64_t state_hash() const;
  Real kinetic_energy() const;    ///< J, all dynamic bodies
  Vec3 linear_momentum() const;   ///< kg m/s, dynamic bodies
  Vec3 angular_momentum() const;  ///< kg m^2/s, dynamic bodies, about the world origin

  /// Internal state, for the engine's own tools, tests and benchmarks.
  detail::WorldState& state() { return *state_; }
  const detail::WorldState& state() const { return *state_; }

 private:
  std::unique_ptr<detail::WorldState> state_;
};

}  // namespace elan
