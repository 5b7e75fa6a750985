// The body columns a snapshot saves, in one list shared by the writer, the reader and the test
// that checks the list still covers every column of BodyStore.
#pragma once

#include "core/base/body_store.hpp"

namespace elan::detail {

// Applies f to every column of the store, in BodyStore's declaration order (the format's order).
template <class S, class F>
void visit_snapshot_columns(S& s, F&& f) {
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

// Bytes per body of the columns above; BodyStore::bytes_per_body() must equal it, or a column
// was added that snapshots do not save.
inline std::size_t snapshot_bytes_per_body() {
  std::size_t bytes = 0;
  BodyStore probe;
  visit_snapshot_columns(probe, [&bytes](auto& c) {
    bytes += sizeof(typename std::remove_reference_t<decltype(c)>::value_type);
  });
  return bytes;
}

}  // namespace elan::detail
