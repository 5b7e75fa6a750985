// SPDX-License-Identifier: MIT
// Shared helpers of the physics, determinism and stage tests: building small worlds in code,
// loading the standard scenes, and the sanitizer switch that shrinks the longest runs.
#pragma once

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "elan/elan.hpp"

namespace elan::test {

// Under AddressSanitizer or ThreadSanitizer: tests run smaller scenes.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif

inline constexpr Real kEps = std::numeric_limits<Real>::epsilon();
inline constexpr Real kDt = Real(1.0 / 60.0);

inline std::string scene_path(const std::string& name) {
  return std::string(ELAN_SCENE_DIR) + "/" + name;
}

inline ShapeDef sphere_shape(Real radius) {
  ShapeDef s;
  s.type = ShapeType::Sphere;
  s.radius = radius;
  return s;
}

inline ShapeDef box_shape(const Vec3& half_extents) {
  ShapeDef s;
  s.type = ShapeType::Box;
  s.half_extents = half_extents;
  return s;
}

inline ShapeDef capsule_shape(Real radius, Real half_height) {
  ShapeDef s;
  s.type = ShapeType::Capsule;
  s.radius = radius;
  s.half_height = half_height;
  return s;
}

inline ShapeDef plane_shape(const Vec3& normal, Real offset) {
  ShapeDef s;
  s.type = ShapeType::Plane;
  s.normal = normal;
  s.offset = offset;
  return s;
}

/// Creates the shape and a body using it; `def.shape` is overwritten.
inline BodyId add_body(World& world, const ShapeDef& shape, BodyDef def) {
  def.shape = world.create_shape(shape);
  return world.create_body(def);
}

inline BodyDef at(const Vec3& position, MotionType motion = MotionType::Dynamic) {
  BodyDef d;
  d.position = position;
  d.motion = motion;
  return d;
}

/// A world without gravity or sleep, on one thread: free flight, spin and joints alone.
inline World zero_gravity_world(int substeps = 4) {
  WorldDef def;
  def.gravity = Vec3::Zero();
  def.substeps = substeps;
  def.allow_sleep = false;
  def.threads = 1;
  return World(def);
}

/// The static ground of the standard scenes: the top face is the plane y = 0.
inline BodyId add_ground(World& world, Real friction = Real(0.5)) {
  BodyDef d = at(Vec3(0, -1, 0), MotionType::Static);
  d.friction = friction;
  return add_body(world, box_shape(Vec3(50, 1, 50)), d);
}

/// Loads a standard scene into a new world with the given thread count and broadphase; the
/// scene's timestep is returned through `dt`.
inline World load_world(const std::string& name, int threads, Real& dt,
                        BroadphaseType broadphase = BroadphaseType::SweepAndPrune) {
  const std::string path = scene_path(name);
  const Scene scene = load_scene(path);
  WorldDef def = scene.world;
  def.threads = threads;
  def.broadphase = broadphase;
  World world(def);
  load_into(scene, world, path);
  dt = scene.timestep;
  return world;
}

/// The gravity vector of magnitude g tilted by `angle` (rad) about +z: a flat ground then acts as
/// a slope of that angle descending towards +x.
inline Vec3 tilted_gravity(Real angle, Real g = Real(9.81)) {
  return Vec3(g * std::sin(angle), -g * std::cos(angle), 0);
}

inline bool all_finite(const World& world) {
  for (std::size_t i = 0; i < world.body_count(); ++i) {
    const BodyId id = world.body_at(i);
    if (!world.position(id).allFinite() || !world.orientation(id).coeffs().allFinite() ||
        !world.linear_velocity(id).allFinite() || !world.angular_velocity(id).allFinite()) {
      return false;
    }
  }
  return true;
}

}  // namespace elan::test
