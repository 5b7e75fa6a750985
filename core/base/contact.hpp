// SPDX-License-Identifier: MIT
// Contact manifolds: the narrowphase's output and the solver's input, one per touching or near
// pair, kept sorted by pair key: the contact list of heads, and beside it, by key too, the tails
// of those with more than one point and the body pair cache's poses of those that reuse them.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/packed_rotation.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/rotate.hpp"
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

// A whole manifold: what the exact tests make and the collide stage works on. The contact list
// keeps it as a ManifoldHead and, past its first point, a ManifoldTail (below).
struct Manifold {
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
static_assert((kMaxManifoldPoints >> (32 - kManifoldBodyBits)) == 0, "point_count's bits");

// The contact list's entry: a manifold but for its points past the first. 64 bytes in float, one
// cache line. A pile keeps about 2.7 manifolds a body and the collide stage rewrites each every
// step, so what can be derived is: the pair key from the bodies, B's arms from A's. Most have one
// point (a sphere or capsule on something: 77 % of a large pile's, 1.39 points a manifold), so
// four point slots each (128 bytes) would leave most of the list unused. The solver reads heads in
// colour order, one here and one there: aligned, each is one line. The body pair cache's poses are
// apart too (PairCache), kept only for the pairs that reuse their points.
struct alignas(64) ManifoldHead {
  uint32_t body_a = 0;
  uint32_t body_b : kManifoldBodyBits = 0;
  uint32_t point_count : 32 - kManifoldBodyBits = 0;
  Vec3 normal = Vec3::UnitY();
  Real tangent_impulse[2] = {0, 0};
  Real twist_impulse = 0;
  ContactPoint first;  // points[0]
  // With more than one point: where its tail is in the list of tails. Set by color_contacts for
  // the solver's stages; stale once the lists change.
  uint32_t tail = 0;

  uint64_t key() const { return make_pair_key(body_a, body_b); }
};
static_assert(sizeof(Real) != 4 || sizeof(ManifoldHead) == 64, "ManifoldHead: 64 bytes in float");

// The points past the first of a manifold that has more than one, in a list of their own sorted
// by key (a box face on a box: four). 80 bytes in float.
struct ManifoldTail {
  uint64_t key = 0;
  ContactPoint points[kMaxManifoldPoints - 1];
};
static_assert(sizeof(Real) != 4 || sizeof(ManifoldTail) == 80, "ManifoldTail: 80 bytes in float");

// The fields a whole manifold and its head share, from one to the other.
template <class From, class To>
void copy_shared(const From& from, To& to) {
  to.body_a = from.body_a;
  to.body_b = from.body_b;
  to.point_count = from.point_count;
  to.normal = from.normal;
  to.tangent_impulse[0] = from.tangent_impulse[0];
  to.tangent_impulse[1] = from.tangent_impulse[1];
  to.twist_impulse = from.twist_impulse;
}

// A manifold's head and tail (the tail only for a manifold with more than one point), written in
// place: the collide stage stores one for every touching pair every step.
inline void store_head(const Manifold& m, ManifoldHead& h) {
  copy_shared(m, h);
  h.first = m.points[0];
}
inline void store_tail(const Manifold& m, ManifoldTail& t) {
  t.key = m.key();
  for (int k = 1; k < kMaxManifoldPoints; ++k) t.points[k - 1] = m.points[k];
}
inline ManifoldHead head_of(const Manifold& m) {
  ManifoldHead h;
  store_head(m, h);
  return h;
}
inline ManifoldTail tail_of(const Manifold& m) {
  ManifoldTail t;
  store_tail(m, t);
  return t;
}

// The whole manifold of a head and its tail (null for one point or none), into `m`; the points
// past its count are left as they were.
inline void load_whole(const ManifoldHead& h, const ManifoldTail* t, Manifold& m) {
  copy_shared(h, m);
  m.points[0] = h.first;
  if (t != nullptr) {
    for (int k = 1; k < kMaxManifoldPoints; ++k) m.points[k] = t->points[k - 1];
  }
}
inline Manifold whole(const ManifoldHead& h, const ManifoldTail* t) {
  Manifold m;
  load_whole(h, t, m);
  return m;
}

// Point k of a head whose tail index is set (ManifoldHead::tail).
inline ContactPoint& point_of(ManifoldHead& h, std::span<ManifoldTail> tails, int k) {
  return k == 0 ? h.first : tails[h.tail].points[k - 1];
}
inline const ContactPoint& point_of(const ManifoldHead& h, std::span<const ManifoldTail> tails,
                                    int k) {
  return k == 0 ? h.first : tails[h.tail].points[k - 1];
}

// The entry of `key` in a list kept beside the contact list (tails, poses: sorted by key, a subset
// of its keys), or null. `cursor` walks the list in key order alongside the contact list, so a
// pass over both is one pass over each.
template <class T>
const T* find_beside(std::span<const T> list, std::size_t& cursor, uint64_t key) {
  while (cursor < list.size() && list[cursor].key < key) ++cursor;
  return cursor < list.size() && list[cursor].key == key ? &list[cursor] : nullptr;
}

// The whole manifold of a head, its tail found in `tails` by `cursor` (find_beside).
inline Manifold whole_at(const ManifoldHead& h, std::span<const ManifoldTail> tails,
                         std::size_t& cursor) {
  return whole(h, h.point_count > 1 ? find_beside(tails, cursor, h.key()) : nullptr);
}

// Every whole manifold of a list of heads and its tails, in key order.
inline std::vector<Manifold> whole_list(std::span<const ManifoldHead> heads,
                                        std::span<const ManifoldTail> tails) {
  std::vector<Manifold> out;
  out.reserve(heads.size());
  std::size_t cursor = 0;
  for (const ManifoldHead& h : heads) out.push_back(whole_at(h, tails, cursor));
  return out;
}

// The heads and tails of a list of whole manifolds in key order.
inline void split_list(std::span<const Manifold> list, std::vector<ManifoldHead>& heads,
                       std::vector<ManifoldTail>& tails) {
  heads.clear();
  tails.clear();
  for (const Manifold& m : list) {
    heads.push_back(head_of(m));
    if (m.point_count > 1) tails.push_back(tail_of(m));
  }
}

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
    return p.anchor_a - rotate(orientation_a, relative_position);
  }
};
static_assert(sizeof(Real) != 4 || sizeof(PairCache) == 72, "PairCache: 72 bytes in float");

// A manifold's two bodies, A and B as it had them: what a contact end event needs of it.
struct ContactRecord {
  uint32_t body_a = 0, body_b = 0;
  uint64_t key() const { return make_pair_key(body_a, body_b); }
};

// Asks the cache for an entry's lines ahead of their use (kWrite: with ownership, for an entry
// about to be rewritten). A hint: no result depends on it.
template <bool kWrite = false, class T>
inline void prefetch(const T& entry) {
  const char* bytes = reinterpret_cast<const char*>(&entry);
  for (std::size_t line = 0; line < sizeof(T); line += 64) {
    __builtin_prefetch(bytes + line, kWrite ? 1 : 0);
  }
}

// Deterministic tangent basis of the unit normal n, right-handed (t2 = n x t1), with one division
// and no square root: Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 6(1), 2017).
// The same normal always gives the same basis. Manifold::tangent_impulse is expressed in it.
inline void tangent_basis(const Vec3& n, Vec3& t1, Vec3& t2) {
  const Real sign = n.z() >= 0 ? Real(1) : Real(-1);
  const Real a = Real(-1) / (sign + n.z());
  const Real b = n.x() * n.y() * a;
  t1 = Vec3(Real(1) + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  t2 = Vec3(b, sign + n.y() * n.y() * a, -n.y());
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
