// SPDX-License-Identifier: MIT
// A deliberate data race on elan's side of a TBB hand-off, for the ThreadSanitizer build only:
// two blocks of one for_blocks call write the same counter without synchronisation. The test
// Tsan.RaceOnElanDataIsReported passes only if TSan reports it, which shows that the hand-off
// annotations (core/base/tbb_hand_off.hpp) order the spawner and the joiner with the tasks and
// nothing more: a race between the tasks themselves still fails the suite.
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "core/base/parallel.hpp"

int main() {
  long shared = 0;  // the racy datum: every block adds to it without a lock
  std::atomic<int> entered{0};
  tbb::task_arena arena(2);
  arena.execute([&] {
    elan::detail::for_blocks(2, 1, [&](std::size_t, std::size_t, std::size_t) {
      // Wait (relaxed: no ordering for TSan to see) until both blocks run at once, on two
      // threads, so that the race is there to find; give up after a second on a one-core run.
      entered.fetch_add(1, std::memory_order_relaxed);
      const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
      while (entered.load(std::memory_order_relaxed) < 2 &&
             std::chrono::steady_clock::now() < until) {
        std::this_thread::yield();
      }
      shared += 1;
    });
  });
  std::printf("shared = %ld\n", shared);
  return 0;
}
