// SPDX-License-Identifier: MIT
// The collide stage, collide_pairs(): manifolds for every broadphase pair in parallel over fixed
// blocks, warm-start impulses matched by key and feature id, touching manifolds compacted in key
// order; pairs found apart skip their exact test while their motion cannot have closed the gap.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <span>

#include "core/base/deep_overlap.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"
#include "core/base/rotate.hpp"
#include "narrowphase/collide.hpp"
#include "narrowphase/composite.hpp"
#include "narrowphase/deep_contact.hpp"

namespace elan::detail {

namespace {

// perf: a block of pairs is one task; big enough to amortise scheduling, small enough to balance
// pairs of very different cost (box-box next to hull-hull).
constexpr std::size_t kPairGrain = 64;

// Copies impulses from the previous step's manifold with the same key into `m`, point by point
// where the feature ids agree. A point whose id has no match takes the impulses of the previous
// point nearest to it within kMatchDistance: when two faces tie for reference (a box resting
// level on a large ground) the clipper may swap reference and incident face from one step to
// the next, which renames the same physical points; matching them by position keeps the warm
// start (Jolt's contact cache matches by position alone). A manifold whose A/B order flipped (a
// motion type changed) or whose normal turned gets no warm start.
constexpr Real kMatchDistance = Real(0.02);  // m
constexpr Real kMatchNormalCos = Real(0.95);

void warm_start(const Manifold& old, Manifold& m) {
  if (old.body_a != m.body_a || old.normal.dot(m.normal) < kMatchNormalCos) return;
  carry_tangent_impulse(old.normal, old.tangent_impulse, m.normal, m.tangent_impulse);
  m.twist_impulse = old.twist_impulse;
  for (int i = 0; i < m.point_count; ++i) {
    ContactPoint& p = m.points[i];
    int match = -1;
    Real best = kMatchDistance * kMatchDistance;
    for (int j = 0; j < old.point_count; ++j) {
      if (old.points[j].feature_id == p.feature_id) {
        match = j;
        break;
      }
      const Real d2 = (old.points[j].anchor_a - p.anchor_a).squaredNorm();
      if (d2 < best) {
        best = d2;
        match = j;
      }
    }
    if (match < 0) continue;
    p.normal_impulse = old.points[match].normal_impulse;
  }
}

// Body pair cache (Jolt's): while B's pose relative to A stays within 1 mm and 2 degrees of the
// pose of the last exact test, the manifold is carried along with the bodies instead of running
// the exact test again. Each step carries it from the poses of the step before; the tolerance is
// measured against the exact test, so a string of reuses cannot drift from it. The tolerances
// are Jolt's defaults (PhysicsSettings::mBodyPairCacheMaxDeltaPositionSq and
// mBodyPairCacheCosMaxDeltaRotationDiv2). The exact test's rotation is kept packed: within
// 3.74e-5 of the true one, it moves the edge of the 2 degree cone by less than 0.01 degree.
constexpr Real kCacheDistance = Real(1e-3);            // m
constexpr Real kCacheCosHalfAngle = Real(0.99984770);  // cos(1 degree): 2 degrees

// A round body's contact point does not travel with its material as it turns (a rolling
// sphere touches the ground under its centre). Carried with the body, a cached point would
// drift off the line of centres by r * angle, and the normal force there would turn the sphere
// further the way it already turned (torque lambda r sin(angle)): a pump that kept spheres and
// capsules in a deep pile rocking. Their exact tests are the cheap closed forms anyway. A compound
// rolls on a round part.
bool rolls(const Shape& s) {
  return s.type == ShapeType::Sphere || s.type == ShapeType::Capsule ||
         s.type == ShapeType::Cylinder || has_round_part(s);
}

// `relative`: B's centre of mass minus A's, in A's frame, now. `m`: last step's manifold.
// On success `m` is the manifold carried along and `cache` holds the poses of now.
// perf: inline in the pair loop (the path of most of a resting pile's pairs), where its
// rotations share the loop's; and in place: a copy of the manifold just loaded read it back in
// wider pieces than it was written (a failed store forwarding).
[[gnu::always_inline]] inline bool reuse_manifold(Manifold& m, PairCache& cache,
                                                  const Transform& xa, const Transform& xb,
                                                  const Vec3& relative) {
  if ((relative - cache.exact_position).squaredNorm() > kCacheDistance * kCacheDistance) {
    return false;
  }
  const Quat rel_now = xa.rotation.conjugate() * xb.rotation;
  if (std::abs(rel_now.dot(cache.exact_rotation.unpack())) < kCacheCosHalfAngle) return false;
  const Quat turn_a = xa.rotation * cache.orientation_a.conjugate();  // since the last update
  const Quat turn_b = xb.rotation * cache.orientation_b.conjugate();
  const Vec3 old_normal = m.normal;
  const Vec3 normal_in_a = rotate(cache.orientation_a.conjugate(), old_normal);
  const Vec3 centres = xb.position - xa.position;
  // The key, the bodies and the impulses stay, for the warm start.
  m.normal = rotate(xa.rotation, normal_in_a).normalized();
  carry_tangent_impulse(old_normal, m.tangent_impulse, m.normal, m.tangent_impulse);
  for (int k = 0; k < m.point_count; ++k) {
    ContactPoint& p = m.points[k];
    const Vec3 on_a = rotate(turn_a, p.anchor_a);  // the material points, from each centre now
    const Vec3 on_b = rotate(turn_b, cache.anchor_b(p));
    // Seen from A, the two material points' gap along A's normal changed by as much as their
    // separation vector did; it was zero: they were one point.
    const Vec3 gap_now = relative + rotate(xa.rotation.conjugate(), on_b - on_a);
    p.separation = p.separation + normal_in_a.dot(gap_now);
    // Both arms reach one world point, midway between the material points: once the bodies
    // have slid or turned they part (a 1 m cube turned 0.5 degree moves its corner 4 mm), and
    // the two halves of an impulse acting at different points would form a couple.
    p.anchor_a = Real(0.5) * (on_a + centres + on_b);
  }
  cache.orientation_a = xa.rotation;
  cache.orientation_b = xb.rotation;
  cache.relative_position = relative;
  return true;
}

// perf: about two in three broadphase pairs of a settling pile do not touch, and nearly all of
// them moved less in a step than their gap, so most exact tests of the collide stage are skipped.
//
// Tolerance of the separation cache, m, plus a part per metre of coordinate size: the exact
// tests' rounding near the origin and GJK's relative tolerance (1e-5 of the distance) are far
// below it, and coordinates far from the origin round to a step of about eps * |x|. (The stored
// rotation's error is bounded in closing().)
constexpr Real kSeparationSlack = Real(1e-3);
constexpr Real kSeparationSlackPerMetre = 64 * std::numeric_limits<Real>::epsilon();

// How much of a cached gap the motion since its test could have closed. B's point y sits at
// q y + p in A's frame (q, p: B's rotation and centre relative to A), so it moved by at most
// |p - p0| plus the chord of the relative turn, 2 sin(angle / 2) |y| = 2 |vec(q q0^-1)| |y|, with
// |y| no more than B's bounding radius. A's points in B's frame likewise, from A's centre
// p' = -q^-1 p and A's bounding radius. A distance is bounded by either.
//
// q0 comes back from its packed form within PackedRotation::kError: the chord, and q0's turn of
// p0, are each off by at most that times the radius it turns. p0 comes back within (sqrt 3 / 2)
// `step` (each coordinate rounded to the nearest step): `step` is added to each motion.
Real closing(const SeparatedPair& s, const Vec3& p, const Quat& q, const Shape& a, const Shape& b,
             Real step) {
  const Quat q0 = s.rotation_value();
  const Vec3 p0 = s.position_at(step);
  const Real chord = 2 * (q * q0.conjugate()).vec().norm() + PackedRotation::kError;
  const Real in_a = (p - p0).norm() + step + chord * b.bounding_radius;
  if (s.kind() == Separation::Kind::FaceOfA) return in_a;
  const Real in_b = (rotate(q.conjugate(), p) - rotate(q0.conjugate(), p0)).norm() + step +
                    PackedRotation::kError * (p0.norm() + step) + chord * a.bounding_radius;
  return s.kind() == Separation::Kind::FaceOfB ? in_b : std::min(in_a, in_b);
}

// Whether the separation cache's entry `kept` proves the pair still apart: the exact test would
// reject it again, so skipping it gives the same bits. `relative` and `rotation`: B's centre and
// rotation relative to A's now; `speculative`: the exact test's distance.
// perf: inline in the pair loop, as reuse_manifold.
[[gnu::always_inline]] inline bool still_apart(const SeparatedPair& kept, const Shape& shape_a,
                                               const Transform& xa, const Shape& shape_b,
                                               const Transform& xb, const Vec3& relative,
                                               const Quat& rotation, Real speculative,
                                               PolyhedronCache& polyhedron_cache) {
  if (kept.kind() == Separation::Kind::EdgePair) {
    // The SAT would find this axis again, and reject the pair on it or earlier.
    return edge_pair_separates(shape_a, xa, shape_b, xb, kept.edge_a(), kept.edge_b(), speculative,
                               polyhedron_cache);
  }
  const Real slack = kSeparationSlack +
                     kSeparationSlackPerMetre *
                         (xa.position.cwiseAbs().maxCoeff() + xb.position.cwiseAbs().maxCoeff());
  const Real step = SeparatedPair::position_step(shape_a, shape_b);
  return closing(kept, relative, rotation, shape_a, shape_b, step) <
         kept.gap() - speculative - slack;
}

// The separation cache's entry for a pair the exact test found apart: what its rejection
// measured, where an entry can hold it and the test is not a closed form (which costs about what
// checking the entry does). False: the pair is kept by its key alone.
// perf: out of line, off the path of the touching pairs, so that the pair loop stays small enough
// for the compiler to inline its rotations.
[[gnu::noinline]] bool separated_entry(uint64_t key, const Shape& a, const Shape& b,
                                       const Separation& separation, const Vec3& relative,
                                       const Quat& rotation, SeparatedPair& out) {
  return !exact_test_is_closed_form(a, b) &&
         SeparatedPair::make(key, separation, relative, rotation,
                             SeparatedPair::position_step(a, b), out);
}

// The deep test of the deep-pair budget (deep_overlap.hpp), on the poses the budget saw.
bool is_deep_pair(const BodyStore& bodies, uint32_t a, const Shape& shape_a, const Transform& xa,
                  uint32_t b, const Shape& shape_b, const Transform& xb) {
  if (!bodies.is_dynamic(a) || !bodies.is_dynamic(b)) return false;
  const Real ra = inner_ball_radius(shape_a);
  const Real rb = inner_ball_radius(shape_b);
  return ra > 0 && rb > 0 && inner_balls_deep(xa.position, ra, xb.position, rb);
}

}  // namespace

void collide_pairs(std::span<const uint64_t> pairs, const BodyStore& bodies,
                   std::span<const Shape> shapes, const CollideSettings& settings,
                   std::span<const uint8_t> idle, ContactStore& contacts,
                   StepScratch* step_scratch) {
  const std::size_t n = pairs.size();
  // With no pairs there is one (empty) part, to carry what the lists hold.
  const std::size_t parts = std::max<std::size_t>(block_count(n, kPairGrain), 1);
  contacts.begin_step(pairs, kPairGrain, parts, step_scratch);
  // determinism: part p reads and writes only its block of the store (ContactStore::Block).
  for_blocks(parts, 1, [&](std::size_t part, std::size_t, std::size_t) {
    ContactStore::Block block(contacts, part, idle);
    const std::size_t begin = std::min(n, part * kPairGrain);
    const std::size_t end = std::min(n, begin + kPairGrain);
    PolyhedronCache polyhedron_cache;
    Manifold m, old;
    Separation separation;
    for (std::size_t i = begin; i < end; ++i) {
      const uint64_t key = pairs[i];
      // Look up: last step's manifold of the pair, its tail and its poses.
      const ContactStore::Touching last = block.look_up(key);
      uint32_t a = pair_first(key), b = pair_second(key);
      // The static or kinematic body, if any, is B (ARCHITECTURE.md, determinism rule 4).
      if (!bodies.is_dynamic(a) && bodies.is_dynamic(b)) std::swap(a, b);
      m.body_a = a;
      m.body_b = b;
      m.point_count = 0;
      const Shape& shape_a = shapes[bodies.shape[a]];
      const Shape& shape_b = shapes[bodies.shape[b]];
      const Transform xa{bodies.position(a), bodies.orientation(a)};
      const Transform xb{bodies.position(b), bodies.orientation(b)};
      const Vec3 relative = rotate(xa.rotation.conjugate(), xb.position - xa.position);
      // Last step's manifold of the pair, whole, if A and B are as they were.
      const bool has_old = last.head != nullptr && last.head->body_a == a;
      assert(last.head == nullptr || (last.head->point_count > 1) == (last.tail != nullptr));
      if (has_old) load_whole(*last.head, last.tail, old);
      // Try the pair cache: the points carried with the bodies.
      const bool cacheable = !rolls(shape_a) && !rolls(shape_b);
      if (has_old && old.point_count > 0 && last.cache != nullptr && cacheable &&
          reuse_manifold(old, *last.cache, xa, xb, relative)) {
        block.file_manifold(old, last);
        continue;
      }
      // Try the separation cache: still apart if the motion since cannot have closed the gap.
      const ContactStore::Apart apart = block.look_up_apart(key);
      const Vec3 displacement =
          (bodies.linear_velocity(a) - bodies.linear_velocity(b)) * settings.dt;
      const Real approach =
          (bodies.linear_velocity(a) - bodies.linear_velocity(b)).norm() * settings.dt;
      const Real speculative = settings.speculative_distance + approach;
      const Quat rotation = xa.rotation.conjugate() * xb.rotation;
      if (apart.separated != nullptr &&
          still_apart(*apart.separated, shape_a, xa, shape_b, xb, relative, rotation, speculative,
                      polyhedron_cache)) {
        continue;
      }
      // Run the exact test, or, in a step whose deep-pair budget bit (bodies spawned into each
      // other), for a deep pair the contact of constant cost (deep_contact.hpp).
      if (settings.deep_contacts && is_deep_pair(bodies, a, shape_a, xa, b, shape_b, xb)) {
        deep_contact(shape_a, xa, a, shape_b, xb, b, m);
      } else {
        const SurfaceMotion motion{displacement, settings.speculative_distance};
        collide(shape_a, xa, shape_b, xb, speculative, m, polyhedron_cache, separation, &motion);
      }
      // File the result: apart (every pair found apart is filed, the continuous stage's
      // candidates) ...
      if (m.point_count == 0) {
        block.let_go(last);
        SeparatedPair entry;
        const bool measured =
            separated_entry(key, shape_a, shape_b, separation, relative, rotation, entry);
        block.file_apart(key, measured ? &entry : nullptr, apart);
        continue;
      }
      // ... or touching, warm-started from last step's manifold, with the poses of this test.
      for (int k = 0; k < m.point_count; ++k) m.points[k].normal_impulse = 0;
      m.tangent_impulse[0] = m.tangent_impulse[1] = 0;
      m.twist_impulse = 0;
      if (has_old) warm_start(old, m);
      if (cacheable) {
        PairCache c;
        c.key = key;
        c.orientation_a = xa.rotation;
        c.orientation_b = xb.rotation;
        c.relative_position = relative;
        c.exact_position = relative;
        c.exact_rotation = PackedRotation::pack(rotation);
        block.file_cache(&c, last, apart);
      } else {
        block.file_cache(nullptr, last, apart);
      }
      block.file_manifold(m, last);
    }
    block.close();
  });
  contacts.finish_step();
}

}  // namespace elan::detail
