// Contact manifolds: the narrowphase's output and the solver's input, one per touching or near
// pair, kept sorted by pair key.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/base/packed_rotation.hpp"
#include "core/base/pair_key.hpp"
#include "elan/math.hpp"

namespace elan::detail {

inline constexpr int kMaxManifoldPoints = 4;

// B's arm is not stored: a manifold's points are each one world point seen from both centres
// (the exact tests report them so and the body pair cache carries them so), so B's arm is A's
// minus B's centre relative to A's at the poses the points were made at (PairCache::anchor_b).
struct ContactPoint {
  Vec3 anchor_a = Vec3::Zero();  // m, world: contact point minus A's centre of mass
  Real separation = 0;           // m: negative = penetration, positive = speculative gap
  uint32_t feature_id = 0;       // same while the same pair of features touches
  Real normal_impulse = 0;       // N s, accumulated; carried to the next step (warm start)
};

// Dense body indices fit in 29 bits, so a manifold's point count shares a word with body_b.
// World::create_body refuses a body past the limit.
inline constexpr uint32_t kManifoldBodyBits = 29;
inline constexpr std::size_t kMaxBodyCount = std::size_t{1} << kManifoldBodyBits;

// 128 bytes in float, two cache lines. A pile keeps about 2.7 manifolds a body and the collide
// stage rewrites each every step, so what can be derived is: the pair key from the bodies, B's
// arms from A's. The solver reads every byte of it, in colour order, one manifold here and one
// there: aligned, that is two lines. The poses of the body pair cache are apart (PairCache), kept
// only for the pairs that reuse their points: in a pile most manifolds have a sphere or capsule
// in them, and those 64 bytes were never read (pile10k: 1547 -> 1415 B/body of engine state).
struct alignas(64) Manifold {
  uint32_t body_a = 0;  // dense index; the static body, if any, is always B
  uint32_t body_b : kManifoldBodyBits = 0;
  // A bit-field of unsigned, not a uint8_t: a char-typed field may alias any store, so every
  // loop over the points that writes one had to load the count again.
  uint32_t point_count : 32 - kManifoldBodyBits = 0;
  Vec3 normal = Vec3::UnitY();  // unit, world, from A towards B
  ContactPoint points[kMaxManifoldPoints];
  // Friction acts once per manifold, at the centre of its points (Gregorius, "Robust Contact
  // Creation for Physics Simulations", GDC 2015): a 2D tangent impulse and a twist about the
  // normal, carried to the next step like the normal impulses.
  Real tangent_impulse[2] = {0, 0};  // N s, along the solver's tangent basis of `normal`
  Real twist_impulse = 0;            // N m s, about `normal`

  // The list's sort key.
  uint64_t key() const { return make_pair_key(body_a, body_b); }
};
static_assert(sizeof(Real) != 4 || sizeof(Manifold) == 128, "Manifold: 128 bytes in float");
static_assert((kMaxManifoldPoints >> (32 - kManifoldBodyBits)) == 0, "point_count's bits");

// Jolt's body pair cache, for the manifold of the same key: the poses when its points were last
// updated (by the exact test or by carrying them along), the reference of the next update; and
// B's pose relative to A at the exact test, the reference of the tolerance, so that reuses cannot
// drift away from it. Kept, in key order, for the touching pairs whose points are reused
// (collide_pairs), no others.
// Its rotations are not aligned to 16 bytes, so an entry is 72 bytes, not 80.
struct PairCache {
  using Rotation = Eigen::Quaternion<Real, Eigen::DontAlign>;
  uint64_t key = 0;
  Rotation orientation_a = Rotation::Identity();  // A's principal frame to world at that time
  Rotation orientation_b = Rotation::Identity();
  Vec3 relative_position = Vec3::Zero();  // m: B's centre of mass minus A's, in A's frame
  Vec3 exact_position = Vec3::Zero();     // m: relative_position at the exact test
  PackedRotation exact_rotation;          // A's frame to B's (A^-1 B) at the exact test

  // B's arm of a point (world, from B's centre of mass) at the poses of the last update. The
  // solver, which runs at those poses, takes B's centre from the body store instead.
  Vec3 anchor_b(const ContactPoint& p) const {
    return p.anchor_a - orientation_a * relative_position;
  }
};
static_assert(sizeof(Real) != 4 || sizeof(PairCache) == 72, "PairCache: 72 bytes in float");

// A manifold's two bodies, A and B as it had them: what a contact end event needs of it.
struct ContactRecord {
  uint32_t body_a = 0, body_b = 0;
  uint64_t key() const { return make_pair_key(body_a, body_b); }
};

// Asks the cache for a manifold's three lines ahead of their use (kWrite: with ownership, for a
// manifold about to be rewritten). A hint: no result depends on it.
template <bool kWrite = false>
inline void prefetch(const Manifold& m) {
  const char* bytes = reinterpret_cast<const char*>(&m);
  for (std::size_t line = 0; line < sizeof(Manifold); line += 64) {
    __builtin_prefetch(bytes + line, kWrite ? 1 : 0);
  }
}

// Deterministic tangent basis from the normal (pick the axis least aligned with n, as Box2D's
// b2ComputeBasis does): the same normal always gives the same basis. Manifold::tangent_impulse
// is expressed in it.
inline void tangent_basis(const Vec3& n, Vec3& t1, Vec3& t2) {
  if (std::abs(n.x()) >= Real(0.57735027)) {
    t1 = Vec3(n.y(), -n.x(), 0);
  } else {
    t1 = Vec3(0, n.z(), -n.y());
  }
  t1.normalize();
  t2 = n.cross(t1);
}

// Re-expresses the friction impulse `old_t` of a manifold with normal `old_n` in the basis of
// `new_n`: the world impulse projected onto the new tangent plane. The basis can switch axis
// between nearby normals, so carrying the two numbers as they are would turn the impulse.
inline void carry_tangent_impulse(const Vec3& old_n, const Real old_t[2], const Vec3& new_n,
                                  Real new_t[2]) {
  Vec3 a1, a2, b1, b2;
  tangent_basis(old_n, a1, a2);
  tangent_basis(new_n, b1, b2);
  const Vec3 impulse = old_t[0] * a1 + old_t[1] * a2;
  new_t[0] = impulse.dot(b1);
  new_t[1] = impulse.dot(b2);
}

}  // namespace elan::detail
