// Stage 3, collide_pairs(): manifolds for every broadphase pair in parallel over fixed blocks,
// warm-start impulses matched by key and feature id, touching manifolds compacted in key order;
// pairs found apart skip their exact test while their motion cannot have closed the gap.
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>

#include "core/base/grow.hpp"
#include "core/base/heap_bytes.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"
#include "narrowphase/collide.hpp"

namespace elan::detail {

bool SeparatedPair::make(uint64_t key, const Separation& separation, const Vec3& position,
                         const Quat& rotation, Real step, SeparatedPair& out) {
  if (separation.kind == Separation::Kind::Unknown) return false;
  if (separation.kind == Separation::Kind::EdgePair) {
    if (!(separation.edge_a >= 0 && separation.edge_a <= 32767 && separation.edge_b >= 0 &&
          separation.edge_b <= 32767)) {
      return false;
    }
    out = SeparatedPair{};
    out.key = key;
    out.gap_bits = 0x80000000u;
    out.position[0] = int16_t(separation.edge_a);
    out.position[1] = int16_t(separation.edge_b);
    return true;
  }
  if (!(separation.gap > 0 && separation.gap <= std::numeric_limits<float>::max())) return false;
  if (!(step > 0 && step <= std::numeric_limits<Real>::max())) return false;
  const Vec3 steps = position / step;
  if (!(steps.cwiseAbs().maxCoeff() <= 32767)) return false;  // false for NaN too
  // The gap as a float rounded towards zero, its lowest four bits (2^-19 of it) then dropped.
  float gap = float(separation.gap);
  if (Real(gap) > separation.gap) gap = std::nextafter(gap, 0.0f);
  uint32_t bits = 0;
  std::memcpy(&bits, &gap, sizeof(bits));
  const PackedRotation packed = PackedRotation::pack(rotation);
  out.key = key;
  out.gap_bits = (bits & ~0xFu) | uint32_t(packed.bytes[6]) << 2 | uint32_t(separation.kind);
  for (int k = 0; k < 3; ++k) out.position[k] = int16_t(std::lrint(steps[k]));
  std::memcpy(out.rotation, packed.bytes, sizeof(out.rotation));
  return true;
}

Real SeparatedPair::gap() const {
  const uint32_t bits = gap_bits & ~0xFu;
  float gap = 0;
  std::memcpy(&gap, &bits, sizeof(gap));
  return Real(gap);
}

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
// capsules in a deep pile rocking. Their exact tests are the cheap closed forms anyway.
bool rolls(const Shape& s) {
  return s.type == ShapeType::Sphere || s.type == ShapeType::Capsule ||
         s.type == ShapeType::Cylinder;
}

// `relative`: B's centre of mass minus A's, in A's frame, now.
// On success `m` is the manifold carried along and `cache` holds the poses of now.
bool reuse_manifold(const Manifold& old, PairCache& cache, const Transform& xa, const Transform& xb,
                    const Vec3& relative, Manifold& m) {
  if ((relative - cache.exact_position).squaredNorm() > kCacheDistance * kCacheDistance) {
    return false;
  }
  const Quat rel_now = xa.rotation.conjugate() * xb.rotation;
  if (std::abs(rel_now.dot(cache.exact_rotation.unpack())) < kCacheCosHalfAngle) return false;
  const Quat turn_a = xa.rotation * cache.orientation_a.conjugate();  // since the last update
  const Quat turn_b = xb.rotation * cache.orientation_b.conjugate();
  const Vec3 normal_in_a = cache.orientation_a.conjugate() * old.normal;
  const Vec3 centres = xb.position - xa.position;
  m = old;  // key, bodies, impulses for the warm start
  m.normal = (xa.rotation * normal_in_a).normalized();
  carry_tangent_impulse(old.normal, old.tangent_impulse, m.normal, m.tangent_impulse);
  for (int k = 0; k < m.point_count; ++k) {
    ContactPoint& p = m.points[k];
    const ContactPoint& q = old.points[k];
    const Vec3 on_a = turn_a * q.anchor_a;  // the material points, from each centre now
    const Vec3 on_b = turn_b * cache.anchor_b(q);
    // Seen from A, the two material points' gap along A's normal changed by as much as their
    // separation vector did; it was zero: they were one point.
    const Vec3 gap_now = relative + xa.rotation.conjugate() * (on_b - on_a);
    p.separation = q.separation + normal_in_a.dot(gap_now);
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

// perf: two in three broadphase pairs of a settling pile do not touch (pile4k: 19k of 29k a step),
// and nearly all of them moved less in a step than their gap; skipping their tests took the
// collide stage from 6.6 to 4.9 ms a step on pile4k.
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
  const Real in_b = (q.conjugate() * p - q0.conjugate() * p0).norm() + step +
                    PackedRotation::kError * (p0.norm() + step) + chord * a.bounding_radius;
  return s.kind() == Separation::Kind::FaceOfB ? in_b : std::min(in_a, in_b);
}

uint64_t list_key(const ManifoldHead& m) {
  return m.key();
}
uint64_t list_key(const SeparatedPair& s) {
  return s.key;
}
uint64_t list_key(const PairCache& c) {
  return c.key;
}
uint64_t list_key(const ManifoldTail& t) {
  return t.key;
}
uint64_t list_key(uint64_t apart_key) {
  return apart_key;
}

bool ended(const ManifoldHead& m) {
  return m.point_count == 0;
}
bool ended(const SeparatedPair& s) {
  return s.kind() == Separation::Kind::Unknown;
}
// The lists kept beside the manifolds' (their tails, their poses) mark an entry that ended with
// a key no pair has (its first index is the lower).
constexpr uint64_t kEndedKey = ~uint64_t{0};
bool ended(const PairCache& c) {
  return c.key == kEndedKey;
}
bool ended(const ManifoldTail& t) {
  return t.key == kEndedKey;
}
bool ended(uint64_t apart_key) {
  return apart_key == kEndedKey;
}

// Files a pair the exact test found apart in one of the two lists of them (see collide_pairs):
// with what its rejection measured where an entry can hold it and the test is not a closed form
// (which costs about what checking the entry does), else by its key alone. `kept` and `by_key`
// are its entries in the two lists, if any: the one not used is ended. Returns the entries that
// ended: 1 for `kept`, 2 for `by_key`.
// perf: out of line, off the path of the touching pairs, so that the pair loop stays small enough
// for the compiler to inline its rotations (jolt_pyramid's collide stage ran 15 % longer inline).
[[gnu::noinline]] unsigned file_apart(uint64_t key, const Shape& a, const Shape& b,
                                      const Separation& separation, const Vec3& relative,
                                      const Quat& rotation, SeparatedPair* kept, uint64_t* by_key,
                                      ScratchVector<SeparatedPair>& added_kept,
                                      ScratchVector<uint64_t>& added_keys) {
  SeparatedPair s;
  if (!exact_test_is_closed_form(a, b) &&
      SeparatedPair::make(key, separation, relative, rotation, SeparatedPair::position_step(a, b),
                          s)) {
    if (kept != nullptr) {
      *kept = s;
    } else {
      added_kept.push_back(s);
    }
    if (by_key == nullptr) return 0;
    *by_key = kEndedKey;
    return 2;
  }
  if (by_key == nullptr) added_keys.push_back(key);
  if (kept == nullptr) return 0;
  kept->end();
  return 1;
}

// Before the blocks run: per-thread buffers emptied, and each block's range of the list found
// (block p owns the keys from its first pair's up to the next block's first pair's).
template <class T>
void begin_update(ListUpdate<T>& u, const std::vector<T>& list, std::span<const uint64_t> pairs,
                  std::size_t parts, StepScratch& step_scratch) {
  // Which thread takes which block changes from run to run, so every buffer gets the room the
  // largest needed: none grows (inside the scratch, leaving its old bytes unused) because the
  // schedule changed.
  if (u.added.size() < thread_slots()) u.added.resize(thread_slots());
  for (ScratchVector<T>& buffer : u.added) take_room(buffer, step_scratch, u.room);
  take_from(u.added_run, step_scratch, parts);
  take_from(u.start, step_scratch, parts + 1);
  take_from(u.live, step_scratch, parts);
  take_from(u.at, step_scratch, parts + 1);
  take_room(u.waiting, step_scratch, parts);
  u.start[0] = 0;
  u.start[parts] = list.size();
  for (std::size_t part = 1; part < parts; ++part) {
    u.start[part] =
        std::size_t(std::lower_bound(list.begin(), list.end(), pairs[part * kPairGrain],
                                     [](const T& x, uint64_t k) { return list_key(x) < k; }) -
                    list.begin());
  }
}

// After the join: the room for the next step, and the buffers back to the scratch.
template <class T>
void end_update(ListUpdate<T>& u) {
  std::size_t largest = 0;
  for (const ScratchVector<T>& buffer : u.added) largest = std::max(largest, buffer.size());
  u.room = largest + largest / 4;
  release(u.bounce);
  release(u.waiting);
  release(u.at);
  release(u.live);
  release(u.start);
  release(u.added_run);
  for (ScratchVector<T>& buffer : u.added) release(buffer);
}

// The join's move of one part: its live entries, merged in key order with its added ones, to
// their place from `at`. Through `bounce`, since the part's old and new places may overlap.
template <class T>
void place_part(std::vector<T>& list, std::size_t from, std::size_t to, std::span<const T> added,
                ScratchVector<T>& bounce, std::size_t at) {
  bounce.clear();
  auto next_added = added.begin();
  for (std::size_t i = from; i < to; ++i) {
    if (ended(list[i])) continue;
    for (; next_added != added.end() && list_key(*next_added) < list_key(list[i]); ++next_added) {
      bounce.push_back(*next_added);
    }
    bounce.push_back(list[i]);
  }
  bounce.insert(bounce.end(), next_added, added.end());
  std::copy(bounce.begin(), bounce.end(), list.begin() + std::ptrdiff_t(at));
}

// The join, serial: each part's live and added entries move to their final place, a prefix sum
// of the parts' counts, in one pass over the list with no second copy of it. Part p moves from
// [start[p], start[p+1]) to [at[p], at[p+1]); it can overwrite its left neighbour's old range
// only if it moves left (at[p] < start[p]), and its right neighbour's only if that one moves
// right (at[p+1] > start[p+1]), so each boundary says which side goes first, and the order is a
// chain: parts waiting for their right neighbour are stacked until it has moved.
template <class T>
void join(ListUpdate<T>& u, std::vector<T>& list, std::size_t parts, StepScratch& step_scratch) {
  ScratchVector<std::size_t>& at = u.at;
  at[0] = 0;
  for (std::size_t p = 0; p < parts; ++p) at[p + 1] = at[p] + u.live[p] + u.added_run[p].count;
  const std::size_t total = at[parts];
  auto unchanged = [&](std::size_t p) {
    return u.live[p] == u.start[p + 1] - u.start[p] && u.added_run[p].count == 0;
  };
  std::size_t largest = 0;  // of the parts that move through `bounce`
  for (std::size_t p = 0; p < parts; ++p) {
    if (!unchanged(p)) largest = std::max(largest, u.live[p] + u.added_run[p].count);
  }
  take_room(u.bounce, step_scratch, largest);
  // Long enough for the old entries and the new while parts move, grown by a quarter (grow_to):
  // a list keeps its largest size for good, and doubling left up to half of it unused. Each growth
  // holds the old list and the new at once and leaves the freed one in the allocator's heap, which
  // once (288-byte manifolds) made a quarter cost more peak RSS than doubling (52.8 against 43.2 MB
  // on pile10k). No longer: 300 steps of pile10k peak at 34.8 MB doubling, 34.7 by half and 34.0 by
  // a quarter; the two lists after 180 steps hold 889 B/body by half, 765 by a quarter.
  grow_to(list, std::max(list.size(), total));
  auto place = [&](std::size_t p) {
    const std::size_t from = u.start[p], to = u.start[p + 1];
    const auto& run = u.added_run[p];
    if (unchanged(p) && at[p] == from) return;
    // perf: a part that only shifts (most of them: an entry added or ended early in the list
    // moves all after it) is copied once, in the direction that reads each entry before it is
    // overwritten, not through `bounce`: on pile10k the join took 1.3 ms a step, serially.
    if (unchanged(p)) {
      const auto first = list.begin() + std::ptrdiff_t(from),
                 last = list.begin() + std::ptrdiff_t(to);
      if (at[p] < from) {
        std::copy(first, last, list.begin() + std::ptrdiff_t(at[p]));
      } else {
        std::copy_backward(first, last, list.begin() + std::ptrdiff_t(at[p + 1]));
      }
      return;
    }
    const std::span<const T> added(u.added[run.thread].data() + run.first, run.count);
    place_part(list, from, to, added, u.bounce, at[p]);
  };
  ScratchVector<std::size_t>& waiting = u.waiting;
  for (std::size_t p = 0; p < parts; ++p) {
    waiting.push_back(p);
    if (p + 1 < parts && at[p + 1] > u.start[p + 1]) continue;
    for (; !waiting.empty(); waiting.pop_back()) place(waiting.back());
  }
  list.resize(total);
}

}  // namespace

template <class T>
std::size_t ListUpdate<T>::heap_bytes() const {
  return detail::heap_bytes(added);
}
template struct ListUpdate<ManifoldHead>;
template struct ListUpdate<ManifoldTail>;
template struct ListUpdate<SeparatedPair>;
template struct ListUpdate<uint64_t>;
template struct ListUpdate<PairCache>;

void collide_pairs(std::span<const uint64_t> pairs, const BodyStore& bodies,
                   std::span<const Shape> shapes, const CollideSettings& settings,
                   std::span<const uint8_t> idle, CollideScratch& scratch,
                   std::vector<ManifoldHead>& contacts, std::vector<ManifoldTail>& tails,
                   ApartPairs& apart_pairs, std::vector<PairCache>& cached,
                   StepScratch* step_scratch) {
  if (step_scratch == nullptr) {
    if (!scratch.own) scratch.own = std::make_unique<StepScratch>();
    step_scratch = scratch.own.get();
    step_scratch->begin_phase();
  }
  const std::size_t n = pairs.size();
  // With no pairs there is one (empty) part, to carry what the lists hold.
  const std::size_t parts = std::max<std::size_t>(block_count(n, kPairGrain), 1);
  // One buffer of new keys per thread of the arena, not per block: a block's new entries are
  // one run in its thread's buffer, so only a step's new keys are held, not each block's most.
  ListUpdate<ManifoldHead>& mu = scratch.contacts;
  ListUpdate<ManifoldTail>& tu = scratch.tails;
  ListUpdate<SeparatedPair>& su = scratch.separated;
  ListUpdate<uint64_t>& ku = scratch.apart_keys;
  ListUpdate<PairCache>& cu = scratch.cached;
  std::vector<SeparatedPair>& separated = apart_pairs.separated;
  std::vector<uint64_t>& apart_keys = apart_pairs.keys;
  begin_update(mu, contacts, pairs, parts, *step_scratch);
  begin_update(tu, tails, pairs, parts, *step_scratch);
  begin_update(su, separated, pairs, parts, *step_scratch);
  begin_update(ku, apart_keys, pairs, parts, *step_scratch);
  begin_update(cu, cached, pairs, parts, *step_scratch);
  auto carried = [&](uint64_t key) {
    return !idle.empty() && idle[pair_first(key)] && idle[pair_second(key)];
  };
  // determinism: part p writes only its ranges of the five lists and one run of each of its
  // thread's buffers. An entry whose key is in a list is updated where it is; a key new to a list
  // goes to the run (which thread's buffer holds it changes nothing: the join reads runs in part
  // order); one that ends is marked (a manifold with point_count 0, which no live manifold has; a
  // separated pair of kind Unknown; an apart key, a tail or poses with kEndedKey). Nothing depends
  // on which thread ran a part. A key is touching (a head, perhaps a tail and poses) or apart (a
  // separated pair or an apart key), not both.
  for_blocks(parts, 1, [&](std::size_t part, std::size_t, std::size_t) {
    const std::size_t slot = thread_slot();
    ScratchVector<ManifoldHead>& added = mu.added[slot];
    ScratchVector<ManifoldTail>& added_tail = tu.added[slot];
    ScratchVector<SeparatedPair>& added_apart = su.added[slot];
    ScratchVector<uint64_t>& added_key = ku.added[slot];
    ScratchVector<PairCache>& added_cache = cu.added[slot];
    const std::size_t first_added = added.size(), first_tail = added_tail.size(),
                      first_apart = added_apart.size(), first_key = added_key.size(),
                      first_cache = added_cache.size();
    const std::size_t begin = std::min(n, part * kPairGrain);
    const std::size_t end = std::min(n, begin + kPairGrain);
    ManifoldHead* prev_it = contacts.data() + mu.start[part];
    ManifoldHead* const prev_end = contacts.data() + mu.start[part + 1];
    ManifoldTail* tail_it = tails.data() + tu.start[part];
    ManifoldTail* const tail_end = tails.data() + tu.start[part + 1];
    SeparatedPair* apart_it = separated.data() + su.start[part];
    SeparatedPair* const apart_end = separated.data() + su.start[part + 1];
    uint64_t* key_it = apart_keys.data() + ku.start[part];
    uint64_t* const key_end = apart_keys.data() + ku.start[part + 1];
    PairCache* cache_it = cached.data() + cu.start[part];
    PairCache* const cache_end = cached.data() + cu.start[part + 1];
    std::size_t dead = 0, dead_tail = 0, dead_apart = 0, dead_key = 0, dead_cache = 0;
    PolyhedronCache polyhedron_cache;
    // A manifold, its tail and its cached poses are carried together: a manifold with points is
    // in the list with its key's tail if it has more than one and its poses if it may reuse them.
    auto keep_if_carried = [&](ManifoldHead& old) {
      if (old.point_count == 0 || !carried(old.key())) {
        old.point_count = 0;
        ++dead;
      }
    };
    auto end_side = [&](auto& entry, std::size_t& dead_count) {
      entry.key = kEndedKey;
      ++dead_count;
    };
    auto keep_side_if_carried = [&](auto& entry, std::size_t& dead_count) {
      if (!carried(entry.key)) end_side(entry, dead_count);
    };
    auto end_apart = [&](SeparatedPair& s) {
      s.end();
      ++dead_apart;
    };
    auto end_key = [&](uint64_t& apart_key) {
      apart_key = kEndedKey;
      ++dead_key;
    };
    Manifold m, old;
    Separation separation;
    for (std::size_t i = begin; i < end; ++i) {
      const uint64_t key = pairs[i];
      // perf: the manifolds and tails two ahead, for writing. The solver stored their impulses by
      // half, so at 2 threads about half were last written by the other core; fetched only when
      // read, each of their lines cost a cross-core round trip on the chain of this loop.
      if (prev_end - prev_it > 2) prefetch<true>(prev_it[2]);
      if (tail_end - tail_it > 2) prefetch<true>(tail_it[2]);
      for (; prev_it != prev_end && prev_it->key() < key; ++prev_it) keep_if_carried(*prev_it);
      for (; tail_it != tail_end && tail_it->key < key; ++tail_it)
        keep_side_if_carried(*tail_it, dead_tail);
      for (; cache_it != cache_end && cache_it->key < key; ++cache_it) {
        keep_side_if_carried(*cache_it, dead_cache);
      }
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
      const Vec3 relative = xa.rotation.conjugate() * (xb.position - xa.position);
      ManifoldHead* same_key = (prev_it != prev_end && prev_it->key() == key) ? prev_it++ : nullptr;
      ManifoldTail* tail = (tail_it != tail_end && tail_it->key == key) ? tail_it++ : nullptr;
      // Last step's manifold of the pair, whole, if A and B are as they were.
      const bool has_old = same_key != nullptr && same_key->body_a == a;
      assert(same_key == nullptr || (same_key->point_count > 1) == (tail != nullptr));
      if (has_old) load_whole(*same_key, tail, old);
      // This step's manifold, `m`, in the lists.
      auto store = [&] {
        if (same_key == nullptr) {
          added.push_back(head_of(m));
        } else {
          store_head(m, *same_key);
        }
        if (m.point_count > 1) {
          if (tail == nullptr) {
            added_tail.push_back(tail_of(m));
          } else {
            store_tail(m, *tail);
          }
        } else if (tail != nullptr) {
          end_side(*tail, dead_tail);
        }
      };
      PairCache* cache = (cache_it != cache_end && cache_it->key == key) ? cache_it++ : nullptr;
      const bool cacheable = !rolls(shape_a) && !rolls(shape_b);
      if (has_old && old.point_count > 0 && cache != nullptr && cacheable &&
          reuse_manifold(old, *cache, xa, xb, relative, m)) {
        store();
        continue;
      }
      // perf: the lists of pairs found apart are walked past the pairs that reuse their points
      // (most of a resting pile's), which touched last step, so neither list has them.
      for (; apart_it != apart_end && apart_it->key < key; ++apart_it) end_apart(*apart_it);
      for (; key_it != key_end && *key_it < key; ++key_it) end_key(*key_it);
      SeparatedPair* apart = (apart_it != apart_end && apart_it->key == key) ? apart_it++ : nullptr;
      uint64_t* apart_key = (key_it != key_end && *key_it == key) ? key_it++ : nullptr;
      const Real approach =
          (bodies.linear_velocity(a) - bodies.linear_velocity(b)).norm() * settings.dt;
      const Real speculative = settings.speculative_distance + approach;
      const Quat rotation = xa.rotation.conjugate() * xb.rotation;
      if (apart != nullptr && apart->kind() == Separation::Kind::EdgePair) {
        if (edge_pair_separates(shape_a, xa, shape_b, xb, apart->edge_a(), apart->edge_b(),
                                speculative, polyhedron_cache)) {
          continue;  // the SAT would find this axis again, and reject the pair on it or earlier
        }
      } else if (apart != nullptr) {
        const Real slack =
            kSeparationSlack + kSeparationSlackPerMetre * (xa.position.cwiseAbs().maxCoeff() +
                                                           xb.position.cwiseAbs().maxCoeff());
        const Real step = SeparatedPair::position_step(shape_a, shape_b);
        if (closing(*apart, relative, rotation, shape_a, shape_b, step) <
            apart->gap() - speculative - slack) {
          continue;  // still apart: the exact test would reject it again
        }
      }
      collide(shape_a, xa, shape_b, xb, speculative, m, polyhedron_cache, separation);
      if (m.point_count == 0) {
        if (same_key != nullptr) keep_if_carried(*same_key);
        if (tail != nullptr) keep_side_if_carried(*tail, dead_tail);
        if (cache != nullptr) keep_side_if_carried(*cache, dead_cache);
        // Every pair found apart is in one of the two lists: the continuous stage's candidates.
        const unsigned ended_entries =
            file_apart(key, shape_a, shape_b, separation, relative, rotation, apart, apart_key,
                       added_apart, added_key);
        dead_apart += ended_entries & 1u;
        dead_key += ended_entries >> 1;
        continue;
      }
      if (apart != nullptr) end_apart(*apart);
      if (apart_key != nullptr) end_key(*apart_key);
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
        if (cache != nullptr) {
          *cache = c;
        } else {
          added_cache.push_back(c);
        }
      } else if (cache != nullptr) {
        end_side(*cache, dead_cache);
      }
      store();
    }
    for (; prev_it != prev_end; ++prev_it) keep_if_carried(*prev_it);
    for (; tail_it != tail_end; ++tail_it) keep_side_if_carried(*tail_it, dead_tail);
    for (; apart_it != apart_end; ++apart_it) end_apart(*apart_it);
    for (; key_it != key_end; ++key_it) end_key(*key_it);
    for (; cache_it != cache_end; ++cache_it) keep_side_if_carried(*cache_it, dead_cache);
    mu.live[part] = mu.start[part + 1] - mu.start[part] - dead;
    mu.added_run[part] = {uint32_t(slot), first_added, added.size() - first_added};
    tu.live[part] = tu.start[part + 1] - tu.start[part] - dead_tail;
    tu.added_run[part] = {uint32_t(slot), first_tail, added_tail.size() - first_tail};
    su.live[part] = su.start[part + 1] - su.start[part] - dead_apart;
    su.added_run[part] = {uint32_t(slot), first_apart, added_apart.size() - first_apart};
    ku.live[part] = ku.start[part + 1] - ku.start[part] - dead_key;
    ku.added_run[part] = {uint32_t(slot), first_key, added_key.size() - first_key};
    cu.live[part] = cu.start[part + 1] - cu.start[part] - dead_cache;
    cu.added_run[part] = {uint32_t(slot), first_cache, added_cache.size() - first_cache};
  });
  // The contact list's changes, before the join drops the ended manifolds: in part order, so in
  // key order. perf: only the parts that lost a manifold are read again.
  scratch.ended.clear();
  scratch.began.clear();
  for (std::size_t p = 0; p < parts; ++p) {
    if (mu.live[p] < mu.start[p + 1] - mu.start[p]) {
      for (std::size_t i = mu.start[p]; i < mu.start[p + 1]; ++i) {
        if (ended(contacts[i])) scratch.ended.push_back({contacts[i].body_a, contacts[i].body_b});
      }
    }
    const auto& run = mu.added_run[p];
    const ScratchVector<ManifoldHead>& added = mu.added[run.thread];
    for (std::size_t i = run.first; i < run.first + run.count; ++i) {
      scratch.began.push_back(added[i].key());
    }
  }
  // determinism: the lists are joined apart (disjoint data), each in part order.
  tbb::parallel_invoke([&] { join(mu, contacts, parts, *step_scratch); },
                       [&] { join(tu, tails, parts, *step_scratch); },
                       [&] { join(su, separated, parts, *step_scratch); },
                       [&] { join(ku, apart_keys, parts, *step_scratch); },
                       [&] { join(cu, cached, parts, *step_scratch); });
  end_update(mu);
  end_update(tu);
  end_update(su);
  end_update(ku);
  end_update(cu);
  trim_spike(scratch.ended, scratch.ended_trim);
  trim_spike(scratch.began, scratch.began_trim);
}

}  // namespace elan::detail
