// SPDX-License-Identifier: MIT
// The step's scratch: phases share its bytes, a phase larger than the block still gets what it
// asks and the next one fits in a grown block, buffers grown in parallel never overlap, and a
// buffer still held across a phase keeps its bytes.
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "core/base/step_scratch.hpp"
#include "core/base/tbb_hand_off.hpp"

namespace elan::detail {
namespace step_scratch_test {

bool inside(const StepScratch& s, const void* p, const void* first) {
  const auto at = reinterpret_cast<std::uintptr_t>(p);
  const auto begin = reinterpret_cast<std::uintptr_t>(first);
  return at >= begin && at < begin + s.heap_bytes();
}

// One phase that takes a buffer of n entries and gives it back.
template <class T>
void phase(StepScratch& s, ScratchVector<T>& v, std::size_t n) {
  s.begin_phase();
  take_from(v, s);
  v.resize(n);
  release(v);
}

TEST(StepScratch, PhasesShareTheBlockAndItHoldsTheLargerNotTheSum) {
  StepScratch s;
  ScratchVector<uint32_t> small, large;
  // Warm-up: the first phases come from the heap and size the block.
  for (int step = 0; step < 3; ++step) {
    phase(s, small, 1000);
    phase(s, large, 5000);
  }
  s.begin_phase();
  take_from(small, s);
  small.resize(1000);
  const void* small_data = small.data();
  release(small);
  s.begin_phase();
  take_from(large, s);
  large.resize(5000);
  // Both phases start at the front of the one block.
  EXPECT_EQ(large.data(), small_data);
  // The larger phase (in whole cache lines), a quarter more: not the two together.
  const std::size_t a = StepScratch::kAlign;
  const std::size_t larger = (5000 * sizeof(uint32_t) + a - 1) / a * a;
  EXPECT_GE(s.heap_bytes(), larger);
  EXPECT_LE(s.heap_bytes(), larger + larger / 4 + a);
  EXPECT_EQ(s.held_bytes(), larger);
  release(large);
  EXPECT_EQ(s.held_bytes(), 0u);
}

TEST(StepScratch, TheLastBufferGivenBackLendsItsBytesToTheNext) {
  // The solver's colouring arrays, dead before its bundles: given back last taken first, the
  // bundles start where the first of them did, and the phase asks only for the larger.
  StepScratch s;
  ScratchVector<uint32_t> first, second, after;
  std::size_t warm = 0;
  for (int step = 0; step < 4; ++step) {
    s.begin_phase();
    if (step == 1) warm = s.heap_bytes();
    take_from(first, s);
    first.resize(1000);
    take_from(second, s);
    second.resize(1000);
    const void* first_data = first.data();
    release(second);
    release(first);
    take_from(after, s);
    after.resize(3000);
    if (step > 0) {
      EXPECT_EQ(static_cast<const void*>(after.data()), first_data);
    }
    release(after);
  }
  // Once warm, the block never grows: each phase reaches 3000 entries at most, where without
  // the rewind it would reach 5000 (the first phase, whose bytes came from the heap, could not
  // rewind, and sized the block).
  s.begin_phase();
  EXPECT_EQ(s.heap_bytes(), warm);
  // Given back out of order, a buffer below the top keeps the bytes above it in use.
  s.begin_phase();
  take_from(first, s);
  first.resize(1000);
  take_from(second, s);
  second.resize(1000);
  second[999] = 7;
  release(first);
  take_from(after, s);
  after.assign(1000, 9);
  EXPECT_EQ(second[999], 7u);
  release(after);
  release(second);
}

// The sweep and the collide stage: the sweep's buffers (one of which grew, leaving its old bytes
// behind it, and given back out of order), then the pair list taken from the back and held while
// the collide stage's buffers start over at the front. They never share bytes, and once warm the
// phase asks only for the larger of the two stages' fronts, plus the back.
TEST(StepScratch, TheBackHoldsABufferWhileTheFrontStartsOver) {
  StepScratch s;
  ScratchVector<uint32_t> entries, blocks, collide;
  ScratchVector<uint64_t> pairs;
  std::size_t warm = 0;
  for (int step = 0; step < 4; ++step) {
    s.begin_phase();
    if (step == 2) warm = s.heap_bytes();
    take_from(entries, s);
    entries.resize(1000);
    const void* front = entries.data();
    take_room(blocks, s, 100);
    for (uint32_t k = 0; k < 150; ++k) blocks.push_back(k);  // grows past its room, to 200
    take_from_back(pairs, s);
    pairs.resize(500);
    std::iota(pairs.begin(), pairs.end(), uint64_t{1});
    release(entries);  // out of order: the bytes stay taken until the rewind
    release(blocks);
    s.rewind_front();
    take_from(collide, s);
    collide.assign(2000, 0xFFFFFFFFu);
    if (step > 1) {
      EXPECT_EQ(static_cast<const void*>(collide.data()), front) << "the front started over";
      const auto* lo = reinterpret_cast<const char*>(front);
      EXPECT_TRUE(inside(s, pairs.data() + 499, lo)) << "the back is in the block";
      EXPECT_GE(reinterpret_cast<const char*>(pairs.data()),
                reinterpret_cast<const char*>(collide.data() + 2000))
          << "front and back apart";
    }
    for (std::size_t k = 0; k < pairs.size(); ++k) ASSERT_EQ(pairs[k], k + 1) << "step " << step;
    release(collide);
    release(pairs);
  }
  s.begin_phase();
  EXPECT_EQ(s.heap_bytes(), warm) << "no growth once warm";
  // The phase asks for the larger front with the back's 4032 bytes (500 pairs, to a cache line):
  // the sweep's 4032 + 448 + 832 (its entries, the block's room and its grown copy) or the collide
  // stage's 8000; a sixteenth more. Without the rewind the collide stage's buffer would start past
  // the grown block (4480) and the phase would ask 16512.
  EXPECT_LE(s.heap_bytes(), (8000 + 4032) * 17 / 16 + 64);
}

TEST(StepScratch, APhaseLargerThanTheBlockGetsItsBytesAndTheNextFits) {
  StepScratch s;
  s.begin_phase();
  ScratchVector<uint64_t> v;
  take_from(v, s);
  v.resize(100);
  std::iota(v.begin(), v.end(), 0);
  release(v);
  s.begin_phase();  // block: 100 keys and a quarter
  take_from(v, s);
  v.resize(10000);  // beyond the block: from the heap
  std::iota(v.begin(), v.end(), 0);
  EXPECT_EQ(v[9999], 9999u);
  release(v);
  s.begin_phase();  // grown to what the last phase asked
  EXPECT_GE(s.heap_bytes(), 10000 * sizeof(uint64_t));
  take_from(v, s);
  v.resize(10000);
  const auto* first = reinterpret_cast<const char*>(v.data());
  EXPECT_TRUE(inside(s, v.data() + 9999, first));
  release(v);
}

TEST(StepScratch, HandsBackWhatASpikeLeft) {
  // A pile's first steps: every pair new, the block grows to what they ask. Once the phases ask
  // far less for a whole SpikeTrim window, the block is cut to a quarter past their high.
  StepScratch s;
  ScratchVector<uint64_t> v;
  phase(s, v, 200000);
  phase(s, v, 1000);
  const std::size_t spike = s.heap_bytes();
  EXPECT_GE(spike, 200000 * sizeof(uint64_t));
  for (uint32_t k = 0; k < 2 * SpikeTrim::kWindow; ++k) phase(s, v, 1000);
  EXPECT_LT(s.heap_bytes(), spike / 10);
  EXPECT_GE(s.heap_bytes(), 1000 * sizeof(uint64_t));
  // A swing within a window is not cut and regrown in turn.
  for (uint32_t k = 0; k < 2 * SpikeTrim::kWindow; ++k) phase(s, v, k % 2 ? 20000 : 1000);
  const std::size_t swing = s.heap_bytes();
  for (uint32_t k = 0; k < 2 * SpikeTrim::kWindow; ++k) phase(s, v, k % 2 ? 20000 : 1000);
  EXPECT_EQ(s.heap_bytes(), swing);
}

TEST(StepScratch, BuffersGrownInParallelNeverShareBytes) {
  // The sweep's chunks push pairs into their own buffers at once: each must read back exactly
  // what it wrote, whether its bytes came from the block or, past it, from the heap.
  StepScratch s;
  constexpr std::size_t kBlocks = 64;
  std::vector<ScratchVector<uint64_t>> blocks(kBlocks);
  tbb::task_arena arena(2);
  for (int phase = 0; phase < 4; ++phase) {
    s.begin_phase();
    for (auto& b : blocks) take_from(b, s);
    // The hand-off to TBB annotated for ThreadSanitizer, as the engine's own (tbb_hand_off.hpp).
    TbbHandOff hand_off;
    const auto fill = [&] {
      tbb::parallel_for(std::size_t{0}, kBlocks, [&](std::size_t k) {
        TbbHandOff::TaskScope task(hand_off);
        for (uint64_t i = 0; i < 500 + 37 * k; ++i) blocks[k].push_back(k << 32 | i);
      });
    };
    hand_off.spawn(fill);
    arena.execute(fill);
    hand_off.joined();
    for (std::size_t k = 0; k < kBlocks; ++k) {
      ASSERT_EQ(blocks[k].size(), 500 + 37 * k);
      for (uint64_t i = 0; i < blocks[k].size(); ++i) ASSERT_EQ(blocks[k][i], k << 32 | i);
    }
    for (auto& b : blocks) release(b);
    EXPECT_EQ(s.held_bytes(), 0u);
  }
}

#if defined(__SANITIZE_ADDRESS__)
TEST(StepScratchDeathTest, AddressSanitizerSeesPastTheEndOfABufferInTheBlock) {
  // One block for many buffers must not cost the sanitized build its checks: the bytes past a
  // buffer's end stay poisoned, as the end of a heap block would.
  StepScratch s;
  ScratchVector<uint32_t> v;
  phase(s, v, 1000);
  s.begin_phase();
  take_from(v, s);
  v.resize(100);
  volatile uint32_t* past = v.data() + 100;
  EXPECT_DEATH(*past = 1, "use-after-poison");
  release(v);
}
#endif

#ifdef NDEBUG
TEST(StepScratch, ABufferHeldAcrossAPhaseKeepsItsBytes) {
  // A misuse (a debug build asserts): the new phase must not start over the held buffer.
  StepScratch s;
  ScratchVector<uint32_t> held, next;
  for (int warm = 0; warm < 2; ++warm) phase(s, held, 256);
  s.begin_phase();
  take_from(held, s);
  held.assign(256, 7);
  s.begin_phase();
  take_from(next, s);
  next.assign(256, 9);
  EXPECT_EQ(std::count(held.begin(), held.end(), 7u), 256);
  release(next);
  release(held);
}
#endif

}  // namespace step_scratch_test
}  // namespace elan::detail
