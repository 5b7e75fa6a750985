// SPDX-License-Identifier: MIT
// Creation structs of the public API: shapes, bodies, worlds. All units SI, frames noted.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "elan/ids.hpp"
#include "elan/math.hpp"

namespace elan {

class ThreadPool;  // elan/thread_pool.hpp

enum class MotionType : uint8_t { Static, Kinematic, Dynamic };

enum class ShapeType : uint8_t {
  Sphere,
  Box,
  Capsule,
  Cylinder,
  ConvexHull,
  Plane,
  Mesh,         ///< static only: a two-sided triangle surface
  Heightfield,  ///< static only: a grid of heights, collided from above
  Compound,     ///< convex children, each at its own pose
};

/// The scene format's name of a shape type: "sphere", "box", "capsule", "cylinder",
/// "convex_hull", "plane", "mesh", "heightfield" or "compound".
const char* shape_type_name(ShapeType type);

/// The shape type the scene format names `name`; none for any other text.
std::optional<ShapeType> shape_type_from_name(std::string_view name);

struct CompoundChild;

/// The pair finder. All give the same sorted pair list, so the same bits. Tree keeps a dynamic
/// bounding-volume tree (the one the queries use) and wins on large, mostly static worlds.
enum class BroadphaseType : uint8_t { SweepAndPrune, AllPairs, Tree };

/// The instruction set the step's solver kernels run on (docs/api.md, "SIMD paths"). A portable
/// build carries three paths and takes the widest the CPU has (`Best`, or the environment variable
/// ELAN_SIMD=sse2|avx2|avx512 when set); a native build (ELAN_NATIVE) has the one path `Native`.
/// Every path gives the same bits.
enum class SimdPath : uint8_t { Best, Sse2, Avx2, Avx512, Native };
/// "best", "sse2", "avx2", "avx512" or "native": the names ELAN_SIMD and `elan run --simd` take.
const char* simd_path_name(SimdPath path);

/// A shape in its own frame. Capsule and cylinder axes are local Y.
struct ShapeDef {
  ShapeType type = ShapeType::Sphere;
  Real radius = 0.5;                        ///< m: sphere, capsule, cylinder
  Real half_height = 0.5;                   ///< m: half the capsule segment / cylinder height
  Vec3 half_extents = Vec3::Constant(0.5);  ///< m: box
  std::vector<Vec3> points;                 ///< m, shape frame: convex hull input cloud
  Vec3 normal = Vec3::UnitY();              ///< plane normal (normalised on creation)
  Real offset = 0;                          ///< m: plane is dot(normal, x) <= offset

  /// Mesh: vertices (m, shape frame) and triangles (zero-based vertex indices). Each triangle is
  /// two-sided; zero-area triangles, repeated or out-of-range indices are refused.
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;

  /// Heightfield: `heights` row after row, `columns` samples a row (at least 2 rows of 2). The
  /// sample heights[j * columns + i] is the point (i spacing_x, heights[..], j spacing_z) of the
  /// shape frame; each cell is two triangles; bodies collide with the surface from above. A NaN
  /// height is a hole: the triangles with that sample at a corner are not there.
  std::vector<Real> heights;  ///< m
  uint32_t columns = 0;
  Real spacing_x = 1;  ///< m, > 0
  Real spacing_z = 1;  ///< m, > 0

  /// Compound: convex children (not plane, mesh, heightfield or compound), each placed in the
  /// compound's shape frame. Mass properties are the children's summed.
  std::vector<CompoundChild> children;

  uint64_t user_data = 0;  ///< the caller's value, kept through snapshots; never read by elan
};

/// One child of a compound shape.
struct CompoundChild {
  ShapeDef shape;
  Vec3 position = Vec3::Zero();         ///< m, the child's shape frame in the compound's frame
  Quat orientation = Quat::Identity();  ///< normalised on creation
};

/// A body. `position`/`orientation` place the shape's own frame; velocities are those of the
/// centre of mass, angular velocity in the world frame.
struct BodyDef {
  MotionType motion = MotionType::Dynamic;
  ShapeId shape;
  Vec3 position = Vec3::Zero();          ///< m, world
  Quat orientation = Quat::Identity();   ///< shape frame to world (normalised on creation)
  Vec3 linear_velocity = Vec3::Zero();   ///< m/s, world, of the centre of mass
  Vec3 angular_velocity = Vec3::Zero();  ///< rad/s, world
  std::optional<Real> mass;              ///< kg; when absent, density * volume
  Real density = 1000;                   ///< kg/m^3
  Real friction = 0.5;                   ///< Coulomb coefficient, mixed as sqrt(f1 f2)
  Real restitution = 0;                  ///< mixed as max(e1, e2)
  Real linear_damping = 0;               ///< 1/s: dv/dt = -d v
  Real angular_damping = 0;              ///< 1/s: dw/dt = -d w
  uint32_t category_bits = 1;            ///< collision filter: what this body is
  uint32_t mask_bits = UINT32_MAX;       ///< collision filter: what it collides with
  bool awake = true;                     ///< start awake (dynamic bodies)
  /// A sensor reports overlap begin/end events (World::sensor_begin_events) with other bodies'
  /// shapes and takes no part in contact response. Static, kinematic or dynamic.
  bool sensor = false;
  Real gravity_scale = 1;  ///< multiplies the world's gravity for this body (finite)
  uint64_t user_data = 0;  ///< the caller's value, kept through snapshots; never read by elan
};

/// The ranges WorldDef, World's setters and ThreadPool accept: substeps and iterations in
/// 1..kMaxSubsteps and 1..kMaxIterations, threads in 0..kMaxThreads (0 = all cores). Tools and
/// scene files check against the same constants.
inline constexpr int kMaxSubsteps = 64;
inline constexpr int kMaxIterations = 64;
inline constexpr int kMaxThreads = 1024;

/// World settings.
struct WorldDef {
  Vec3 gravity = Vec3(0, Real(-9.81), 0);  ///< m/s^2, world
  int substeps = 4;                        ///< soft-step substeps per step
  int iterations = 2;                      ///< solver iterations per substep
  bool allow_sleep = true;
  int threads = 0;  ///< worker count; 0 = all cores (ignored when `thread_pool` is set)
  BroadphaseType broadphase = BroadphaseType::SweepAndPrune;
  /// The caller's pool: when set, the world runs its step in it (with its thread count as the
  /// worker count) instead of making its own. Must outlive the world.
  ThreadPool* thread_pool = nullptr;
  /// The SIMD path; asking for one this CPU or this build lacks is an `Error` on field "simd".
  SimdPath simd = SimdPath::Best;
};

}  // namespace elan
