// SPDX-License-Identifier: MIT
// One sorted list updated in place by a parallel pass over fixed blocks of keys, then joined:
// the merge every list of the contact store goes through (ContactStore), written once.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/base/grow.hpp"
#include "core/base/heap_bytes.hpp"
#include "core/base/parallel.hpp"
#include "core/base/step_scratch.hpp"

namespace elan::detail {

// The per-type hooks of an entry of a sorted list: its key, and whether the pass marked it as
// ended (to be dropped by the join). Specialised beside each entry type's list
// (narrowphase/contact_store.hpp):
//   static uint64_t key(const T&);
//   static bool ended(const T&);
template <class T>
struct ListEntry;

// The update of one list sorted by key (unique keys), in three steps:
//   begin_update   serial: each block's range of the list found (block p owns the keys from its
//                  first key up to the next block's first key), per-thread buffers emptied;
//   the blocks     parallel: block p rewrites the entries of its range in place, marks those that
//                  end (ListEntry<T>::ended), appends entries of keys new to the list, in key
//                  order, to its thread's buffer (`added`), then records its counts
//                  (finish_part);
//   join           serial: each block's live entries merged with its new ones and moved to their
//                  final place, a prefix sum of the blocks' counts.
// determinism: a block writes only its own range and one run of a thread's buffer; the join reads
// the runs in block order, so which thread ran a block changes nothing.
template <class T>
struct ListUpdate {
  struct Run {
    uint32_t thread = 0;
    std::size_t first = 0, count = 0;
  };
  // Per thread: entries of new keys, block by block. Each has room for a quarter more than the
  // largest held the step before.
  std::vector<ScratchVector<T>> added;
  std::size_t room = 0;
  // The rest, per block, are taken from the step's scratch for the stage too.
  ScratchVector<Run> added_run;        // per block: its new keys' run, in key order
  ScratchVector<std::size_t> start;    // per block + 1: its range of the list on entry
  ScratchVector<std::size_t> live;     // per block: entries of its range that stay
  ScratchVector<std::size_t> at;       // per block + 1: its range of the list on return
  ScratchVector<std::size_t> waiting;  // the join: blocks waiting for their right neighbour
  // The join: one block's entries on their way, with room for the largest block that moves.
  ScratchVector<T> bounce;

  // A block's counts, once it has run: `dead` entries of its range ended, and its new entries
  // are those of its thread's buffer from `first_added` on.
  void finish_part(std::size_t part, std::size_t thread, std::size_t first_added,
                   std::size_t dead) {
    live[part] = start[part + 1] - start[part] - dead;
    added_run[part] = {uint32_t(thread), first_added, added[thread].size() - first_added};
  }

  std::size_t heap_bytes() const { return detail::heap_bytes(added); }
};

// Before the blocks run: per-thread buffers emptied, and each block's range of the list found.
// Block p's first key is keys[p * grain].
template <class T>
void begin_update(ListUpdate<T>& u, const std::vector<T>& list, std::span<const uint64_t> keys,
                  std::size_t grain, std::size_t parts, StepScratch& step_scratch) {
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
    u.start[part] = std::size_t(
        std::lower_bound(list.begin(), list.end(), keys[part * grain],
                         [](const T& x, uint64_t k) { return ListEntry<T>::key(x) < k; }) -
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
    if (ListEntry<T>::ended(list[i])) continue;
    for (; next_added != added.end() && ListEntry<T>::key(*next_added) < ListEntry<T>::key(list[i]);
         ++next_added) {
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
  // a list keeps its largest size for good, and doubling left up to half of it unused; each
  // growth holds the old list and the new at once.
  grow_to(list, std::max(list.size(), total));
  auto place = [&](std::size_t p) {
    const std::size_t from = u.start[p], to = u.start[p + 1];
    const auto& run = u.added_run[p];
    if (unchanged(p) && at[p] == from) return;
    // perf: a part that only shifts (most of them: an entry added or ended early in the list
    // moves all after it) is copied once, in the direction that reads each entry before it is
    // overwritten, not through `bounce`.
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

}  // namespace elan::detail
