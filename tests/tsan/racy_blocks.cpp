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
  long shared = 0;  // the racy datum: both blocks add to it without a lock
  std::atomic<int> entered{0};
  std::atomic<bool> written{false};
  // Relaxed: no ordering for TSan to see. Gives up after five seconds (a one-core run; a loaded
  // machine may start the second thread late).
  const auto wait_for = [](const auto& done) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (!done() && std::chrono::steady_clock::now() < until) std::this_thread::yield();
  };
  tbb::task_arena arena(2);
  arena.execute([&] {
    elan::detail::for_blocks(2, 1, [&](std::size_t, std::size_t, std::size_t block) {
      // Both blocks run at once, on two threads, so that the race is there to find ...
      entered.fetch_add(1, std::memory_order_relaxed);
      wait_for([&] { return entered.load(std::memory_order_relaxed) == 2; });
      // ... and block 1 writes after block 0 has, not at the same instant: TSan's own record of
      // an access is not atomic with it, so two writes at one instant can both go unreported
      // (the canary once failed that way, with the increment lost).
      if (block == 1) wait_for([&] { return written.load(std::memory_order_relaxed); });
      shared += 1;
      if (block == 0) written.store(true, std::memory_order_relaxed);
    });
  });
  std::printf("shared = %ld\n", shared);
  return 0;
}
