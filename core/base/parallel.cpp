// SPDX-License-Identifier: MIT
// Radix sort for the pair keys: a parallel MSD sort that scatters into buckets block by block and
// sorts the buckets as separate tasks.
#include "core/base/parallel.hpp"

#include <array>
#include <bit>
#include <cassert>
#include <span>

#include "core/base/grow.hpp"

namespace elan::detail {

namespace {

constexpr int kTopBits = 8;
constexpr std::size_t kTopBuckets = std::size_t{1} << kTopBits;
constexpr std::size_t kBucketGrain = 8;
// Below this many keys one serial bucket sort beats the parallel passes' setup.
constexpr std::size_t kSerialBelow = 8192;
// sort_keys cuts its input into sources this long; sort_key_blocks concatenates first when the
// blocks are so many that their histograms would outweigh the keys.
constexpr std::size_t kChunk = 16384;
constexpr std::size_t kMaxSources = 256;
// Runs this short are insertion sorted; a pair list's run is one body's partners, a handful.
constexpr std::size_t kSmallRun = 32;
constexpr int kMaxSubBits = 12;

void insertion_sort(uint64_t* a, std::size_t m) {
  for (std::size_t i = 1; i < m; ++i) {
    const uint64_t v = a[i];
    std::size_t j = i;
    while (j > 0 && v < a[j - 1]) {
      a[j] = a[j - 1];
      --j;
    }
    a[j] = v;
  }
}

// Stable counting sort of src[0, m) into dst on digit (key >> shift) & (digits - 1); count
// needs digits + 1 slots. Returns the longest run of one digit.
uint32_t counting_pass(const uint64_t* src, uint64_t* dst, std::size_t m, int shift,
                       std::size_t digits, uint32_t* count) {
  const uint64_t mask = digits - 1;
  std::fill(count, count + digits + 1, 0u);
  for (std::size_t i = 0; i < m; ++i) ++count[((src[i] >> shift) & mask) + 1];
  uint32_t longest = 0;
  for (std::size_t d = 0; d < digits; ++d) {
    longest = std::max(longest, count[d + 1]);
    count[d + 1] += count[d];
  }
  for (std::size_t i = 0; i < m; ++i) dst[count[(src[i] >> shift) & mask]++] = src[i];
  return longest;
}

// Sorts src[0, m) into dst[0, m), clobbering src. About as many digits as keys: a stable pass on
// the second digit, then one on the top varying bits, leaves only keys equal in both digits out
// of order (a pair key's partners of one body differ in b's high bits), so one insertion pass
// over the whole range costs about m and rarely mispredicts. Long runs of one top digit (keys
// sharing their top bits) are sorted alone instead, so the worst case stays m log m.
void sort_bucket(uint64_t* src, uint64_t* dst, std::size_t m) {
  if (m <= kSmallRun) {
    std::copy(src, src + m, dst);
    insertion_sort(dst, m);
    return;
  }
  uint64_t all_or = 0, all_and = ~uint64_t{0};
  for (std::size_t i = 0; i < m; ++i) {
    all_or |= src[i];
    all_and &= src[i];
  }
  const uint64_t varying = all_or ^ all_and;
  if (varying == 0) {
    std::copy(src, src + m, dst);
    return;
  }
  // Bits above the top varying one are equal in every key, so digit order is key order.
  const int top = std::bit_width(varying);
  const int low = std::countr_zero(varying);
  const int bits = std::clamp(int(std::bit_width(m)), 4, kMaxSubBits);
  const int shift = std::max(low, top - bits);
  const std::size_t digits = std::size_t{1} << bits;
  std::array<uint32_t, (std::size_t{1} << kMaxSubBits) + 1> count;
  uint32_t longest;
  if (shift > low) {
    // The next digit down: the top varying bits below the first digit, skipping bits that are
    // constant (a pair key's high half is a, its low half b < 2^32, with zeros between).
    const int below = std::bit_width(varying & ((uint64_t{1} << shift) - 1));
    counting_pass(src, dst, m, std::max(low, below - bits), digits, count.data());
    longest = counting_pass(dst, src, m, shift, digits, count.data());
    std::copy(src, src + m, dst);
  } else {
    longest = counting_pass(src, dst, m, shift, digits, count.data());
  }
  if (longest <= kSmallRun) {
    insertion_sort(dst, m);
    return;
  }
  // count[d] is now the end of run d of the top digit.
  std::size_t begin = 0;
  for (std::size_t d = 0; d < digits; ++d) {
    const std::size_t end = count[d];
    if (end - begin <= kSmallRun) {
      insertion_sort(dst + begin, end - begin);
    } else {
      std::sort(dst + begin, dst + end);
    }
    begin = end;
  }
}

// scratch.keys with room for n keys: from the step scratch if given (given back by give_back).
void size_keys(KeySortScratch& scratch, std::size_t n, StepScratch* step_scratch) {
  if (step_scratch) {
    take_from(scratch.keys, *step_scratch, n);
  } else {
    grow_to(scratch.keys, n);
  }
}

void give_back(KeySortScratch& scratch) {
  for (auto it = scratch.bucket.rbegin(); it != scratch.bucket.rend(); ++it) release(*it);
  release(scratch.keys);
}

// The parallel MSD pass over `sources` spans (source(b) gives span b) of `total` keys, into
// out[0, total). out must not alias a source. With `direct`, the keys are scattered into `out`
// and each bucket is sorted from a copy in its thread's scratch; otherwise they are scattered
// into scratch.keys and each bucket sorted from there into `out`.
template <class Source>
void sort_sources(std::size_t sources, const Source& source, std::size_t total, uint64_t max_key,
                  uint64_t* out, KeySortScratch& scratch, bool direct, StepScratch* step_scratch) {
  const int shift = std::max(0, int(std::bit_width(max_key)) - kTopBits);
  if (!direct) size_keys(scratch, total, step_scratch);
  scratch.counts.assign(sources * kTopBuckets + kTopBuckets + 1, 0);
  uint32_t* counts = scratch.counts.data();
  uint32_t* bucket_start = counts + sources * kTopBuckets;
  // determinism: each source counts into its own row (rule 1).
  for_blocks(sources, 1, [&](std::size_t b, std::size_t, std::size_t) {
    uint32_t* c = counts + b * kTopBuckets;
    for (uint64_t k : source(b)) {
      assert((k >> shift) < kTopBuckets);
      ++c[k >> shift];
    }
  });
  // Within a bucket, source b's keys follow source b-1's.
  bin_major_offsets(counts, sources, kTopBuckets, bucket_start);
  uint64_t* mid = direct ? out : scratch.keys.data();
  // determinism: every source writes the slots its offsets reserve (rule 1).
  for_blocks(sources, 1, [&](std::size_t b, std::size_t, std::size_t) {
    uint32_t* c = counts + b * kTopBuckets;
    for (uint64_t k : source(b)) mid[c[k >> shift]++] = k;
  });
  const std::size_t threads = thread_slots();
  if (direct) {
    if (scratch.bucket.size() < threads) scratch.bucket.resize(threads);
    // Which thread sorts which bucket changes from run to run, so every thread's copy is sized
    // for the largest bucket: none reallocates because the schedule changed.
    uint32_t largest = 0;
    for (std::size_t d = 0; d < kTopBuckets; ++d) {
      largest = std::max(largest, bucket_start[d + 1] - bucket_start[d]);
    }
    for (ScratchVector<uint64_t>& copy : scratch.bucket) {
      if (step_scratch) {
        take_room(copy, *step_scratch, largest);
      } else if (largest > copy.capacity()) {
        copy.reserve(largest + largest / 4);
      }
    }
  }
  // determinism: a bucket's sorted keys are a function of its keys alone, whichever thread's
  // scratch held them.
  for_blocks(kTopBuckets, kBucketGrain, [&](std::size_t begin, std::size_t end, std::size_t) {
    ScratchVector<uint64_t>* copy = direct ? &scratch.bucket[thread_slot()] : nullptr;
    for (std::size_t d = begin; d < end; ++d) {
      const uint32_t lo = bucket_start[d], hi = bucket_start[d + 1];
      if (direct) {
        copy->assign(out + lo, out + hi);  // within the capacity reserved above
        sort_bucket(copy->data(), out + lo, hi - lo);
      } else {
        sort_bucket(mid + lo, out + lo, hi - lo);
      }
    }
  });
  if (step_scratch) give_back(scratch);
}

}  // namespace

void sort_keys(std::span<uint64_t> keys, uint64_t max_key, KeySortScratch& scratch,
               StepScratch* step_scratch) {
  const std::size_t n = keys.size();
  if (n < kSerialBelow) {
    size_keys(scratch, n, step_scratch);
    std::copy(keys.begin(), keys.end(), scratch.keys.begin());
    sort_bucket(scratch.keys.data(), keys.data(), n);
    if (step_scratch) give_back(scratch);
    return;
  }
  const uint64_t* data = keys.data();
  const auto chunk = [&](std::size_t b) {
    return std::span<const uint64_t>(data + b * kChunk, std::min(n, (b + 1) * kChunk) - b * kChunk);
  };
  // Sources read keys, the MSD pass writes scratch, the buckets are sorted back into keys.
  sort_sources(block_count(n, kChunk), chunk, n, max_key, keys.data(), scratch, false,
               step_scratch);
}

template <class Keys>
void sort_key_blocks(const std::vector<ScratchVector<uint64_t>>& blocks, uint64_t max_key,
                     Keys& out, KeySortScratch& scratch, StepScratch* step_scratch) {
  std::size_t total = 0;
  for (const auto& b : blocks) total += b.size();
  if (total < kSerialBelow || blocks.size() > kMaxSources) {
    concat_blocks(blocks, out);
    sort_keys(out, max_key, scratch, step_scratch);
    return;
  }
  if (total > out.capacity()) {
    out.clear();
    out.reserve(total);
  }
  out.resize(total);
  const auto block = [&](std::size_t b) { return std::span<const uint64_t>(blocks[b]); };
  sort_sources(blocks.size(), block, total, max_key, out.data(), scratch, true, step_scratch);
}

template void sort_key_blocks(const std::vector<ScratchVector<uint64_t>>&, uint64_t,
                              std::vector<uint64_t>&, KeySortScratch&, StepScratch*);
template void sort_key_blocks(const std::vector<ScratchVector<uint64_t>>&, uint64_t,
                              ScratchVector<uint64_t>&, KeySortScratch&, StepScratch*);

}  // namespace elan::detail
