// SPDX-License-Identifier: MIT
// The deep sieve (deep_sieve.hpp): per-thread candidate sets, merged after the finder.
#include "broadphase/deep_sieve.hpp"

#include <algorithm>

#include "core/base/heap_bytes.hpp"
#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"
#include "core/base/splitmix.hpp"

namespace elan::detail {

namespace {

constexpr uint32_t kNoSlot = 0xFFFFFFFFu;
constexpr uint64_t kOpen = ~uint64_t{0};  // the bar of a set not yet full
// Sets a thread's candidates are reserved for up front (size_for): 140 kB a thread.
constexpr std::size_t kReservedSlots = 1024;

bool better(const DeepSieve::Candidate& x, const DeepSieve::Candidate& y) {
  return x.rank < y.rank || (x.rank == y.rank && x.partner < y.partner);
}

// Neighbouring keys get unrelated ranks (core/base/splitmix.hpp).
inline uint32_t mix(uint64_t key) {
  return uint32_t(splitmix64_finalize(key));
}

inline uint64_t rank_of(const DeepBall& a, const DeepBall& b, uint64_t key) {
  if (a.run == b.run) return pair_second(key) - pair_first(key);
  return (uint64_t(deep_pair_level(a.run, b.run) - 1) << 32) | mix(key);
}

}  // namespace

bool balls_deep(const DeepBall& a, const DeepBall& b) {
  return deep_balls_inline(a, b);
}

uint64_t deep_pair_rank(const DeepBall& a, const DeepBall& b, uint64_t key) {
  return rank_of(a, b, key);
}

void DeepSieve::begin(std::span<const DeepBall> balls) {
  balls_ = balls;
  if (threads_.size() < thread_slots()) threads_.resize(thread_slots());
  // Every thread's sets are sized here, not at its first batch: a worker that first takes a batch
  // long after the scene is warm would otherwise allocate its sets in that step.
  for (Sets& s : threads_) size_for(s, balls.size());
  size_for(merged_, balls.size());
  // Kept from the last update: a body's flag is only a hint (closed_runs.hpp).
  if (crowded_.size() != balls.size()) crowded_.assign(balls.size(), 0);
}

void DeepSieve::size_for(Sets& s, std::size_t bodies) {
  if (s.slot_of.size() < bodies) {
    s.slot_of.resize(bodies, kNoSlot);
    s.bar.resize(bodies, kOpen);
    // Which thread takes which batch changes from run to run, so a thread's sets would reach new
    // highs, and reallocate, long after the scene is warm (ragdolls: jointed limbs are deep
    // pairs until the joint filter drops them). Reserved once for up to kReservedSlots bodies.
    const std::size_t slots = std::min<std::size_t>(bodies, kReservedSlots);
    s.owner.reserve(slots);
    s.count.reserve(slots);
    s.entries.reserve(slots * kCandidates);
  }
}

// Keeps in the body's set the kCandidates best of what it held and c; a candidate already held
// (a pair reported twice) is not added again.
void DeepSieve::offer(Sets& s, uint32_t body, const Candidate& c) {
  constexpr uint32_t K = kCandidates;
  if (c.rank > s.bar[body]) return;
  uint32_t slot = s.slot_of[body];
  if (slot == kNoSlot) {
    slot = uint32_t(s.owner.size());
    s.slot_of[body] = slot;
    s.owner.push_back(body);
    s.count.push_back(0);
    s.entries.resize(s.entries.size() + K);
  }
  Candidate* e = s.entries.data() + std::size_t(slot) * K;
  uint32_t n = s.count[slot];
  if (n == K && !better(c, e[K - 1])) return;
  uint32_t p = n;
  while (p > 0 && better(c, e[p - 1])) --p;
  if (p > 0 && e[p - 1].partner == c.partner) return;  // held already (equal, not better)
  if (n == K) n = K - 1;                               // the worst makes room
  for (uint32_t q = n; q > p; --q) e[q] = e[q - 1];
  e[p] = c;
  s.count[slot] = n + 1;
  if (n + 1 == K) s.bar[body] = e[K - 1].rank;
}

void DeepSieve::count_taken(std::size_t count) {
  threads_[thread_slot()].taken += count;
}

std::size_t DeepSieve::sieve(uint64_t* keys, std::size_t count) {
  // perf: the thread's sets are looked up once a batch, not once a pair.
  Sets& s = threads_[thread_slot()];
  const DeepBall* balls = balls_.data();
  const uint64_t* bar = s.bar.data();
  std::size_t kept = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const uint64_t key = keys[k];
    const uint32_t a = pair_first(key), b = pair_second(key);
    if (!deep_balls_inline(balls[a], balls[b])) {
      keys[kept++] = key;
      continue;
    }
    ++s.taken;
    const uint64_t rank = rank_of(balls[a], balls[b], key);
    if (rank > bar[a] && rank > bar[b]) continue;
    offer(s, a, {rank, b});
    offer(s, b, {rank, a});
  }
  return kept;
}

void DeepSieve::reset(Sets& s) {
  for (const uint32_t body : s.owner) {
    s.slot_of[body] = kNoSlot;
    s.bar[body] = kOpen;
  }
  s.owner.clear();
  s.count.clear();
  s.entries.clear();
  s.taken = 0;
}

// determinism: the best kCandidates of a union are the best of the union of each part's best, so
// the merged sets do not depend on which thread took which pair nor on the order they are merged.
std::size_t DeepSieve::collect(std::vector<uint64_t>& out) {
  std::size_t taken = 0;
  for (Sets& s : threads_) {
    taken += s.taken;
    for (std::size_t slot = 0; slot < s.owner.size(); ++slot) {
      const Candidate* e = s.entries.data() + slot * kCandidates;
      for (uint32_t q = 0; q < s.count[slot]; ++q) offer(merged_, s.owner[slot], e[q]);
    }
    reset(s);
  }
  // A pair kept by both its bodies appears twice: the lower body's set writes it, the higher one's
  // only when the lower one did not keep it.
  std::fill(crowded_.begin(), crowded_.end(), uint8_t{0});
  for (std::size_t slot = 0; slot < merged_.owner.size(); ++slot) {
    const uint32_t body = merged_.owner[slot];
    const Candidate* e = merged_.entries.data() + slot * kCandidates;
    if (merged_.count[slot] == kCandidates && body < crowded_.size()) crowded_[body] = 1;
    for (uint32_t q = 0; q < merged_.count[slot]; ++q) {
      const uint32_t partner = e[q].partner;
      if (body > partner) {
        const uint32_t other = merged_.slot_of[partner];
        bool held = false;
        if (other != kNoSlot) {
          const Candidate* f = merged_.entries.data() + std::size_t(other) * kCandidates;
          for (uint32_t r = 0; r < merged_.count[other]; ++r) held |= f[r].partner == body;
        }
        if (held) continue;
      }
      out.push_back(make_pair_key(body, partner));
    }
  }
  reset(merged_);
  return taken;
}

std::size_t DeepSieve::heap_bytes() const {
  const auto sets_bytes = [](const Sets& s) {
    return detail::heap_bytes(s.slot_of) + detail::heap_bytes(s.bar) + detail::heap_bytes(s.owner) +
           detail::heap_bytes(s.count) + detail::heap_bytes(s.entries);
  };
  std::size_t bytes =
      detail::heap_bytes(threads_) + sets_bytes(merged_) + detail::heap_bytes(crowded_);
  for (const Sets& s : threads_) bytes += sets_bytes(s);
  return bytes;
}

}  // namespace elan::detail
