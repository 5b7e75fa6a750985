// SPDX-License-Identifier: MIT
// BodyTraits: a body's contact material, damping and collision filter, kept once for all the
// bodies that share them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "elan/math.hpp"

namespace elan::detail {

// The values a body is made of rather than where it is: most bodies share them with many others
// (a pile's bodies all have one set), so the body store keeps a 4-byte index a body into a
// TraitTable, not these bytes a body. Default: all zero, as a new column's values were, but a
// gravity scale of 1.
struct BodyTraits {
  Real friction = 0;         // Coulomb coefficient, mixed as sqrt(f_a f_b)
  Real restitution = 0;      // mixed as max(e_a, e_b)
  Real linear_damping = 0;   // 1/s
  Real angular_damping = 0;  // 1/s
  Real gravity_scale = 1;    // multiplies the world's gravity (1: none, exact)
  uint32_t category = 0;  // collision filter: a pair passes if (cat_a & mask_b) && (cat_b & mask_a)
  uint32_t mask = 0;
  uint32_t flags = 0;  // kTraitSensor
  uint32_t spare = 0;  // keeps the struct free of padding in both builds: same_bits is a memcmp
};

// BodyTraits::flags: the body is a sensor (overlap events, no contact response, unseen by queries
// unless they ask).
inline constexpr uint32_t kTraitSensor = 1u << 0;

// Bit for bit: a body given -0 friction must not read another's +0 (the solver's bits differ).
bool same_bits(const BodyTraits& a, const BodyTraits& b);

// The distinct traits of a store's bodies, each with its count of users. A body's traits are
// shared with an entry acquired lately (the last kRecent distinct ones: bodies are made in runs
// of one kind, or a few kinds in turn) or put in a new entry; an entry with no users left is
// reused by the next new one. Values may repeat across entries (sharing is for memory only:
// every body reads its own values whichever entry holds them). Which index a body gets depends
// on the calls' order alone, never on addresses.
class TraitTable {
 public:
  static constexpr std::size_t kRecent = 8;
  static constexpr uint32_t kNone = ~uint32_t{0};

  const BodyTraits& operator[](uint32_t k) const { return entries_[k]; }
  std::span<const BodyTraits> entries() const { return entries_; }
  // The entries with no users, in the order they will be reused (last first).
  std::span<const uint32_t> free_entries() const { return free_; }

  // An entry holding `traits`, with one more user.
  uint32_t acquire(const BodyTraits& traits);
  // One user fewer for entry k.
  void release(uint32_t k);
  // Whether a body has positive restitution (the solver then keeps bounce data).
  bool any_restitution() const;

  // The table of a snapshot: its entries and free list, and each body's entry (the users are
  // counted from these). False, the table left empty, when they disagree: an index past the
  // entries, a free entry with users or a used one missing from the free list, twice in it.
  bool restore(std::vector<BodyTraits> entries, std::vector<uint32_t> free,
               std::span<const uint32_t> body_entry);

  std::size_t heap_bytes() const;

 private:
  std::vector<BodyTraits> entries_;
  std::vector<uint32_t> users_;
  std::vector<uint32_t> free_;
  std::array<uint32_t, kRecent> recent_ = filled_none();
  std::size_t next_recent_ = 0;

  static std::array<uint32_t, kRecent> filled_none() {
    std::array<uint32_t, kRecent> a;
    a.fill(kNone);
    return a;
  }
};

}  // namespace elan::detail
