// SPDX-License-Identifier: MIT
// Stage executor: block claiming with an atomic cursor per stage, completion counting, and a
// spin-then-yield wait before the next stage.
#include "solver/stage_executor.hpp"

#include <tbb/task_group.h>

#include <algorithm>
#include <thread>

#include "core/base/tbb_hand_off.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define ELAN_PAUSE() _mm_pause()
#else
#define ELAN_PAUSE() ((void)0)
#endif

namespace elan::detail {

void StageExecutor::reset(const std::vector<StageSpec>& stages) {
  const std::size_t n = stages.size();
  if (capacity_ < n) {
    capacity_ = n + n / 2 + 16;
    done_ = std::make_unique<Counter[]>(capacity_);
  }
  for (std::size_t i = 0; i < n; ++i) done_[i].value.store(0, std::memory_order_relaxed);
  first_block_.resize(n);
  std::size_t blocks = 0;
  for (std::size_t i = 0; i < n; ++i) {
    first_block_[i] = blocks;
    blocks += stages[i].block_count;
  }
  if (claim_capacity_ < blocks || run_ == UINT32_MAX) {
    claim_capacity_ = std::max(claim_capacity_, blocks + blocks / 2 + 64);
    claim_ = std::make_unique<std::atomic<uint32_t>[]>(claim_capacity_);
    for (std::size_t b = 0; b < claim_capacity_; ++b) claim_[b].store(0, std::memory_order_relaxed);
    run_ = 0;
  }
  ++run_;
  // threading: no fence is needed here. These relaxed stores, and run_, are made by the caller
  // before run_parallel spawns the workers' tasks, and a task spawn is a release by the spawner
  // and an acquire by the thread that runs the task (TBB's task queues), so every participant
  // sees the cleared counters and the new run number before its first claim. Within a run the
  // atomics carry their own ordering: a block's writes happen before its claimer's
  // fetch_add(release) on the stage's counter, and every participant leaves the stage only
  // after a load(acquire) that reads the final count, which is in the release sequence of every
  // fetch_add, so it sees every block's writes. The claims themselves need only atomicity
  // (relaxed): a block claimed twice is impossible because exchange is one read-modify-write.
  // TBB's spawn and join are invisible to ThreadSanitizer (libtbb is not instrumented):
  // run_parallel annotates them (TbbHandOff).
}

void StageExecutor::run_parallel(const std::vector<StageSpec>& stages, int participants,
                                 WorkRef work) {
  const std::size_t n = stages.size();
  const uint32_t run = run_;
  auto participate = [&](uint32_t t) {
    for (std::size_t i = 0; i < n; ++i) {
      const uint32_t count = stages[i].block_count;
      if (count == 0) continue;
      std::atomic<uint32_t>* claim = claim_.get() + first_block_[i];
      auto take = [&](uint32_t b) {
        return claim[b].exchange(run, std::memory_order_relaxed) != run;
      };
      // Outward from this participant's start until a block another one has taken: the blocks
      // each participant takes form one run of blocks around its start, so none is left over.
      // perf: a stage of one block is the caller's (participant 0, always present), so the data
      // it writes stays in one core's cache from pass to pass. Taken by whichever thread came
      // first, the solver's cut would move between the cores' caches.
      if (count > 1 || t == 0) {
        const uint32_t start = uint32_t(uint64_t(count) * t / uint32_t(participants));
        uint32_t finished = 0;
        for (uint32_t b = start; b < count && take(b); ++b, ++finished)
          work.call(work.object, stages[i], b);
        for (uint32_t b = start; b-- > 0 && take(b); ++finished)
          work.call(work.object, stages[i], b);
        if (finished) done_[i].value.fetch_add(finished, std::memory_order_release);
      }
      // threading: every claimed block is finished by the thread that claimed it, so this wait
      // ends even if other participants never arrive; a late one finds stages done and skips.
      int spins = 0;
      while (done_[i].value.load(std::memory_order_acquire) < count) {
        if (++spins < 4096) {
          ELAN_PAUSE();
        } else {
          std::this_thread::yield();
        }
      }
    }
  };

  TbbHandOff hand_off;
  tbb::task_group group;
  hand_off.spawn(participate);
  for (int t = 1; t < participants; ++t) {
    group.run([&participate, &hand_off, t] {
      TbbHandOff::TaskScope task(hand_off);
      participate(uint32_t(t));
    });
  }
  participate(0);
  group.wait();
  hand_off.joined();
}

}  // namespace elan::detail
