// SPDX-License-Identifier: MIT
// StepScratch: one block of memory that the stages of a step take their per-step buffers from,
// in turn, one phase each: the sweep and the collide stage (the bounding boxes, the sweep's strip
// entries, pair blocks and sorts, the pair list they leave, which the collide stage reads; then
// its threads' buffers of new keys, its per-block arrays and join), the solver (its islands,
// median cut and colourings, then its bundles and point rows). Each is dead before the next phase
// starts, so each phase starts again at the front of the block, and the block holds the largest,
// not their sum (Box2D v3's b2ArenaAllocator and Jolt's TempAllocator, per step).
//
// A buffer is a std::vector with a ScratchAllocator: it grows and is indexed as any vector, and
// taking memory is a bump of an atomic offset, so the sweep's chunks may grow theirs in parallel.
// Giving back the buffer taken last moves the offset back (a stack), so the solver's colouring
// arrays, dead before its bundles are laid out, lend them their bytes within one phase.
// A buffer that outlives the ones taken around it (the pair list: written at the end of the sweep,
// read through the collide stage) is taken from the back of the block instead, a second stack
// growing down: the sweep's buffers then all go back from the front, which starts over
// (rewind_front) under the collide stage's, even where one of them grew and left a hole.
// What the block cannot hold comes from the heap; the next phase then starts with a block large
// enough for what this one asked (a sixteenth more: growing it copies nothing, since nothing is
// held then), so a scene allocates while it grows and then never. Which thread took which bytes
// does not matter: no result depends on an address.
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/base/grow.hpp"

namespace elan::detail {

class StepScratch {
 public:
  static constexpr std::size_t kAlign = 64;  // every buffer starts on a cache line

  StepScratch() = default;
  StepScratch(const StepScratch&) = delete;
  StepScratch& operator=(const StepScratch&) = delete;
  ~StepScratch();

  // Starts a phase at the front of the block. Every buffer of the last phase must have been
  // released (release()): one still held keeps its bytes, and the phase continues behind it
  // instead (never two buffers in the same bytes; a debug build asserts). The block is resized
  // here only, when nothing is held: grown to what the last phase asked, or, after a passing
  // spike, cut back (SpikeTrim's rule over phases).
  void begin_phase();

  // Thread-safe. `bytes` rounded up to kAlign.
  void* allocate(std::size_t bytes);
  // From the back of the block. Serial: no other buffer may be taken or given back meanwhile.
  void* allocate_back(std::size_t bytes);
  // `back`: the buffer came from allocate_back. Serial for those.
  void deallocate(void* p, std::size_t bytes, bool back = false);
  // Starts the front of the block over when none of its buffers is held (the back's may be), so
  // bytes left unused behind a buffer that grew, or given back out of order, are used again. A
  // no-op while one is held (a debug build asserts). Serial.
  void rewind_front();

  std::size_t heap_bytes() const { return capacity_; }
  std::size_t held_bytes() const { return held_.load(std::memory_order_relaxed); }

 private:
  static std::size_t round_up(std::size_t bytes) { return (bytes + kAlign - 1) / kAlign * kAlign; }
  void reallocate(std::size_t capacity);

  std::byte* block_ = nullptr;
  std::size_t capacity_ = 0;
  std::atomic<std::size_t> top_{0};   // where the next buffer starts (past the block: heap)
  std::atomic<std::size_t> peak_{0};  // the most both ends held at once in this phase
  std::atomic<std::size_t> held_{0};  // bytes handed out and not yet given back
  // Bytes taken from the back (a stack: the lowest buffer is the last taken), and of the bytes
  // held those of back buffers. Changed serially only; atomic for the front's concurrent reads.
  std::atomic<std::size_t> back_{0};
  std::size_t held_back_ = 0;
  void note_peak(std::size_t end);
  SpikeTrim trim_;
};

// The allocator of a buffer in a StepScratch. A default-constructed one (no scratch) allocates
// from the heap, so such a vector also works where no step is running (tests, a lone sweep).
template <class T>
struct ScratchAllocator {
  using value_type = T;
  using propagate_on_container_copy_assignment = std::true_type;
  using propagate_on_container_move_assignment = std::true_type;
  using propagate_on_container_swap = std::true_type;

  StepScratch* scratch = nullptr;
  bool back = false;  // from the back of the block (StepScratch::allocate_back)

  ScratchAllocator() = default;
  explicit ScratchAllocator(StepScratch* s, bool from_back = false) : scratch(s), back(from_back) {}
  template <class U>
  ScratchAllocator(const ScratchAllocator<U>& other) : scratch(other.scratch), back(other.back) {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (scratch) {
      return static_cast<T*>(back ? scratch->allocate_back(bytes) : scratch->allocate(bytes));
    }
    return static_cast<T*>(::operator new(bytes, std::align_val_t(StepScratch::kAlign)));
  }
  void deallocate(T* p, std::size_t n) {
    if (scratch) {
      scratch->deallocate(p, n * sizeof(T), back);
    } else {
      ::operator delete(p, std::align_val_t(StepScratch::kAlign));
    }
  }
  // resize() leaves new elements as the memory holds them: every scratch buffer is written whole
  // before it is read (the sweep's entries, prepare_bundle's bundles and rows), and setting the
  // bundles and rows to zero first would write all of them once more every step, for nothing.
  template <class U>
  void construct(U* p) noexcept {
    static_assert(std::is_trivially_destructible_v<U>, "scratch buffers hold plain data");
    static_cast<void>(p);
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const ScratchAllocator<U>& other) const {
    return scratch == other.scratch && back == other.back;
  }
};

template <class T>
using ScratchVector = std::vector<T, ScratchAllocator<T>>;

// Empties `v` and points it at `scratch`, room for nothing yet: the start of its use in a phase.
template <class T>
void take_from(ScratchVector<T>& v, StepScratch& scratch) {
  ScratchVector<T>(ScratchAllocator<T>(&scratch)).swap(v);
}

// As take_from, its buffers taken from the back of the block: one that outlives the buffers
// taken around it (see StepScratch).
template <class T>
void take_from_back(ScratchVector<T>& v, StepScratch& scratch) {
  ScratchVector<T>(ScratchAllocator<T>(&scratch, true)).swap(v);
}

// As take_from, then sized to n elements, left unset (ScratchAllocator::construct).
template <class T>
void take_from(ScratchVector<T>& v, StepScratch& scratch, std::size_t n) {
  take_from(v, scratch);
  v.resize(n);
}

// As take_from, with room for n elements and none in it: a buffer filled by push_back that must
// not grow (a grown one leaves its old bytes unused in the block until the phase ends).
template <class T>
void take_room(ScratchVector<T>& v, StepScratch& scratch, std::size_t n) {
  take_from(v, scratch);
  v.reserve(n);
}

// Gives `v`'s bytes back (to the scratch or the heap): the end of its use in a phase.
template <class T>
void release(ScratchVector<T>& v) {
  ScratchVector<T>().swap(v);
}

}  // namespace elan::detail
