// Column bookkeeping of the body store: append, swap-remove, reserve.
#include "core/base/body_store.hpp"

namespace elan::detail {

namespace {
// Applies f to every column, in declaration order, so the three operations cannot drift apart.
template <class S, class F>
void for_each_column(S& s, F&& f) {
  f(s.px);
  f(s.py);
  f(s.pz);
  f(s.qw);
  f(s.qx);
  f(s.qy);
  f(s.qz);
  f(s.vx);
  f(s.vy);
  f(s.vz);
  f(s.wx);
  f(s.wy);
  f(s.wz);
  f(s.fx);
  f(s.fy);
  f(s.fz);
  f(s.tx);
  f(s.ty);
  f(s.tz);
  f(s.inv_mass);
  f(s.inv_ix);
  f(s.inv_iy);
  f(s.inv_iz);
  f(s.friction);
  f(s.restitution);
  f(s.linear_damping);
  f(s.angular_damping);
  f(s.sleep_time);
  f(s.shape);
  f(s.category);
  f(s.mask);
  f(s.slot);
  f(s.motion);
  f(s.flags);
}
}  // namespace

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
