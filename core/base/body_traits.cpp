// SPDX-License-Identifier: MIT
#include "core/base/body_traits.hpp"

#include <algorithm>
#include <cstring>

#include "core/base/heap_bytes.hpp"

namespace elan::detail {

static_assert(sizeof(BodyTraits) == 5 * sizeof(Real) + 16, "BodyTraits: no padding to compare");

bool same_bits(const BodyTraits& a, const BodyTraits& b) {
  return std::memcmp(&a, &b, sizeof(BodyTraits)) == 0;
}

uint32_t TraitTable::acquire(const BodyTraits& traits) {
  for (uint32_t k : recent_) {
    if (k != kNone && users_[k] != 0 && same_bits(entries_[k], traits)) {
      ++users_[k];
      return k;
    }
  }
  uint32_t k;
  if (!free_.empty()) {
    k = free_.back();
    free_.pop_back();
    entries_[k] = traits;
  } else {
    k = uint32_t(entries_.size());
    entries_.push_back(traits);
    users_.push_back(0);
  }
  users_[k] = 1;
  // An index already among the recent ones (a free entry reused) keeps its place: else a store
  // that makes each body with default traits first, then its own, would push its own out.
  if (std::find(recent_.begin(), recent_.end(), k) == recent_.end()) {
    recent_[next_recent_] = k;
    next_recent_ = (next_recent_ + 1) % kRecent;
  }
  return k;
}

void TraitTable::release(uint32_t k) {
  if (--users_[k] == 0) free_.push_back(k);
}

bool TraitTable::any_restitution() const {
  for (std::size_t k = 0; k < entries_.size(); ++k) {
    if (users_[k] != 0 && entries_[k].restitution > 0) return true;
  }
  return false;
}

bool TraitTable::restore(std::vector<BodyTraits> entries, std::vector<uint32_t> free,
                         std::span<const uint32_t> body_entry) {
  *this = TraitTable{};
  std::vector<uint32_t> users(entries.size(), 0);
  for (uint32_t k : body_entry) {
    if (k >= entries.size()) return false;
    ++users[k];
  }
  std::vector<uint8_t> listed(entries.size(), 0);
  for (uint32_t k : free) {
    if (k >= entries.size() || users[k] != 0 || listed[k] != 0) return false;
    listed[k] = 1;
  }
  for (std::size_t k = 0; k < entries.size(); ++k) {
    if (users[k] == 0 && listed[k] == 0) return false;
  }
  entries_ = std::move(entries);
  users_ = std::move(users);
  free_ = std::move(free);
  return true;
}

std::size_t TraitTable::heap_bytes() const {
  return detail::heap_bytes(entries_) + detail::heap_bytes(users_) + detail::heap_bytes(free_);
}

}  // namespace elan::detail
