// SPDX-License-Identifier: MIT
// split_in_halves(): a median cut of the simulated bodies (see partition.hpp).
#include "solver/partition.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace elan::detail {

namespace {

// Orders floats as unsigned integers: flip every bit of a negative, the sign bit of the rest.
// A non-finite value orders last.
uint32_t order_key(Real x) {
  const float f = float(x);
  if (!std::isfinite(f)) return std::numeric_limits<uint32_t>::max();
  const uint32_t bits = std::bit_cast<uint32_t>(f);
  return (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
}

}  // namespace

void split_in_halves(const BodyStore& bodies, std::span<const uint32_t> simulated,
                     std::span<uint64_t> keys, std::span<uint8_t> side) {
  const std::size_t n = simulated.size();
  if (n == 0) return;
  // The axis of largest spread of the centres (min and max do not depend on the visiting order).
  const Column<Real>* columns[3] = {&bodies.px, &bodies.py, &bodies.pz};
  int axis = 0;
  Real widest = -1;
  for (int d = 0; d < 3; ++d) {
    Real lo = std::numeric_limits<Real>::infinity(), hi = -lo;
    for (const uint32_t i : simulated) {
      const Real x = (*columns[d])[i];
      if (std::isfinite(x)) {
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    }
    if (hi - lo > widest) {
      widest = hi - lo;
      axis = d;
    }
  }
  // determinism: (coordinate, index) keys are distinct, so the n / 2 smallest are one set
  // whatever the selection algorithm visits first.
  const Column<Real>& x = *columns[axis];
  for (std::size_t k = 0; k < n; ++k) {
    keys[k] = (uint64_t(order_key(x[simulated[k]])) << 32) | uint64_t(k);
  }
  const std::size_t half = n / 2;
  std::nth_element(keys.begin(), keys.begin() + std::ptrdiff_t(half), keys.end());
  for (std::size_t k = 0; k < n; ++k) side[uint32_t(keys[k])] = k < half ? 0 : 1;
}

}  // namespace elan::detail
