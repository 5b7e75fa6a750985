// Column bookkeeping of the body store: append, swap-remove, reserve.
#include "core/base/body_store.hpp"

namespace elan::detail {

std::size_t BodyStore::push_back() {
  const std::size_t i = size();
  for_each_column(*this, [](auto& c) { c.emplace_back(); });
  qw[i] = 1;
  return i;
}

void BodyStore::swap_remove(std::size_t index) {
  for_each_column(*this, [index](auto& c) {
    c[index] = c.back();
    c.pop_back();
  });
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
