// SPDX-License-Identifier: MIT
// StageExecutor: runs a fixed list of stages, each split into independent blocks, on the
// caller's thread plus the arena's workers, with one lightweight sync between stages.
//
// perf: a TBB fork/join per colour per substep is 100+ joins a step, and waking a sleeping worker
// costs far more than a sync. Here the workers are started once per solve and stay in a spin-then-
// yield wait between stages (the scheme of Box2D v3's solver stages), so a sync costs about one
// cross-core round trip. Within a stage, participant t starts at block t * count / participants
// and claims blocks outward (forward, then backward from its start) by marking each block's own
// flag, as b2ExecuteMainStage does: the participants claim in different cache lines until they
// meet, instead of all contending for one cursor (two contended atomics per block, whose line
// moves between the cores), and each keeps working on the same part of every pass, the part its
// cache already holds. A stage of one block is always the caller's (participant 0),
// for the same reason. Completed blocks are counted once per participant and stage.
// determinism: a block's work and its writes are fixed by (stage, block); which thread runs a
// block is not, but blocks of one stage touch disjoint data, so the result is the same.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace elan::detail {

struct StageSpec {
  uint32_t block_count = 0;  // may be 0: the stage is skipped
  uint32_t kind = 0;         // what the callback should do (caller-defined)
  uint32_t arg = 0;          // e.g. the colour (caller-defined)
};

class StageExecutor {
 public:
  // Runs every stage in order; `work(stage, block)` is called once per block of each stage.
  // Must be called from inside the task arena whose workers should help. `participants` is how
  // many threads may take part (1 = the caller alone, no tasks are spawned). A template, so the
  // callback is not wrapped in a std::function (which would allocate every step).
  template <class Work>
  void run(const std::vector<StageSpec>& stages, int participants, const Work& work) {
    if (participants <= 1) {
      for (const StageSpec& s : stages)
        for (uint32_t b = 0; b < s.block_count; ++b) work(s, b);
      return;
    }
    reset(stages);
    run_parallel(stages, participants, work);
  }

  // Counters and claim flags kept between runs (the memory report).
  std::size_t heap_bytes() const {
    return capacity_ * sizeof(Counter) + claim_capacity_ * sizeof(std::atomic<uint32_t>) +
           first_block_.capacity() * sizeof(std::size_t);
  }

 private:
  // Type-erased by reference only (no allocation): a pointer to the caller's callable.
  struct WorkRef {
    const void* object;
    void (*call)(const void*, const StageSpec&, uint32_t);
  };
  template <class F>
  void run_parallel(const std::vector<StageSpec>& stages, int participants, const F& f) {
    WorkRef ref{&f, [](const void* o, const StageSpec& s, uint32_t b) {
                  (*static_cast<const F*>(o))(s, b);
                }};
    run_parallel(stages, participants, ref);
  }
  void run_parallel(const std::vector<StageSpec>& stages, int participants, WorkRef work);
  void reset(const std::vector<StageSpec>& stages);

  struct alignas(64) Counter {
    std::atomic<uint32_t> value{0};
  };
  std::unique_ptr<Counter[]> done_;  // per stage: blocks finished
  std::size_t capacity_ = 0;
  // Per block of every stage (stage i's at first_block_[i]): the run that claimed it. A new run
  // number each run, so the flags need no clearing.
  std::unique_ptr<std::atomic<uint32_t>[]> claim_;
  std::size_t claim_capacity_ = 0;
  std::vector<std::size_t> first_block_;
  uint32_t run_ = 0;
};

}  // namespace elan::detail
