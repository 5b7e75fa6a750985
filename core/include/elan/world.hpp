// SPDX-License-Identifier: MIT
// World: owns bodies, shapes and contacts and advances them in time with World::step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "elan/debug_draw.hpp"
#include "elan/defs.hpp"
#include "elan/error.hpp"
#include "elan/events.hpp"
#include "elan/ids.hpp"
#include "elan/joints.hpp"
#include "elan/math.hpp"
#include "elan/profile.hpp"
#include "elan/queries.hpp"

namespace elan {

namespace detail {
struct WorldState;
struct WorldAccess;
}  // namespace detail

class ThreadPool;

/// A physics world. Not thread-safe: call its methods from one thread at a time; the step
/// itself runs in parallel on the world's own pool of `WorldDef::threads` workers (or on
/// `WorldDef::thread_pool`). Results are bit-identical for any thread count and broadphase on one
/// build, also across creating and destroying bodies between steps.
///
/// Every call taking a BodyId or ShapeId throws elan::Error (field "body" / "shape") for an id
/// that is stale, destroyed or from another world's range; setters throw elan::Error naming the
/// field for non-finite or out-of-range values. None of them may be called during a step.
class World {
 public:
  /// Throws elan::Error for invalid settings (non-finite gravity, substeps < 1, ...).
  explicit World(const WorldDef& def = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Makes room for `bodies` bodies and `shapes` shapes in all, so that creating up to that many
  /// allocates nothing more for them (Jolt takes such maxima up front; here they are a hint, and
  /// a world may grow past them). Without it the stores grow by doubling and keep up to half
  /// their capacity unused. Throws elan::Error "bodies" for more than 2^29 (a world's limit) or
  /// "shapes" for more than 2^32 - 2.
  void reserve(std::size_t bodies, std::size_t shapes);
  /// Creates an immutable shape that any number of bodies may share. Throws elan::Error.
  ShapeId create_shape(const ShapeDef& def);
  /// Destroys a shape no body uses (elan::Error "shape" if one does). Its id stays invalid:
  /// shape ids are not reused.
  void destroy_shape(ShapeId id);
  bool is_valid(ShapeId id) const;
  /// Creates a body. Throws elan::Error naming the field for invalid input (a stale shape id,
  /// non-finite values, zero orientation, non-positive mass or density, a non-static plane), or
  /// "body" when the world already holds 2^29 bodies.
  BodyId create_body(const BodyDef& def);
  /// Destroys a body between steps. Its contacts are dropped, with a ContactEndEvent for each
  /// touching one (appended to contact_end_events() at once), and the dynamic bodies it touched
  /// are woken. The last body moves into its dense index (swap-remove), so dense indices and
  /// bulk views are invalidated; other ids stay valid.
  void destroy_body(BodyId id);

  /// Creates a joint between steps (see JointDef). Throws elan::Error naming the field: a stale
  /// body, A == B, neither body dynamic, a zero or non-finite axis, limits lower > upper, a
  /// negative motor force, a spring frequency <= 0, lengths out of order, a swing limit outside
  /// [0, pi], a negative friction, break_force <= 0. Wakes the bodies.
  JointId create_joint(const JointDef& def);
  /// Removes a joint between steps (no event) and wakes its bodies.
  void destroy_joint(JointId id);
  bool is_valid(JointId id) const;
  std::size_t joint_count() const;
  /// Id of the joint at dense index `index` (creation order while nothing is removed).
  JointId joint_at(std::size_t index) const;
  /// The definition the joint was made with, as changed by the setters below.
  const JointDef& joint_def(JointId id) const;
  /// Runtime changes (checked as in create_joint; they wake the bodies).
  void set_joint_motor(JointId id, const JointMotor& motor);
  void set_joint_spring(JointId id, const JointSpring& spring);
  void set_joint_limits(JointId id, const JointLimits& limits);
  void set_joint_swing_limit(JointId id, Real swing_limit);              ///< Cone, rad in [0, pi]
  void set_joint_lengths(JointId id, Real min_length, Real max_length);  ///< Distance, m
  void set_joint_friction(JointId id, Real friction);                    ///< N m (slider: N), >= 0
  /// Constraint force (N, world) and torque (N m, world) the joint applied to body A over the
  /// last step (the last substep's impulses / substep time); zero before its first step.
  Vec3 joint_force(JointId id) const;
  Vec3 joint_torque(JointId id) const;
  /// The joint's coordinate at the current poses: hinge angle and cone twist (rad, of A relative
  /// to B about the axis, in (-pi, pi]), slider position (m, along the axis), distance (m).
  /// 0 for ball and fixed joints.
  Real joint_coordinate(JointId id) const;
  /// Joints that left the world in the last step (broken) or by destroy_body since; cleared when
  /// the next step starts.
  std::span<const JointRemovedEvent> joint_removed_events() const;

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

  Real friction(BodyId id) const;
  Real restitution(BodyId id) const;
  uint32_t category_bits(BodyId id) const;
  uint32_t mask_bits(BodyId id) const;

  /// Setters of one body, between steps. Those that move or push a non-static body wake it; on
  /// a static body velocity setters, forces and impulses are ignored.
  void set_linear_velocity(BodyId id, const Vec3& v);   ///< m/s, world, of the centre of mass
  void set_angular_velocity(BodyId id, const Vec3& w);  ///< rad/s, world
  /// Teleports the shape frame (as BodyDef::position), m, world. Velocities are kept.
  void set_position(BodyId id, const Vec3& position);
  /// Shape frame to world; normalised (elan::Error for a zero or non-finite quaternion).
  void set_orientation(BodyId id, const Quat& orientation);
  void set_transform(BodyId id, const Transform& pose);  ///< both at once
  /// Force (N, world) through the centre of mass for the next step only (cleared by the step).
  void apply_force(BodyId id, const Vec3& force);
  /// Force (N, world) at a world point (m): adds the torque (point - centre of mass) x force.
  void apply_force_at(BodyId id, const Vec3& force, const Vec3& point);
  void apply_torque(BodyId id, const Vec3& torque);  ///< N m, world, for the next step only
  /// Instant velocity change: dv = J / m, dw = I^-1 ((point - centre of mass) x J);
  /// J in N s, world; point in m, world. Dynamic bodies only (ignored otherwise).
  void apply_impulse(BodyId id, const Vec3& impulse, const Vec3& point);
  void apply_linear_impulse(BodyId id, const Vec3& impulse);   ///< N s, world: dv = J / m
  void apply_angular_impulse(BodyId id, const Vec3& impulse);  ///< N m s, world: dw = I^-1 L
  /// Kinematic bodies: sets the velocities that carry the shape frame to `target` (world) in
  /// `dt` seconds (> 0), the rotation by the shorter arc. elan::Error "body" if not kinematic.
  void move_kinematic(BodyId id, const Transform& target, Real dt);
  void wake(BodyId id);   ///< dynamic bodies: simulate again (its island wakes with it)
  void sleep(BodyId id);  ///< dynamic bodies: stop simulating now, velocities zeroed
  void set_friction(BodyId id, Real friction);        ///< >= 0, mixed as sqrt(f1 f2)
  void set_restitution(BodyId id, Real restitution);  ///< >= 0, mixed as max(e1, e2)
  /// kg, > 0, dynamic bodies only; the inertia follows from the shape (I = mass * unit inertia).
  void set_mass(BodyId id, Real mass);
  /// Collision filter bits (see BodyDef); takes effect in the next step's broadphase.
  void set_collision_filter(BodyId id, uint32_t category_bits, uint32_t mask_bits);

  // ---- Body state and changes users reach for (issue 39).
  ShapeId shape(BodyId id) const;
  /// The definition a shape was made with (with its user_data as last set).
  const ShapeDef& shape_def(ShapeId id) const;
  /// kg m^2, world frame, about the centre of mass (zero for static and kinematic bodies).
  Mat3 inertia(BodyId id) const;
  Aabb bounds(BodyId id) const;  ///< the bounding box the broadphase and queries use
  bool is_sensor(BodyId id) const;
  Real gravity_scale(BodyId id) const;
  Real linear_damping(BodyId id) const;
  Real angular_damping(BodyId id) const;
  /// Static <-> kinematic <-> dynamic between steps: a body made dynamic gets its mass from its
  /// shape's density of creation (or its last set mass) and wakes; a body made static or
  /// kinematic keeps (kinematic) or zeroes (static) its velocities; its contacts are rebuilt.
  void set_motion_type(BodyId id, MotionType type);
  void set_gravity_scale(BodyId id, Real scale);           ///< finite
  void set_damping(BodyId id, Real linear, Real angular);  ///< 1/s, >= 0
  /// Swaps a body's shape between steps (mass and inertia follow at the body's density; a
  /// static-only shape on a non-static body is an elan::Error "shape"). Wakes the body.
  void set_shape(BodyId id, ShapeId shape);
  void set_sensor(BodyId id, bool sensor);
  void set_gravity(const Vec3& gravity);  ///< m/s^2, world; wakes every body
  uint64_t user_data(BodyId id) const;
  void set_user_data(BodyId id, uint64_t value);
  uint64_t user_data(ShapeId id) const;
  void set_user_data(ShapeId id, uint64_t value);
  uint64_t user_data(JointId id) const;
  void set_user_data(JointId id, uint64_t value);

  /// Bulk, zero-copy views of the body columns in dense index order; element i belongs to
  /// body_ids()[i]. Positions are those of the centre of mass and orientations those of the
  /// principal axes (the store's own pose): for every shape but the convex hull this is the
  /// shape frame; a hull's shape frame is offset by its frame (use position()/orientation()).
  /// Invalidated by create_body and destroy_body (and snapshot restore); step() and setters do
  /// not reallocate, so a view stays valid across steps and shows the new values.
  struct BodyColumns {
    std::span<const Real> px, py, pz;      ///< m, world: centre of mass
    std::span<const Real> qw, qx, qy, qz;  ///< principal axes to world, unit
    std::span<const Real> vx, vy, vz;      ///< m/s, world
    std::span<const Real> wx, wy, wz;      ///< rad/s, world
  };
  BodyColumns body_columns() const;
  /// Dense index -> id, valid until the next create_body / destroy_body.
  std::span<const BodyId> body_ids() const;
  /// Bulk setters: one value per body in dense index order. Each span must have body_count()
  /// elements of finite values (elan::Error "positions" / ... otherwise, nothing changed).
  /// Same effect as the per-body setter on every body: moved or pushed non-static bodies wake.
  void set_center_of_mass_positions(std::span<const Real> x, std::span<const Real> y,
                                    std::span<const Real> z);
  void set_linear_velocities(std::span<const Real> x, std::span<const Real> y,
                             std::span<const Real> z);
  void set_angular_velocities(std::span<const Real> x, std::span<const Real> y,
                              std::span<const Real> z);

  /// Contact events of the last step, in pair-key order (by the pair's dense indices), plus
  /// end events of destroy_body calls since. Cleared when the next step starts.
  std::span<const ContactBeginEvent> contact_begin_events() const;
  std::span<const ContactEndEvent> contact_end_events() const;
  /// Sensor overlap events of the last step (plus end events of destroy_body calls since).
  std::span<const SensorBeginEvent> sensor_begin_events() const;
  std::span<const SensorEndEvent> sensor_end_events() const;
  /// Contacts that began in the last step with an approach speed >= the hit threshold.
  std::span<const ContactHitEvent> contact_hit_events() const;
  void set_hit_event_threshold(Real speed);  ///< m/s, >= 0; default 1 (Box2D's)
  /// The current contact manifolds (touching or speculative), in pair-key order, between steps.
  std::size_t contact_count() const;
  ContactView contact(std::size_t index) const;
  /// The manifolds that involve `body`, into `out` (cleared), in pair-key order.
  void contacts_of(BodyId body, std::vector<ContactView>& out) const;
  /// Calls the drawer for what `what` (DebugDrawFlags) selects; see DebugDrawer.
  void debug_draw(DebugDrawer& drawer, uint32_t what) const;
  /// Installs (or, with an empty function, removes) the pair filter; see PairFilter.
  void set_pair_filter(PairFilter filter);

  // ---- Queries (issue 39). All const: they read the world and its query tree, kept current by
  // every change between steps and, for the bodies a step moved, by the first query after the
  // step (under a lock: one thread refits, the others wait), so any number of threads may query
  // at once between steps. The tree's shape depends on when the world was queried; no answer does
  // but cast_ray_any's choice among several hits, and the bodies a filter's `accept` is asked
  // about may differ too. Nothing a step computes depends on it. Filters: see QueryFilter.

  /// Closest body the ray from `origin` (m, world) along `direction` (any non-zero length)
  /// enters within `max_distance` (m); ties go to the lower dense index.
  std::optional<RayHit> cast_ray(const Vec3& origin, const Vec3& direction, Real max_distance,
                                 const QueryFilter& filter = {}) const;
  /// Some body the ray enters within max_distance (the first the tree walk finds: the same for
  /// the same calls, but which of several hits may change with the steps after which the world
  /// was queried), cheaper than the closest: for line-of-sight tests.
  std::optional<RayHit> cast_ray_any(const Vec3& origin, const Vec3& direction, Real max_distance,
                                     const QueryFilter& filter = {}) const;
  /// Every body the ray enters within max_distance, into `out` (cleared), sorted by distance
  /// then dense index.
  void cast_ray_all(const Vec3& origin, const Vec3& direction, Real max_distance,
                    std::vector<RayHit>& out, const QueryFilter& filter = {}) const;
  /// Closest hits of many rays, in parallel on the world's pool: hits[i] for rays[i] (a null
  /// body when it hits nothing). elan::Error "hits" when the spans' sizes differ.
  void cast_rays(std::span<const Ray> rays, std::span<RayHit> hits,
                 const QueryFilter& filter = {}) const;
  /// Sweeps `shape` (any shape this world made, but plane, mesh and heightfield) from `start`
  /// (shape frame to world) along `translation` (m, world); the first body it touches.
  std::optional<ShapeCastHit> cast_shape(ShapeId shape, const Transform& start,
                                         const Vec3& translation,
                                         const QueryFilter& filter = {}) const;
  /// Every body the sweep touches, into `out` (cleared), sorted by fraction then dense index.
  void cast_shape_all(ShapeId shape, const Transform& start, const Vec3& translation,
                      std::vector<ShapeCastHit>& out, const QueryFilter& filter = {}) const;
  /// Bodies whose exact shape overlaps `shape` at `pose` (touching counts), in dense index
  /// order, into `out` (cleared).
  void overlap_shape(ShapeId shape, const Transform& pose, std::vector<BodyId>& out,
                     const QueryFilter& filter = {}) const;
  /// Bodies whose bounding box overlaps the box (m, world), in dense index order, into `out`
  /// (cleared). Boxes are conservative: a body listed may not touch the box exactly.
  void overlap_box(const Vec3& lo, const Vec3& hi, std::vector<BodyId>& out,
                   const QueryFilter& filter = {}) const;
  /// Bodies whose solid contains `point` (m, world; meshes and heightfields contain nothing),
  /// in dense index order, into `out` (cleared).
  void overlap_point(const Vec3& point, std::vector<BodyId>& out,
                     const QueryFilter& filter = {}) const;
  /// The closest point of one body's surface to `point` (distance negative inside).
  PointHit closest_point(BodyId body, const Vec3& point) const;
  /// The closest body surface point within `max_distance` of `point`, if any.
  std::optional<PointHit> closest_point(const Vec3& point, Real max_distance,
                                        const QueryFilter& filter = {}) const;
  /// Moves a vertical capsule whose centre is at `position` by `displacement` (m, world),
  /// sliding along walls, climbing steps up to def.step_height and not climbing ground steeper
  /// than def.max_slope. Reads the world only; the caller moves its own kinematic body (and
  /// leaves it out with def.filter). Deterministic.
  CharacterMoveResult move_character(const Vec3& position, const Vec3& displacement,
                                     const CharacterMoveDef& def) const;

  /// The SIMD path the step runs (WorldDef::simd resolved: never `Best`).
  SimdPath simd_path() const;

  /// Settings that may change between steps.
  const WorldDef& settings() const;
  void set_substeps(int substeps);
  void set_iterations(int iterations);
  /// Whether resting islands may fall asleep (WorldDef::allow_sleep, on by default). Switching
  /// it off wakes every dynamic body and zeroes its sleep timer; the timers then stay at zero
  /// while it is off, so once it is switched on again a body sleeps only after resting for the
  /// full time to sleep. Switching it on changes nothing else, and setting the value it already
  /// has changes nothing at all. Bodies put to sleep by sleep() while it is off stay asleep until
  /// woken. Snapshots keep it: restore_snapshot and load_snapshot take the snapshot's value.
  void set_sleep_enabled(bool enabled);
  bool sleep_enabled() const;
  void set_broadphase(BroadphaseType type);
  /// Changes the worker count (1 or more; 0 = all cores); the world then uses its own pool.
  void set_threads(int threads);

  /// Counts and times of the last step.
  const StepStats& last_step() const;
  /// 64-bit hash of every body's stored position, orientation, linear and angular velocity,
  /// in body index order.
  uint64_t state_hash() const;
  Real kinetic_energy() const;    ///< J, all dynamic bodies
  Vec3 linear_momentum() const;   ///< kg m/s, dynamic bodies
  Vec3 angular_momentum() const;  ///< kg m^2/s, dynamic bodies, about the world origin

 private:
  // The engine's own code reaches the state through detail::state_of (core/world/world_access.hpp).
  friend struct detail::WorldAccess;
  std::unique_ptr<detail::WorldState> state_;
};

/// Steps several independent worlds by `dt` each, concurrently: a parallel loop over the worlds
/// in `pool` (without one, in the calling thread's current oneTBB arena: by default all cores),
/// each world's own parallel loops nested in the same pool and its solver stages run by one
/// thread (the worlds' own pools are not used). Each world ends with the same bits as if stepped
/// alone. Worlds must be distinct. Returns the OR of the worlds' StepStatus flags.
uint32_t step_all(std::span<World* const> worlds, Real dt, ThreadPool* pool = nullptr);

}  // namespace elan
