// SPDX-License-Identifier: MIT
// The deterministic parallel helpers (core/base/parallel.hpp): for_blocks cuts work by count and
// grain alone, whatever the thread count; bin_major_offsets keeps block order within a bin; the
// key sorts give std::sort's order for any thread count and any split into blocks.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <random>
#include <tuple>
#include <vector>

#include "core/base/parallel.hpp"

namespace elan::detail {
namespace parallel_test {

struct Block {
  std::size_t begin, end, block;
  bool operator==(const Block&) const = default;
  bool operator<(const Block& o) const { return block < o.block; }
};

// The blocks for_blocks hands out in an arena of `threads`, sorted by block index.
std::vector<Block> blocks_of(std::size_t count, std::size_t grain, int threads) {
  std::vector<Block> seen;
  std::mutex lock;
  tbb::task_arena arena(threads);
  arena.execute([&] {
    for_blocks(count, grain, [&](std::size_t begin, std::size_t end, std::size_t block) {
      std::lock_guard<std::mutex> hold(lock);
      seen.push_back({begin, end, block});
    });
  });
  std::sort(seen.begin(), seen.end());
  return seen;
}

TEST(ForBlocks, BlocksAreAFunctionOfCountAndGrainAlone) {
  for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{63}, std::size_t{64},
                                  std::size_t{65}, std::size_t{1000}}) {
    const std::size_t grain = 64;
    const std::vector<Block> one = blocks_of(count, grain, 1);
    ASSERT_EQ(one.size(), block_count(count, grain)) << count;
    std::size_t next = 0;
    for (std::size_t b = 0; b < one.size(); ++b) {
      EXPECT_EQ(one[b].block, b);
      EXPECT_EQ(one[b].begin, next) << "blocks tile [0, count) in order";
      EXPECT_EQ(one[b].end, std::min(count, (b + 1) * grain));
      next = one[b].end;
    }
    EXPECT_EQ(next, count);
    EXPECT_EQ(blocks_of(count, grain, 2), one) << count;
    EXPECT_EQ(blocks_of(count, grain, 4), one) << count;
  }
}

TEST(BinMajorOffsets, BlockOrderKeptWithinEveryBin) {
  // Two blocks, three bins: counts[block * bins + bin].
  uint32_t counts[] = {2, 0, 1,   // block 0
                       1, 3, 0};  // block 1
  uint32_t bin_start[4];
  const uint32_t total = bin_major_offsets(counts, 2, 3, bin_start, /*pad=*/1);
  // Bin 0: block 0 at 0 (2 items), block 1 at 2 (1), pad; bin 1 at 4: block 0 (none), block 1
  // at 4 (3), pad; bin 2 at 8: block 0 at 8 (1), block 1 at 9 (none), pad.
  const uint32_t expected_counts[] = {0, 4, 8, 2, 4, 9};
  for (int k = 0; k < 6; ++k) EXPECT_EQ(counts[k], expected_counts[k]) << k;
  EXPECT_EQ(bin_start[0], 0u);
  EXPECT_EQ(bin_start[1], 4u);
  EXPECT_EQ(bin_start[2], 8u);
  EXPECT_EQ(bin_start[3], 10u);
  EXPECT_EQ(total, 10u);
}

// Keys below max_key with many duplicates and the extremes 0 and max_key.
std::vector<uint64_t> random_keys(std::size_t count, uint64_t max_key, uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<uint64_t> keys(count);
  for (uint64_t& k : keys) k = max_key == ~0ull ? rng() : rng() % (max_key + 1);
  for (std::size_t i = 0; i < count / 8; ++i) keys[rng() % count] = keys[rng() % count];
  if (count > 2) {
    keys[0] = max_key;
    keys[1] = 0;
  }
  return keys;
}

TEST(SortKeys, StdSortOrderForAnyThreadCount) {
  for (const auto& [count, max_key] : {std::tuple<std::size_t, uint64_t>{0, 10},
                                       {1, 10},
                                       {1000, 255},
                                       {100000, (1ull << 40) - 1},
                                       {50000, ~0ull},
                                       {70000, 3}}) {
    const std::vector<uint64_t> input = random_keys(count, max_key, uint32_t(count));
    std::vector<uint64_t> expected = input;
    std::sort(expected.begin(), expected.end());
    for (const int threads : {1, 2, 4}) {
      std::vector<uint64_t> keys = input;
      KeySortScratch scratch;
      tbb::task_arena arena(threads);
      // A copy: clang 14 (the sanitizer builds) cannot capture a structured binding.
      const uint64_t max = max_key;
      arena.execute([&] { sort_keys(keys, max, scratch); });
      EXPECT_EQ(keys, expected) << count << " keys, " << threads << " threads";
    }
  }
}

TEST(SortKeyBlocks, SortsTheConcatenationOfTheBlocks) {
  const uint64_t max_key = (1ull << 50) - 1;
  const std::vector<uint64_t> input = random_keys(60000, max_key, 7);
  std::vector<uint64_t> expected = input;
  std::sort(expected.begin(), expected.end());
  // The same multiset cut into blocks of different sizes (one empty) must sort the same way.
  for (const std::size_t parts : {std::size_t{1}, std::size_t{3}, std::size_t{17}}) {
    std::vector<ScratchVector<uint64_t>> blocks(parts + 1);
    for (std::size_t i = 0; i < input.size(); ++i) blocks[(i * i) % parts].push_back(input[i]);
    for (const int threads : {1, 2}) {
      std::vector<uint64_t> out;
      KeySortScratch scratch;
      tbb::task_arena arena(threads);
      arena.execute([&] { sort_key_blocks(blocks, max_key, out, scratch); });
      EXPECT_EQ(out, expected) << parts << " blocks, " << threads << " threads";
    }
  }
}

}  // namespace parallel_test
}  // namespace elan::detail
