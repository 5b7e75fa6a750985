// SPDX-License-Identifier: MIT
#include "core/base/step_scratch.hpp"

#include <cassert>
#include <cstdint>
#include <new>

// No-ops unless built with AddressSanitizer.
#include <sanitizer/asan_interface.h>

namespace elan::detail {

StepScratch::~StepScratch() {
  reallocate(0);
}

void StepScratch::reallocate(std::size_t capacity) {
  if (block_) {
    ASAN_UNPOISON_MEMORY_REGION(block_, capacity_);
    ::operator delete(block_, std::align_val_t(kAlign));
  }
  block_ = nullptr;
  capacity_ = 0;
  if (capacity == 0) return;
  block_ = static_cast<std::byte*>(::operator new(capacity, std::align_val_t(kAlign)));
  capacity_ = capacity;
  // Under AddressSanitizer the block is poisoned but for the buffers handed out, each to the byte
  // it asked for: a write past a buffer's end, or into one given back, is caught as it would be
  // in separate heap blocks.
  ASAN_POISON_MEMORY_REGION(block_, capacity_);
}

void StepScratch::begin_phase() {
  assert(held_.load() == 0 && "StepScratch: a buffer of the last phase is still held");
  if (held_.load(std::memory_order_relaxed) != 0) return;
  top_.store(0, std::memory_order_relaxed);
  back_.store(0, std::memory_order_relaxed);
  const std::size_t asked = peak_.exchange(0, std::memory_order_relaxed);
  if (asked > capacity_) {
    reallocate(round_up(asked + asked / 16));
    return;
  }
  const std::size_t cut = trim_.note(asked, capacity_, 1);
  if (cut != 0) reallocate(round_up(cut));
}

void StepScratch::note_peak(std::size_t end) {
  std::size_t peak = peak_.load(std::memory_order_relaxed);
  while (end > peak && !peak_.compare_exchange_weak(peak, end, std::memory_order_relaxed)) {
  }
}

void* StepScratch::allocate(std::size_t asked) {
  const std::size_t bytes = round_up(asked);
  held_.fetch_add(bytes, std::memory_order_relaxed);
  const std::size_t at = top_.fetch_add(bytes, std::memory_order_relaxed);
  // The phase's size is what both ends held at once.
  const std::size_t end = at + bytes + back_.load(std::memory_order_relaxed);
  note_peak(end);
  if (end <= capacity_) {
    ASAN_UNPOISON_MEMORY_REGION(block_ + at, asked);
    return block_ + at;
  }
  return ::operator new(bytes, std::align_val_t(kAlign));
}

void* StepScratch::allocate_back(std::size_t asked) {
  const std::size_t bytes = round_up(asked);
  held_.fetch_add(bytes, std::memory_order_relaxed);
  held_back_ += bytes;
  const std::size_t back = back_.load(std::memory_order_relaxed) + bytes;
  const std::size_t end = top_.load(std::memory_order_relaxed) + back;
  note_peak(end);
  if (end <= capacity_) {
    back_.store(back, std::memory_order_relaxed);
    std::byte* p = block_ + (capacity_ - back);
    ASAN_UNPOISON_MEMORY_REGION(p, asked);
    return p;
  }
  return ::operator new(bytes, std::align_val_t(kAlign));
}

void StepScratch::rewind_front() {
  const std::size_t front_held = held_.load(std::memory_order_relaxed) - held_back_;
  assert(front_held == 0 && "StepScratch: a buffer at the front is still held");
  if (front_held == 0) top_.store(0, std::memory_order_relaxed);
}

void StepScratch::deallocate(void* p, std::size_t bytes, bool back) {
  bytes = round_up(bytes);
  held_.fetch_sub(bytes, std::memory_order_relaxed);
  if (back) held_back_ -= bytes;
  const auto at = reinterpret_cast<std::uintptr_t>(p);
  const auto first = reinterpret_cast<std::uintptr_t>(block_);
  if (at >= first && at < first + capacity_) {
    ASAN_POISON_MEMORY_REGION(p, bytes);
    if (back) {
      // The last bytes taken from the back: the next buffer there starts where this one ended.
      const std::size_t taken = back_.load(std::memory_order_relaxed);
      if (at - first == capacity_ - taken) back_.store(taken - bytes, std::memory_order_relaxed);
      return;
    }
    // The last bytes taken: the next buffer starts where this one did. If another thread took
    // bytes since, the exchange fails and they stay behind it.
    std::size_t top = at - first + bytes;
    top_.compare_exchange_strong(top, at - first, std::memory_order_relaxed);
    return;
  }
  ::operator delete(p, std::align_val_t(kAlign));
}

}  // namespace elan::detail
