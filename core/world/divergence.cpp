// SPDX-License-Identifier: MIT
// The divergence finder: compares two worlds body by body, bit for bit, and steps two worlds side
// by side until they first differ (elan/snapshot.hpp).
#include <bit>
#include <cstdint>

#include "core/base/body_store.hpp"
#include "core/world/world_access.hpp"
#include "core/world/world_state.hpp"
#include "elan/snapshot.hpp"

namespace elan {

using detail::BodyStore;
using detail::Column;

namespace {

template <class T>
uint64_t bits_of(T v) {
  if constexpr (sizeof(T) == 8) {
    return std::bit_cast<uint64_t>(v);
  } else if constexpr (sizeof(T) == 4) {
    return std::bit_cast<uint32_t>(v);
  } else {
    return v;
  }
}

}  // namespace

Divergence compare_worlds(const World& a, const World& b) {
  const BodyStore& x = detail::state_of(a).bodies;
  const BodyStore& y = detail::state_of(b).bodies;
  Divergence d;
  if (x.size() != y.size()) {
    d.found = true;
    d.field = "body_count";
    d.value_a = double(x.size());
    d.value_b = double(y.size());
    return d;
  }
  struct Field {
    const char* name;
    Column<Real> BodyStore::*column;
  };
  static constexpr Field kFields[] = {
      {"px", &BodyStore::px}, {"py", &BodyStore::py},
      {"pz", &BodyStore::pz}, {"qw", &BodyStore::qw},
      {"qx", &BodyStore::qx}, {"qy", &BodyStore::qy},
      {"qz", &BodyStore::qz}, {"vx", &BodyStore::vx},
      {"vy", &BodyStore::vy}, {"vz", &BodyStore::vz},
      {"wx", &BodyStore::wx}, {"wy", &BodyStore::wy},
      {"wz", &BodyStore::wz}, {"sleep_time", &BodyStore::sleep_time}};
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (const Field& f : kFields) {
      const Real va = (x.*f.column)[i], vb = (y.*f.column)[i];
      if (bits_of(va) != bits_of(vb)) {
        d.found = true;
        d.body = i;
        d.field = f.name;
        d.value_a = double(va);
        d.value_b = double(vb);
        return d;
      }
    }
    if (x.flags[i] != y.flags[i]) {
      d.found = true;
      d.body = i;
      d.field = "flags";
      d.value_a = x.flags[i];
      d.value_b = y.flags[i];
      return d;
    }
  }
  return d;
}

Divergence find_divergence(World& a, World& b, uint64_t steps, Real dt) {
  Divergence d = compare_worlds(a, b);
  for (uint64_t step = 1; step <= steps && !d.found; ++step) {
    a.step(dt);
    b.step(dt);
    d = compare_worlds(a, b);
    d.step = step;
  }
  return d;
}

}  // namespace elan
