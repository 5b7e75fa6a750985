// SPDX-License-Identifier: MIT
// ContactStore: the contact state kept from step to step (manifolds, the body pair cache, the
// separation cache) and the few operations the step needs on it: look up a pair's entries, file
// this step's result, finish the step (the merge that yields the begin/end changes).
#pragma once

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/base/contact.hpp"
#include "core/base/grow.hpp"
#include "core/base/packed_rotation.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"
#include "core/base/shape.hpp"
#include "core/base/step_scratch.hpp"
#include "narrowphase/separation.hpp"
#include "narrowphase/sorted_list_update.hpp"

namespace elan::detail {

// A pair the exact test found apart, what the rejection measured, and B's pose relative to A at
// that test: the reference the motion since is measured from. 24 bytes (a pile keeps about three
// of these a body): the rotation is packed into six bytes (PackedRotation's kept components), the
// position into 16-bit steps of the pair's size (position_step), and the separation's kind and
// the rotation's left-out component take the gap's four lowest bits. Each code rounds so that
// closing() still over-estimates the motion: the gap comes back a little smaller, and the
// position's and rotation's errors are added to the motion.
struct SeparatedPair {
  uint64_t key = 0;
  uint32_t gap_bits = 0;     // Separation::gap as a float, the lowest four bits replaced by tags
  int16_t position[3] = {};  // B's centre of mass minus A's, in A's frame: steps of position_step
  uint8_t rotation[6] = {};  // A's frame to B's (A^-1 B), PackedRotation's kept components

  // The step of the position code, m: 2 (r_a + r_b) / 32767 for the shapes' bounding radii, so
  // that the centres of any pair whose boxes overlap, and then some, are within range.
  static Real position_step(const Shape& a, const Shape& b) {
    return 2 * (a.bounding_radius + b.bounding_radius) / 32767;
  }
  // The entry, or false (`out` untouched) where the codes cannot hold it: an unknown kind, a gap
  // that is not positive and finite, a centre out of the position code's range, an edge index
  // past int16.
  static bool make(uint64_t key, const Separation& separation, const Vec3& position,
                   const Quat& rotation, Real step, SeparatedPair& out);

  // An EdgePair entry (the gap's sign bit set, which no kept gap has) holds the two edges in
  // position[0] and [1] and nothing else (no gap: gap() is -0).
  Separation::Kind kind() const {
    return gap_bits >> 31 ? Separation::Kind::EdgePair : Separation::Kind(gap_bits & 3u);
  }
  int edge_a() const { return position[0]; }
  int edge_b() const { return position[1]; }
  // m: at most the measured gap.
  Real gap() const;
  Vec3 position_at(Real step) const {
    return step * Vec3(Real(position[0]), Real(position[1]), Real(position[2]));
  }
  Quat rotation_value() const { return PackedRotation::unpack(rotation, int(gap_bits >> 2 & 3u)); }
  // Marks the entry as ended (kind Unknown).
  void end() { gap_bits = 0; }
};
static_assert(sizeof(Real) != 4 || sizeof(SeparatedPair) == 24, "SeparatedPair: 24 bytes in float");

// The lists kept beside the manifolds' (their tails, their poses) and the apart keys mark an
// entry that ended with a key no pair has (its first index is the lower).
inline constexpr uint64_t kEndedKey = ~uint64_t{0};

// The store's entry types as sorted lists (sorted_list_update.hpp): how each is keyed, and how a
// step marks one that ended.
template <>
struct ListEntry<ManifoldHead> {
  static uint64_t key(const ManifoldHead& m) { return m.key(); }
  static bool ended(const ManifoldHead& m) { return m.point_count == 0; }
};
template <>
struct ListEntry<ManifoldTail> {
  static uint64_t key(const ManifoldTail& t) { return t.key; }
  static bool ended(const ManifoldTail& t) { return t.key == kEndedKey; }
};
template <>
struct ListEntry<PairCache> {
  static uint64_t key(const PairCache& c) { return c.key; }
  static bool ended(const PairCache& c) { return c.key == kEndedKey; }
};
template <>
struct ListEntry<SeparatedPair> {
  static uint64_t key(const SeparatedPair& s) { return s.key; }
  static bool ended(const SeparatedPair& s) { return s.kind() == Separation::Kind::Unknown; }
};
template <>
struct ListEntry<uint64_t> {
  static uint64_t key(uint64_t apart_key) { return apart_key; }
  static bool ended(uint64_t apart_key) { return apart_key == kEndedKey; }
};

// The pairs the collide stage found apart this step, in key order in each list: the continuous
// stage's candidates (a pair with a manifold had its speculative contact in the solve).
struct ApartCandidates {
  std::span<const SeparatedPair> separated;
  std::span<const uint64_t> keys;
};

// Five lists sorted by pair key, kept from step to step:
//   heads      one per touching manifold (or carried: see Block), its first point;
//   tails      the points past the first of the heads with more than one;
//   pair_cache the body pair cache's poses of the heads that may reuse their points;
//   separated  pairs found apart with what proves them apart (the separation cache);
//   apart_keys the other pairs found apart, by key alone.
// A key is touching (a head, perhaps a tail and poses) or apart (separated or an apart key),
// never both. Keys are dense body indices (make_pair_key): see remove_body.
//
// A step goes through it as begin_step, one Block per fixed block of the step's sorted pairs (in
// parallel), finish_step: every list is updated in place by one sorted-list merge
// (sorted_list_update.hpp), so no second copy of any is held (Box2D v3 and Jolt keep their
// contacts in place too; Jolt's ContactConstraintManager has the same three operations:
// GetContactsFromCache, AddBodyPair, FinalizeContactCache).
class ContactStore {
 public:
  // Last step's entries of a key that touched: its head, the head's tail if it has more than one
  // point, its poses if it may reuse them (each null if absent).
  struct Touching {
    ManifoldHead* head = nullptr;
    ManifoldTail* tail = nullptr;
    PairCache* cache = nullptr;
  };
  // Last step's entries of a key found apart (at most one is set).
  struct Apart {
    SeparatedPair* separated = nullptr;
    uint64_t* key = nullptr;
  };
  class Block;

  // --- the step ---

  // Before the blocks: each block's ranges of the lists found. Block p owns the keys from
  // pairs[p * grain] up to the next block's first. The merge's buffers are taken from
  // `step_scratch` in its current phase and given back by finish_step (none: from a scratch of
  // the store's own).
  void begin_step(std::span<const uint64_t> pairs, std::size_t grain, std::size_t parts,
                  StepScratch* step_scratch);
  // After the blocks: the changes to the manifolds (began, ended) recorded, then each list's
  // entries that ended dropped and its new ones merged in, in key order.
  void finish_step();

  // --- reading ---

  std::span<ManifoldHead> heads() { return heads_; }
  std::span<const ManifoldHead> heads() const { return heads_; }
  std::span<ManifoldTail> tails() { return tails_; }
  std::span<const ManifoldTail> tails() const { return tails_; }
  std::span<const PairCache> pair_cache() const { return cache_; }
  std::size_t size() const { return heads_.size(); }
  ApartCandidates continuous_candidates() const { return {separated_, apart_keys_}; }
  // What the last step changed in the manifolds, each in key order. `ended`: the manifolds that
  // were in the store and are not any more; `began`: the keys new to it. Every manifold the
  // store holds has points, so these are the pairs that stopped and started touching (the
  // contact events).
  std::span<const ContactRecord> ended() const { return merge_.ended; }
  std::span<const uint64_t> began() const { return merge_.began; }

  // Every manifold whole, in key order, with its poses (null if it keeps none): f(m, cache).
  template <class F>
  void for_each_manifold(F&& f) const {
    std::size_t tail = 0, cache = 0;
    for (const ManifoldHead& head : heads_) {
      const Manifold m = whole_at(head, tails_, tail);
      f(m, find_beside(std::span<const PairCache>(cache_), cache, m.key()));
    }
  }
  // The whole manifolds, in key order.
  std::vector<Manifold> manifolds() const { return whole_list(heads_, tails_); }

  // --- changes outside the step ---

  // Rebuilds the store from whole manifolds and the poses of those that keep them, both in key
  // order; the separation cache from `separated` and `apart_keys` (a snapshot keeps none: it is
  // only a cache). The last step's changes are forgotten.
  void restore(std::span<const Manifold> manifolds, std::span<const PairCache> cache,
               std::span<const SeparatedPair> separated = {},
               std::span<const uint64_t> apart_keys = {});
  // The same one manifold at a time, into the store's own buffers (no allocation once they have
  // grown): begin_restore(count), then restore_manifold(k, ...) for k = 0..count-1 in key order.
  // The separation cache is forgotten.
  void begin_restore(std::size_t count);
  void restore_manifold(std::size_t k, const Manifold& m, const PairCache* cache) {
    heads_[k] = head_of(m);
    if (m.point_count > 1) tails_.push_back(tail_of(m));
    if (cache != nullptr) cache_.push_back(*cache);
  }

  // Body `index` is removed and the last body, `last`, takes its index (BodyStore::swap_remove).
  // Its manifolds are dropped, each passed to dropped(head) first; those of `last` are renamed
  // to `index` and every list re-sorted by key. The separation cache starts over.
  //
  // Keys stay dense body indices, renamed here, rather than stable ids: the pair list, the
  // manifolds and so the solver's order are sorted by key, and keying by id would change the
  // order, and with it every result's bits. A rename touches only a destroy, never a step.
  template <class F>
  void remove_body(uint32_t index, uint32_t last, F&& dropped);

  // Forgets the separation cache (it names bodies by index; a rollback restores poses it was not
  // measured at). Nothing else changes: it is only a cache.
  void clear_apart() {
    separated_.clear();
    apart_keys_.clear();
  }

  std::size_t heap_bytes() const;
  // The bytes the merge's per-thread buffers hold: between steps none, as they are the step
  // scratch's (taken in begin_step, given back in finish_step).
  std::size_t step_buffer_bytes() const;

 private:
  // The merge's state between steps (the buffers' room) and its output, the changes.
  struct Merge {
    ListUpdate<ManifoldHead> heads;
    ListUpdate<ManifoldTail> tails;
    ListUpdate<PairCache> cache;
    ListUpdate<SeparatedPair> separated;
    ListUpdate<uint64_t> apart_keys;
    std::vector<ContactRecord> ended;
    std::vector<uint64_t> began;
    SpikeTrim ended_trim, began_trim;  // a new pile begins every pair at once
    std::size_t parts = 0;
    StepScratch* step_scratch = nullptr;
    std::unique_ptr<StepScratch> own;  // for the new-key buffers when the caller gives no scratch
  };

  // Drops the entries of `list` that name `index`, renames `last` to `index` in the others and
  // re-sorts if any was renamed (the lists kept beside the heads, keyed by `key`).
  template <class T>
  static void rename_beside(std::vector<T>& list, uint32_t index, uint32_t last, bool resort);

  std::vector<ManifoldHead> heads_;
  std::vector<ManifoldTail> tails_;
  std::vector<PairCache> cache_;
  std::vector<SeparatedPair> separated_;
  std::vector<uint64_t> apart_keys_;
  Merge merge_;
};

// One block's walk of the store during a step: its key range of every list, in key order,
// pair by pair (the pairs of the block, ascending). For each pair the caller looks up its last
// entries (look_up, then look_up_apart), then files its result (file_manifold and file_cache for
// a touching pair, let_go and file_apart for one found apart); close() when the block is done.
// Entries of keys the block passes without a pair end, but for those carried: a manifold whose
// two bodies are both flagged in `idle` (the world flags static and sleeping bodies, which the
// broadphase does not pair) is kept as it is, with its tail and poses, so a sleeping island keeps
// its contacts and wakes warm-started. An empty `idle` carries nothing.
//
// determinism: a block writes only its ranges of the five lists and one run of each of its
// thread's buffers; an entry that ends is marked (ListEntry<T>::ended), a key new to a list goes
// to the run. Nothing depends on which thread ran the block.
class ContactStore::Block {
 public:
  Block(ContactStore& store, std::size_t part, std::span<const uint8_t> idle)
      : store_(store),
        part_(part),
        slot_(thread_slot()),
        idle_(idle),
        added_head_(store.merge_.heads.added[slot_]),
        added_tail_(store.merge_.tails.added[slot_]),
        added_cache_(store.merge_.cache.added[slot_]),
        added_separated_(store.merge_.separated.added[slot_]),
        added_key_(store.merge_.apart_keys.added[slot_]),
        first_head_(added_head_.size()),
        first_tail_(added_tail_.size()),
        first_cache_(added_cache_.size()),
        first_separated_(added_separated_.size()),
        first_key_(added_key_.size()) {
    const Merge& u = store.merge_;
    head_ = store.heads_.data() + u.heads.start[part];
    head_end_ = store.heads_.data() + u.heads.start[part + 1];
    tail_ = store.tails_.data() + u.tails.start[part];
    tail_end_ = store.tails_.data() + u.tails.start[part + 1];
    cache_ = store.cache_.data() + u.cache.start[part];
    cache_end_ = store.cache_.data() + u.cache.start[part + 1];
    separated_ = store.separated_.data() + u.separated.start[part];
    separated_end_ = store.separated_.data() + u.separated.start[part + 1];
    key_ = store.apart_keys_.data() + u.apart_keys.start[part];
    key_end_ = store.apart_keys_.data() + u.apart_keys.start[part + 1];
  }

  // Last step's touching entries of `key` (above every key looked up before), for rewriting in
  // place. The touching entries of the keys passed on the way end, unless carried.
  Touching look_up(uint64_t key) {
    // perf: the manifolds and tails two ahead, for writing. The solver stored their impulses by
    // half, so at 2 threads about half were last written by the other core; fetched only when
    // read, each of their lines cost a cross-core round trip on the chain of this loop.
    if (head_end_ - head_ > 2) prefetch<true>(head_[2]);
    if (tail_end_ - tail_ > 2) prefetch<true>(tail_[2]);
    for (; head_ != head_end_ && head_->key() < key; ++head_) let_go_head(*head_);
    for (; tail_ != tail_end_ && tail_->key < key; ++tail_) let_go_beside(*tail_, dead_tail_);
    for (; cache_ != cache_end_ && cache_->key < key; ++cache_) {
      let_go_beside(*cache_, dead_cache_);
    }
    Touching t;
    t.head = (head_ != head_end_ && head_->key() == key) ? head_++ : nullptr;
    t.tail = (tail_ != tail_end_ && tail_->key == key) ? tail_++ : nullptr;
    t.cache = (cache_ != cache_end_ && cache_->key == key) ? cache_++ : nullptr;
    return t;
  }

  // Last step's apart entries of `key` (the same key as the last look_up). The apart entries of
  // the keys passed on the way end. perf: the apart lists are walked past the pairs that reuse
  // their points (most of a resting pile's) only when needed, and those touched last step, so
  // neither list has them.
  Apart look_up_apart(uint64_t key) {
    for (; separated_ != separated_end_ && separated_->key < key; ++separated_) {
      end_separated(*separated_);
    }
    for (; key_ != key_end_ && *key_ < key; ++key_) end_key(*key_);
    Apart a;
    a.separated = (separated_ != separated_end_ && separated_->key == key) ? separated_++ : nullptr;
    a.key = (key_ != key_end_ && *key_ == key) ? key_++ : nullptr;
    return a;
  }

  // This step's manifold `m` (with points) of a pair whose last entries are `old`: its head, and
  // its tail if it has more than one point, rewritten in place or added.
  void file_manifold(const Manifold& m, const Touching& old) {
    dead_tail_ += file_manifold_entries(m, old, added_head_, added_tail_);
  }
  // The poses of a touching pair after its exact test: `cache`, or none (null: it may not reuse
  // its points). Its apart entries, `apart`, end: it touches.
  void file_cache(const PairCache* cache, const Touching& old, const Apart& apart) {
    if (apart.separated != nullptr) end_separated(*apart.separated);
    if (apart.key != nullptr) end_key(*apart.key);
    if (cache != nullptr) {
      if (old.cache != nullptr) {
        *old.cache = *cache;
      } else {
        added_cache_.push_back(*cache);
      }
    } else if (old.cache != nullptr) {
      end_beside(*old.cache, dead_cache_);
    }
  }

  // A pair that does not touch this step: its touching entries end, unless carried.
  void let_go(const Touching& old) {
    if (old.head != nullptr) let_go_head(*old.head);
    if (old.tail != nullptr) let_go_beside(*old.tail, dead_tail_);
    if (old.cache != nullptr) let_go_beside(*old.cache, dead_cache_);
  }
  // A pair found apart, filed in one of the two apart lists: `entry` if given (what its
  // rejection measured), else by its key alone. Its entry in the other list, if any, ends.
  void file_apart(uint64_t key, const SeparatedPair* entry, const Apart& apart) {
    const unsigned ended = file_apart_entries(key, entry, apart, added_separated_, added_key_);
    dead_separated_ += ended & 1u;
    dead_key_ += ended >> 1;
  }

  // The block is done: the keys it did not reach are passed, and its counts recorded.
  void close() {
    for (; head_ != head_end_; ++head_) let_go_head(*head_);
    for (; tail_ != tail_end_; ++tail_) let_go_beside(*tail_, dead_tail_);
    for (; separated_ != separated_end_; ++separated_) end_separated(*separated_);
    for (; key_ != key_end_; ++key_) end_key(*key_);
    for (; cache_ != cache_end_; ++cache_) let_go_beside(*cache_, dead_cache_);
    Merge& u = store_.merge_;
    u.heads.finish_part(part_, slot_, first_head_, dead_head_);
    u.tails.finish_part(part_, slot_, first_tail_, dead_tail_);
    u.separated.finish_part(part_, slot_, first_separated_, dead_separated_);
    u.apart_keys.finish_part(part_, slot_, first_key_, dead_key_);
    u.cache.finish_part(part_, slot_, first_cache_, dead_cache_);
  }

 private:
  bool carried(uint64_t key) const {
    return !idle_.empty() && idle_[pair_first(key)] && idle_[pair_second(key)];
  }
  // A manifold, its tail and its cached poses are carried together: a manifold with points is
  // in the store with its key's tail if it has more than one and its poses if it may reuse them.
  void let_go_head(ManifoldHead& old) {
    if (old.point_count == 0 || !carried(old.key())) {
      old.point_count = 0;
      ++dead_head_;
    }
  }
  template <class T>
  void end_beside(T& entry, std::size_t& dead) {
    entry.key = kEndedKey;
    ++dead;
  }
  template <class T>
  void let_go_beside(T& entry, std::size_t& dead) {
    if (!carried(entry.key)) end_beside(entry, dead);
  }
  void end_separated(SeparatedPair& s) {
    s.end();
    ++dead_separated_;
  }
  void end_key(uint64_t& apart_key) {
    apart_key = kEndedKey;
    ++dead_key_;
  }
  // file_manifold's filing; returns the tails that ended (0 or 1). perf: static, and taking the
  // buffers alone, so that where the compiler keeps it out of line the walk's cursors need not
  // leave the registers.
  static unsigned file_manifold_entries(const Manifold& m, const Touching& old,
                                        ScratchVector<ManifoldHead>& added_head,
                                        ScratchVector<ManifoldTail>& added_tail) {
    if (old.head == nullptr) {
      added_head.push_back(head_of(m));
    } else {
      store_head(m, *old.head);
    }
    if (m.point_count > 1) {
      if (old.tail == nullptr) {
        added_tail.push_back(tail_of(m));
      } else {
        store_tail(m, *old.tail);
      }
      return 0;
    }
    if (old.tail == nullptr) return 0;
    old.tail->key = kEndedKey;
    return 1;
  }
  // file_apart's filing; returns the entries that ended: 1 for the separated one, 2 for the key.
  // perf: out of line, off the path of the touching pairs, so that the collide stage's pair loop
  // stays small enough for the compiler to inline its rotations.
  [[gnu::noinline]] static unsigned file_apart_entries(
      uint64_t key, const SeparatedPair* entry, const Apart& apart,
      ScratchVector<SeparatedPair>& added_separated, ScratchVector<uint64_t>& added_keys);

  ContactStore& store_;
  std::size_t part_, slot_;
  std::span<const uint8_t> idle_;
  ScratchVector<ManifoldHead>& added_head_;
  ScratchVector<ManifoldTail>& added_tail_;
  ScratchVector<PairCache>& added_cache_;
  ScratchVector<SeparatedPair>& added_separated_;
  ScratchVector<uint64_t>& added_key_;
  std::size_t first_head_, first_tail_, first_cache_, first_separated_, first_key_;
  ManifoldHead *head_, *head_end_;
  ManifoldTail *tail_, *tail_end_;
  PairCache *cache_, *cache_end_;
  SeparatedPair *separated_, *separated_end_;
  uint64_t *key_, *key_end_;
  std::size_t dead_head_ = 0, dead_tail_ = 0, dead_cache_ = 0, dead_separated_ = 0, dead_key_ = 0;
};

template <class T>
void ContactStore::rename_beside(std::vector<T>& list, uint32_t index, uint32_t last, bool resort) {
  std::size_t kept = 0;
  for (T entry : list) {
    uint32_t a = pair_first(entry.key), b = pair_second(entry.key);
    if (a == index || b == index) continue;
    if (a == last) a = index;
    if (b == last) b = index;
    entry.key = make_pair_key(a, b);
    list[kept++] = entry;
  }
  list.resize(kept);
  if (resort) {
    std::sort(list.begin(), list.end(), [](const T& x, const T& y) { return x.key < y.key; });
  }
}

template <class F>
void ContactStore::remove_body(uint32_t index, uint32_t last, F&& dropped) {
  std::size_t kept = 0;
  bool resort = false;
  for (std::size_t k = 0; k < heads_.size(); ++k) {
    ManifoldHead m = heads_[k];
    if (m.body_a == index || m.body_b == index) {
      dropped(static_cast<const ManifoldHead&>(m));
      continue;
    }
    if (index != last && (m.body_a == last || m.body_b == last)) {
      if (m.body_a == last) m.body_a = index;
      if (m.body_b == last) m.body_b = index;
      resort = true;
    }
    heads_[kept++] = m;
  }
  heads_.resize(kept);
  // The manifolds' tails and poses go with them: the same keys, dropped and renamed alike (the
  // poses are A's and B's, which keep their roles).
  rename_beside(tails_, index, last, resort);
  rename_beside(cache_, index, last, resort);
  // The separation cache names bodies by index too; it is only a cache, so it starts over.
  clear_apart();
  if (resort) {
    // determinism: keys are unique, so the sorted order is a function of the keys alone.
    std::sort(heads_.begin(), heads_.end(),
              [](const ManifoldHead& x, const ManifoldHead& y) { return x.key() < y.key(); });
  }
}

}  // namespace elan::detail
