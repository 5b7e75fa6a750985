// SPDX-License-Identifier: MIT
// The parallel key sort the broadphase ends with: equal to std::sort on pair lists and on
// adversarial key sets, whether the keys come in one vector or in blocks, under 1 and 2 threads.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "core/base/pair_key.hpp"
#include "core/base/parallel.hpp"

namespace elan::detail {
namespace broadphase_sort_keys_test {

enum class Keys { Pairs, FullWidth, FewDistinct, OneBody, Constant };

// Keys no larger than max_key. Pairs: a body's partners are a handful, as in a pile; OneBody: all
// keys share the lower index, so one bucket and one run hold everything (the std::sort path).
std::vector<uint64_t> make_keys(Keys kind, std::size_t count, uint32_t bodies, uint64_t& max_key,
                                std::mt19937_64& rng) {
  std::vector<uint64_t> keys(count);
  std::uniform_int_distribution<uint32_t> body(0, bodies - 1);
  max_key = make_pair_key(bodies - 2, bodies - 1);
  for (uint64_t& k : keys) {
    switch (kind) {
      case Keys::Pairs: {
        const uint32_t a = body(rng);
        uint32_t b = body(rng);
        if (b == a) b = (a + 1) % bodies;
        k = make_pair_key(a, b);
        break;
      }
      case Keys::FullWidth:
        k = rng();
        break;
      case Keys::FewDistinct:
        k = uint64_t(rng() % 5) << 40;
        break;
      case Keys::OneBody:
        k = make_pair_key(0, 1 + body(rng) % (bodies - 1));
        break;
      case Keys::Constant:
        k = make_pair_key(3, 7);
        break;
    }
  }
  if (kind == Keys::FullWidth) max_key = ~uint64_t{0};
  if (kind == Keys::FewDistinct) max_key = uint64_t{4} << 40;
  return keys;
}

// Cuts keys into blocks of random lengths, some empty, as sweep chunks and plane blocks come.
std::vector<ScratchVector<uint64_t>> split(const std::vector<uint64_t>& keys, std::size_t blocks,
                                           std::mt19937_64& rng) {
  std::vector<ScratchVector<uint64_t>> out(blocks);
  for (uint64_t k : keys) {
    const std::size_t b = rng() % blocks;
    if (b % 7 != 3)
      out[b].push_back(k);
    else
      out[(b + 1) % blocks].push_back(k);
  }
  return out;
}

TEST(SortKeys, MatchesStdSortOnEveryKeySetAndSize) {
  std::mt19937_64 rng(7);
  for (Keys kind :
       {Keys::Pairs, Keys::FullWidth, Keys::FewDistinct, Keys::OneBody, Keys::Constant}) {
    for (std::size_t count : {0u, 1u, 31u, 33u, 1000u, 8191u, 8192u, 70000u, 300000u}) {
      uint64_t max_key = 0;
      const std::vector<uint64_t> keys = make_keys(kind, count, 65541, max_key, rng);
      std::vector<uint64_t> expected = keys;
      std::sort(expected.begin(), expected.end());
      for (int threads : {1, 2}) {
        tbb::task_arena arena(threads);
        arena.execute([&] {
          KeySortScratch scratch;
          std::vector<uint64_t> sorted = keys;
          sort_keys(sorted, max_key, scratch);
          EXPECT_EQ(sorted, expected) << "kind " << int(kind) << " count " << count;
          for (std::size_t blocks : {1u, 40u, 300u}) {
            std::vector<uint64_t> out{42};
            sort_key_blocks(split(keys, blocks, rng), max_key, out, scratch);
            EXPECT_EQ(out, expected)
                << "kind " << int(kind) << " count " << count << " blocks " << blocks;
          }
          // The sweep's way: the sorts' buffers from a step scratch, all given back.
          StepScratch step;
          for (int phase = 0; phase < 2; ++phase) {
            step.begin_phase();
            std::vector<uint64_t> sorted_in_step = keys, out{42};
            sort_keys(sorted_in_step, max_key, scratch, &step);
            EXPECT_EQ(sorted_in_step, expected) << "kind " << int(kind) << " count " << count;
            sort_key_blocks(split(keys, 40, rng), max_key, out, scratch, &step);
            EXPECT_EQ(out, expected) << "kind " << int(kind) << " count " << count;
            EXPECT_EQ(step.held_bytes(), 0u);
          }
        });
      }
    }
  }
}

TEST(SortKeys, SmallBodyCountsUseEveryBucket) {
  // Few bodies: keys crowd into a few of the 256 top buckets (with 2 bodies max_key is 1 and the
  // key itself is the bucket), each then holding long runs of one key.
  std::mt19937_64 rng(11);
  uint64_t max_key = 0;
  for (uint32_t bodies : {2u, 3u, 17u}) {
    const std::vector<uint64_t> keys = make_keys(Keys::Pairs, 20000, bodies, max_key, rng);
    std::vector<uint64_t> expected = keys;
    std::sort(expected.begin(), expected.end());
    KeySortScratch scratch;
    std::vector<uint64_t> sorted = keys;
    sort_keys(sorted, max_key, scratch);
    EXPECT_EQ(sorted, expected) << bodies << " bodies";
  }
}

}  // namespace broadphase_sort_keys_test
}  // namespace elan::detail
