// SPDX-License-Identifier: MIT
// Column bookkeeping of the body store: append, swap-remove, reserve.
#include "core/base/body_store.hpp"

namespace elan::detail {

std::size_t BodyStore::push_back() {
  const std::size_t i = size();
  for_each_column(*this, [](auto& c) { c.emplace_back(); });
  qw[i] = 1;
  applied[i] = kNoForce;
  traits[i] = trait_table.acquire(BodyTraits{});
  return i;
}

void BodyStore::swap_remove(std::size_t index) {
  trait_table.release(traits[index]);
  // The removed body's force goes (the list's last entry takes its place), then the last body's
  // entry follows it to `index`.
  if (const uint32_t k = applied[index]; k != kNoForce) {
    applied_forces[k] = applied_forces.back();
    applied[applied_forces[k].body] = k;
    applied_forces.pop_back();
  }
  for_each_column(*this, [index](auto& c) {
    c[index] = c.back();
    c.pop_back();
  });
  if (index < size() && applied[index] != kNoForce) {
    applied_forces[applied[index]].body = uint32_t(index);
  }
}

AppliedForce& BodyStore::applied_force(std::size_t i) {
  if (applied[i] == kNoForce) {
    applied[i] = uint32_t(applied_forces.size());
    applied_forces.push_back({uint32_t(i), Vec3::Zero(), Vec3::Zero()});
  }
  return applied_forces[applied[i]];
}

void BodyStore::reserve(std::size_t n) {
  for_each_column(*this, [n](auto& c) { c.reserve(n); });
}

std::size_t BodyStore::bytes_per_body() const {
  std::size_t bytes = 0;
  for_each_column(*this, [&bytes](auto& c) { bytes += sizeof(c[0]); });
  return bytes;
}

}  // namespace elan::detail
