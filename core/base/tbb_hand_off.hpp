// SPDX-License-Identifier: MIT
// Happens-before annotations for ThreadSanitizer at elan's hand-offs of work to TBB: Debian's
// libtbb is not instrumented, so TSan cannot see that a task starts after its spawner's writes
// and that the joiner resumes after the task's. Compiled to nothing without TSan.
//
// threading: a `TbbHandOff` lives on the spawning thread's stack for one parallel call.
// `spawn()`, called just before the call and after the callables TBB is given are built (a task
// may read them in place, as parallel_invoke's and task_arena::execute's do), releases the
// spawner's writes so far; every task acquires them on entry
// (`TaskScope`) and releases into a second address on exit, and `joined()` acquires that one
// after the call returns. TSan's release joins the releasing thread's clock into the address's
// clock, so the joiner acquires every task's. These are exactly the edges TBB itself provides
// (spawn publishes the task; wait_for_all returns after every task's completion was recorded),
// no more: data the tasks share among themselves is still checked, so a race on elan's own data
// is still reported. Each call site has its own pair of addresses (on its stack), never a global
// one, which would order unrelated calls (two worlds stepped side by side) and hide their races.
#pragma once

#if defined(__SANITIZE_THREAD__)
#define ELAN_THREAD_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define ELAN_THREAD_SANITIZER 1
#endif
#endif

#if defined(ELAN_THREAD_SANITIZER)
extern "C" void __tsan_acquire(void* addr);
extern "C" void __tsan_release(void* addr);
#endif

namespace elan::detail {

class TbbHandOff {
 public:
  TbbHandOff() = default;
  TbbHandOff(const TbbHandOff&) = delete;
  TbbHandOff& operator=(const TbbHandOff&) = delete;

  // Brackets one task's body: acquires the spawner's writes, releases the task's on exit.
  class TaskScope {
   public:
    explicit TaskScope(TbbHandOff& h) : h_(h) { acquire(&h_.spawn_); }
    ~TaskScope() { release(&h_.join_); }
    TaskScope(const TaskScope&) = delete;
    TaskScope& operator=(const TaskScope&) = delete;

   private:
    TbbHandOff& h_;
  };

  // Just before the parallel call: what this thread wrote so far is visible to every task.
  // `callables` are what the tasks will read in place: their addresses are passed to TSan so
  // that the compiler builds them before the release, not after (a local whose address has not
  // escaped may be built later than written).
  template <class... T>
  void spawn(const T&... callables) {
    (release(const_cast<char*>(reinterpret_cast<const char*>(&callables))), ...);
    release(&spawn_);
  }

  // After the parallel call has returned: every task's writes are visible to the caller.
  void joined() { acquire(&join_); }

 private:
  static void release([[maybe_unused]] char* addr) {
#if defined(ELAN_THREAD_SANITIZER)
    __tsan_release(addr);
#endif
  }
  static void acquire([[maybe_unused]] char* addr) {
#if defined(ELAN_THREAD_SANITIZER)
    __tsan_acquire(addr);
#endif
  }
  char spawn_ = 0;
  char join_ = 0;
};

}  // namespace elan::detail
