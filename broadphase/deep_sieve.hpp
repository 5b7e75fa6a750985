// SPDX-License-Identifier: MIT
// The deep sieve: bodies spawned at one point overlap all the others, n of them n (n - 1) / 2
// pairs (10,000 boxes: 50 million), and a broadphase that stores and sorts them all spends
// seconds and hundreds of megabytes on pairs the deep-pair budget (core/world/deep_pairs.hpp)
// then drops. The finders hand each pair they find to the sieve, which tests it as it comes:
// a pair that is not deep is stored as before; a deep one is only offered to its two bodies'
// candidate sets, each of which keeps the kCandidates best of its body's deep partners. The
// candidates are then joined to the stored pairs, so the list holds at most kCandidates deep
// pairs per body.
//
// Deep (as deep_pairs.hpp): both bodies have an inner ball (radius r > 0) and their centres are
// closer than kDeepFraction (r_a + r_b). Best (deep_pair_rank): first the partners of the body's
// own run of kRun consecutive bodies that can be deep (DeepBall::run), nearest in index first; then
// those of its run's group of 8 runs, of 64 runs, and so on (deep_pair_level), each level in the
// order of a hash of the pair. The order is a function of the pair and its bodies' runs (the
// scene's state), so a body's best kCandidates are a function of the set of its deep partners,
// whatever order the pairs come in and however they are split between threads: each thread keeps
// sets of its own, merged at the end, and the candidates are the same for every finder and any
// thread count.
//
// Why runs: bodies spawned at one point are made one after the other, and a run of kRun of them
// keeps all its kRun (kRun - 1) / 2 pairs, kDeepPairBudget = kRun - 1 a body, so the crowd parts
// in groups, none pushing on another's members until they are no longer deep, as the budget's
// greedy pass in key order alone made it. Nearest-first (by distance), or a hash alone, joins the
// whole crowd in one graph of pushes whose chains add up past the push-out cap within half a
// second (100 boxes at one point: 14 to 19 m/s at steps 24 to 41 against the cap's 3;
// tests/physics/spawn_overlap.cpp). Why the hash for the rest: the finders meet pairs in index
// order, and by index distance nearly every offer would improve a set (each partner nearer than the
// last); in hash order a set's worst improves rarely, and most offers are turned away by one
// compare. Why the levels: once a crowd's runs have parted, a body with kCandidates deep partners
// in its group of 8 (or 64) runs takes none from outside it, so a finder can pass by, unoffered,
// the pairs between two such bodies of different groups (closed_runs.hpp): 10,000 boxes at one
// point still overlap in tens of millions of deep pairs a step then.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/deep_overlap.hpp"
#include "elan/math.hpp"

namespace elan::detail {

// A body's inner ball (deep_pairs.hpp): centre and radius, m; r = 0 for a body that is never deep.
// run: the body's run (deep_sieve.hpp), its ordinal among the bodies with r > 0 over kRun.
struct DeepBall {
  Real x = 0, y = 0, z = 0, r = 0;
  uint32_t run = 0;
};

// True when the two balls are deep (both radii positive, centres closer than kDeepFraction of
// their sum). The one test of the sieve and the
// budget. Symmetric in a and b: the differences change sign, their squares do not.
bool balls_deep(const DeepBall& a, const DeepBall& b);

// The same test inline, for the hot loops (the exported one cannot be inlined into them in a
// shared library build, which must allow its interposition). The squared distance is summed x, y,
// then z; a vector lane that does the same operations in the same order gives the same answer.
inline bool deep_balls_inline(const DeepBall& a, const DeepBall& b) {
  const Real dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  const Real d2 = dx * dx + dy * dy + dz * dz;
  const Real reach = kDeepFraction * (a.r + b.r);
  // NaN centres (a quarantined body) compare false: never deep.
  return a.r > 0 && b.r > 0 && d2 < reach * reach;
}

// Runs form groups level by level (deep_sieve.hpp): a group of level L is 8^(L - 1) consecutive
// runs, those whose numbers agree but for their last kLevelShift (L - 1) bits (level 1: the run).
// A pair's level: the lowest whose group holds both bodies' runs.
inline constexpr uint32_t kLevelShift = 3;
inline uint32_t deep_pair_level(uint32_t run_a, uint32_t run_b) {
  const uint32_t width = uint32_t(std::bit_width(run_a ^ run_b));
  return 1 + (width + kLevelShift - 1) / kLevelShift;
}

// A deep pair's rank in its bodies' sets, lower is better: |a - b| for a pair within one run, else
// (level - 1) 2^32 + a 32-bit hash of the key (make_pair_key). Equal ranks (the partners a - d
// and a + d) fall back to the partner's index.
uint64_t deep_pair_rank(const DeepBall& a, const DeepBall& b, uint64_t key);

class DeepSieve {
 public:
  // Deep partners a body's candidate set keeps: the budget (deep_pairs.hpp). The pairs other
  // bodies keep of it come on top, so the budget's cut still has more to choose from.
  static constexpr uint32_t kCandidates = 8;
  // Bodies of a run (deep_sieve.hpp): the budget and the body.
  static constexpr uint32_t kRun = kCandidates + 1;

  // Starts an update: one ball per body, read until collect(). Sizes the per-thread sets (call it
  // in the arena the finder runs in).
  void begin(std::span<const DeepBall> balls);
  // Takes the deep pairs of keys[0, count) into the calling thread's sets and moves the others,
  // in order, to the front. Returns how many are left. Safe from any worker thread of the arena.
  std::size_t sieve(uint64_t* keys, std::size_t count);
  // Counts deep pairs a finder passed by without offering them, as the sieve would have turned
  // them away (closed_runs.hpp), among the calling thread's taken pairs.
  void count_taken(std::size_t count);
  // The balls begin() was given.
  std::span<const DeepBall> balls() const { return balls_; }
  // Per body, 1 when its set was full at the last collect(): it has at least kCandidates deep
  // partners (a crowd's body); else 0, and all 0 for a body count new since. Read after collect()
  // for that update's crowd (deep_pairs.hpp), and at the next update as a hint for
  // closed_runs.hpp, which no result depends on.
  std::span<const uint8_t> crowded() const { return crowded_; }
  // After the finder: the merged candidates' pair keys, appended to `out` unsorted, unique. Returns
  // how many deep pairs were taken (0: the update found none). Empties the sets for the next
  // update, and rewrites crowded().
  std::size_t collect(std::vector<uint64_t>& out);
  std::size_t heap_bytes() const;

  struct Candidate {
    uint64_t rank;  // deep_pair_rank
    uint32_t partner;
  };

 private:
  // One thread's sets: per body a slot (or none) and a bar, per slot its body, count and sorted
  // candidates.
  struct Sets {
    std::vector<uint32_t> slot_of;
    // Per body: the rank of its set's worst candidate once the set is full, else all ones. An
    // offer of a higher rank cannot enter: in a crowd nearly every pair is turned away by two
    // compares against this column, small enough to stay in cache.
    std::vector<uint64_t> bar;
    std::vector<uint32_t> owner;
    std::vector<uint32_t> count;
    std::vector<Candidate> entries;  // kCandidates per slot, best first
    std::size_t taken = 0;
    // Pads the sets of two threads onto different cache lines (the counters are written often).
    char pad[64];
  };
  static void offer(Sets& s, uint32_t body, const Candidate& c);
  static void size_for(Sets& s, std::size_t bodies);
  static void reset(Sets& s);

  std::span<const DeepBall> balls_;
  std::vector<Sets> threads_;
  Sets merged_;
  std::vector<uint8_t> crowded_;
};

}  // namespace elan::detail
