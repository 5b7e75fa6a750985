// SPDX-License-Identifier: MIT
// Serial O(n^2) broadphase: the oracle that all-pairs and sweep-and-prune are tested against.
#include <cstdint>
#include <vector>

#include "broadphase/find_pairs.hpp"
#include "broadphase/pair_test.hpp"
#include "core/base/pair_key.hpp"

namespace elan::detail {

void find_pairs_brute_force(const BroadphaseInput& in, std::vector<uint64_t>& out_pairs) {
  out_pairs.clear();
  const uint32_t n = uint32_t(in.bounds->size());
  // Keys come out in ascending (i, j) order, so the list is sorted and unique by construction.
  for (uint32_t i = 0; i < n; ++i) {
    for (uint32_t j = i + 1; j < n; ++j) {
      if (boxes_overlap(*in.bounds, i, j) && accept_pair(in, i, j)) {
        out_pairs.push_back(make_pair_key(i, j));
      }
    }
  }
}

}  // namespace elan::detail
