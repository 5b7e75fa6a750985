// SPDX-License-Identifier: MIT
// Snapshots (the whole world, restorable into any World), compact rollback states (only what a
// step changes, restorable onto the same world) and a divergence finder for two worlds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "elan/math.hpp"
#include "elan/world.hpp"

namespace elan {

/// Format version written by save_snapshot and save_rollback. A snapshot of any version from
/// kOldestSnapshotVersion on is read (version 9 has no user data, gravity scales, sensor flags or
/// overlaps: they load as their defaults; versions 9 and 10 carry a mesh's binary tree, collapsed
/// on load into the 4-wide tree the mesh is built with, so the world steps as it would have;
/// version 12 may carry heightfield holes, NaN samples, which no earlier version has, so a build
/// that reads only up to 11 refuses them rather than taking a hole for ground); a rollback state
/// of another version is refused.
inline constexpr uint32_t kSnapshotVersion = 12;
inline constexpr uint32_t kOldestSnapshotVersion = 9;

/// Saves the whole state of `world`: settings (`WorldDef`, step count), every shape as built
/// (hull vertices, faces and edges in the principal frame, frames, mass properties), every body
/// column as stored, the id slots, generations and free list, and every field of every contact
/// manifold (the next step's warm start). Restoring it and stepping gives the same bits as never
/// having stopped, for any thread count and broadphase.
///
/// Format (all integers and `Real` bit patterns little-endian, written value by value):
///
///     magic "\x89ELANSNP" (8 bytes) | u32 version | u32 sizeof(Real)
///     | world: gravity 3R, i32 substeps, i32 iterations, u8 allow_sleep, i32 threads,
///       u8 broadphase, u64 step count, u32 reported status flags
///     | u32 shapes, each: u8 type, R radius, R half_height, 3R half_extents, 3R plane normal,
///       R plane offset, 3R frame position, 4R frame rotation (w x y z), R volume,
///       3R unit inertia, 3R local min, 3R local max, R bounding radius, u8 has hull
///       [u32 n, n x 3R vertices | u32 n, n x (3R normal, R offset, u32 first, u32 count) faces
///        | u32 n, n x u32 face vertices | u32 n, n x 2 u32 edges], then a mesh's, heightfield's
///       or compound's built data (`core/world/snapshot.cpp`: a mesh's triangles in tree order
///       and its tree, 4-wide from version 11: u32 nodes, each 12 f32 mins and 12 f32 maxes
///       axis by axis, 4 u32 indices, 4 u32 counts), u8 destroyed, u64 user data (version 10)
///     | u32 bodies n, then each BodyStore column in declaration order, n values each
///     | u32 applied forces, each: u32 body, 3R force, 3R torque (the force and torque applied
///       for the next step; the body's `applied` column holds its entry's index)
///     | u32 body traits t, each: R friction, R restitution, R linear damping, R angular damping,
///       u32 category bits, u32 mask bits, (version 10) R gravity scale, u32 flags (1: sensor)
///       | u32 free traits, each u32 (the body's `traits`
///       column holds its entry's index; entries no body uses are listed as free)
///     | u32 slots m, m x u32 slot index, m x u32 generation | u32 f, f x u32 free slots
///     | u32 manifolds, each: u64 key, u32 body a, u32 body b, 3R normal, u8 point count,
///       4 points x (3R anchor a, R separation, u32 feature id, R normal impulse),
///       2R tangent impulses, R twist impulse, u8 has poses (1 for a manifold that may reuse
///       its points: neither body a sphere, capsule or cylinder), then if 1: 4R orientation a,
///       4R orientation b (w x y z), 3R relative position, 3R exact position, 7-byte exact
///       rotation (3 x i16 components and u8 index of the fourth, the largest, which is left
///       out: core/base/packed_rotation.hpp)
///       (version 2 added the poses, 3 the exact ones; 4 dropped anchor b, derived from
///       a, and the max normal impulse, which nothing read; 5 packed the exact rotation; 6
///       kept the poses only where they are read)
///     | joints (version 8): u32 joints, each: u8 type, u32 body slot a, u32 body slot b
///       (UINT32_MAX: the world), u32 joint slot, 3R anchor, 3R anchor b, 3R axis, u8 flags
///       (has_anchor 1, collide_connected 2, limits 4, motor 8, spring 16), R limits lower,
///       upper, motor speed, max force, spring frequency, damping ratio, target, min length,
///       max length, swing limit, break force, friction, constraint hertz and damping ratio,
///       3R anchor a and 3R anchor b in the bodies'
///       frames, 4R frame a, 4R frame b, R min, max and rest length as resolved, impulses
///       (3R point, 3R angular, 3R linear, 3R friction, R axial, spring, motor, lower, upper,
///       swing), 3R force, 3R torque, (version 10) u64 user data | u32 joint slots m, m x u32
///       index, m x u32 generation | u32 f, f x u32 free joint slots
///     | (version 10) per body in index order: u64 user data, R density, R given mass (0: none)
///       | R hit event threshold | u32 sensor overlaps, each: u32 sensor, u32 visitor (body
///       indices, sorted)
///     | u64 checksum: 64-bit FNV-1a over 8-byte little-endian words of every byte before it
///       (the tail zero-padded), so any single changed byte changes it.
///
/// R is sizeof(Real) bytes. A leading 0x89 keeps a text file from passing as a snapshot.
std::vector<uint8_t> save_snapshot(const World& world);

/// Replaces the whole state of `world` (bodies, shapes, ids, contacts, gravity, substeps,
/// iterations, sleep setting, step count) with the snapshot's. The world keeps its own thread
/// count, broadphase, thread pool and pair filter (results do not depend on the first three;
/// the filter is the caller's code); the last step's events are cleared. Throws elan::Error (field
/// "snapshot") for a file that is not a snapshot, another format version or `Real` size, a
/// truncated or corrupt file, or inconsistent contents; `world` is then left unchanged.
void restore_snapshot(World& world, std::span<const uint8_t> bytes);

/// A new world from a snapshot, with the saved thread count and broadphase. Throws as
/// restore_snapshot.
World load_snapshot(std::span<const uint8_t> bytes);

/// Saves only what a step changes, for rolling back a world whose bodies and shapes stay the
/// same (no body created or destroyed in between): for every non-static body its pose,
/// velocities, applied force and torque, sleep timer and flags (20 R + 1 byte: 81 bytes per
/// body with float), the step count, every contact manifold with its impulses, keyed by pair
/// key and feature id, and the joints as in a snapshot (a joint that broke or was created since
/// is back as it was). The manifold geometry (normal, anchors, separation) is kept too: a
/// sleeping island's manifolds are carried from step to step as they are and solved as stored
/// when the island wakes, and a point whose feature id finds no match is warm-started by
/// position, so neither can be re-derived from the poses.
///
/// Format: magic "\x89ELANRBK" | u32 version | u32 sizeof(Real) | u32 bodies | u64 layout
/// fingerprint (shape, slot and motion of every body) | u64 step count | per non-static body
/// in index order: px py pz qw qx qy qz vx vy vz wx wy wz, fx fy fz tx ty tz (the applied force and
/// torque, zero if none), sleep_time (R each),
/// u8 flags | u32 manifolds, each: u64 key, u8 (1 when body A is the higher index), 3R normal,
/// u8 point count, per point: 3R anchor a, R separation, u32 feature id,
/// R normal impulse; then 2R tangent impulses, R twist impulse, u8 has poses and, if 1,
/// 4R orientation a, 4R orientation b, 3R relative position, 3R exact position, 7-byte exact
/// rotation (as in the snapshot) | joints as in the snapshot | sensor overlaps as in the snapshot
/// | u64 checksum as above.
std::vector<uint8_t> save_rollback(const World& world);
/// As above, into `out` (cleared first), reusing its capacity: no allocation once warm.
void save_rollback(const World& world, std::vector<uint8_t>& out);

/// Puts `world` back into the saved state. Throws elan::Error (field "rollback") for another
/// world's state (body count or layout differs), another version or `Real` size, or a
/// truncated or corrupt buffer; `world` is then left unchanged.
void restore_rollback(World& world, std::span<const uint8_t> bytes);

/// Where two worlds first differ.
struct Divergence {
  bool found = false;    ///< false: no difference in the steps compared
  uint64_t step = 0;     ///< steps taken by find_divergence when seen (0: before stepping)
  std::size_t body = 0;  ///< dense body index
  /// "px", "py", "pz", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz" (centre of
  /// mass pose and velocities as stored, the state hash's fields), then "sleep_time", "flags";
  /// "body_count" when the worlds hold different numbers of bodies.
  std::string field;
  double value_a = 0;  ///< the field's value in each world (for body_count: the counts)
  double value_b = 0;
};

/// Compares the stored state of every body of `a` and `b`, bit for bit (so -0 and +0 differ),
/// in index order and, within a body, in the field order above. Returns the first difference.
Divergence compare_worlds(const World& a, const World& b);

/// Compares `a` and `b`, then steps both by `dt` side by side, comparing after each step, for
/// at most `steps` steps. Returns the first difference (with its step) or found == false.
Divergence find_divergence(World& a, World& b, uint64_t steps, Real dt);

}  // namespace elan
