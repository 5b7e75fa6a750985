// Contact manifolds: the narrowphase's output and the solver's input, one per touching or near
// pair, kept sorted by pair key.
#pragma once

#include <cstdint>

#include "elan/math.hpp"

namespace elan::detail {

inline constexpr int kMaxManifoldPoints = 4;

struct ContactPoint {
  Vec3 anchor_a = Vec3::Zero();  // m, world: contact point minus A's centre of mass
  Vec3 anchor_b = Vec3::Zero();  // m, world: contact point minus B's centre of mass
  Real separation = 0;           // m: negative = penetration, positive = speculative gap
  uint32_t feature_id = 0;       // same while the same pair of features touches
  Real normal_impulse = 0;       // N s, accumulated; carried to the next step (warm start)
  Real max_normal_impulse = 0;   // N s, largest applied during the step (events, sleep)
};

struct Manifold {
  uint64_t key = 0;     // make_pair_key(body_a, body_b)
  uint32_t body_a = 0;  // dense index; the static body, if any, is always B
  uint32_t body_b = 0;
  Vec3 normal = Vec3::UnitY();  // unit, world, from A towards B
  int point_count = 0;
  ContactPoint points[kMaxManifoldPoints];
  // Friction acts once per manifold, at the centre of its points (Gregorius, "Robust Contact
  // Creation for Physics Simulations", GDC 2015): a 2D tangent impulse and a twist about the
  // normal, carried to the next step like the normal impulses.
  Real tangent_impulse[2] = {0, 0};  // N s, along the solver's tangent basis of `normal`
  Real twist_impulse = 0;            // N m s, about `normal`
  // Poses when the points were last computed by the exact test, for reusing them while the
  // pair's relative pose stays within a small tolerance (Jolt's body pair cache).
  Quat orientation_a = Quat::Identity();  // A's principal frame to world at that time
  Quat orientation_b = Quat::Identity();
  Vec3 relative_position = Vec3::Zero();  // m: B's centre of mass minus A's, in A's frame
};

}  // namespace elan::detail
