// Stage executor: block claiming with an atomic cursor per stage, completion counting, and a
// spin-then-yield wait before the next stage.
#include "solver/stage_executor.hpp"

#include <tbb/task_group.h>

#include <thread>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define ELAN_PAUSE() _mm_pause()
#else
#define ELAN_PAUSE() ((void)0)
#endif

namespace elan::detail {

void StageExecutor::reset(std::size_t n) {
  if (capacity_ < n) {
    capacity_ = n + n / 2 + 16;
    claimed_ = std::make_unique<Counter[]>(capacity_);
    done_ = std::make_unique<Counter[]>(capacity_);
  }
  for (std::size_t i = 0; i < n; ++i) {
    claimed_[i].value.store(0, std::memory_order_relaxed);
    done_[i].value.store(0, std::memory_order_relaxed);
  }
  std::atomic_thread_fence(std::memory_order_release);
}

void StageExecutor::run_parallel(const std::vector<StageSpec>& stages, int participants,
                                 WorkRef work) {
  const std::size_t n = stages.size();
  auto participate = [&]() {
    for (std::size_t i = 0; i < n; ++i) {
      const uint32_t count = stages[i].block_count;
      if (count == 0) continue;
      for (;;) {
        const uint32_t b = claimed_[i].value.fetch_add(1, std::memory_order_relaxed);
        if (b >= count) break;
        work.call(work.object, stages[i], b);
        done_[i].value.fetch_add(1, std::memory_order_release);
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

  tbb::task_group group;
  for (int t = 1; t < participants; ++t) group.run(participate);
  participate();
  group.wait();
}

}  // namespace elan::detail
