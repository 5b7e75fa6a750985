// SPDX-License-Identifier: MIT
// split_halves() and load_packets(): the solver's packets (see packets.hpp).
#include "solver/packets.hpp"

#include <algorithm>

#include "solver/partition.hpp"

namespace elan::detail {

void split_halves(const BodyStore& bodies, SolverState& st, StepScratch& scratch) {
  const std::size_t n = bodies.size();
  st.simulated.clear();
  // Room for every body, reserved once the store has grown: push_back's doubling would leave up to
  // half of it unused for good.
  if (st.simulated.capacity() < n) st.simulated.reserve(n);
  uint32_t kinematic = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (bodies.is_dynamic(i) && bodies.is_awake(i) && !(bodies.flags[i] & kFrozen)) {
      st.simulated.push_back(uint32_t(i));
    } else if (bodies.motion[i] == uint8_t(MotionType::Kinematic)) {
      ++kinematic;
    }
  }
  const uint32_t dynamic = uint32_t(st.simulated.size());
  const std::size_t count = 1 + std::size_t(dynamic) + kinematic;
  st.side.resize(dynamic);
  take_from(st.split_keys, scratch, dynamic);
  split_in_halves(bodies, st.simulated, st.split_keys, st.side);
  release(st.split_keys);
  const uint32_t in_half_0 = uint32_t(std::count(st.side.begin(), st.side.end(), uint8_t(0)));
  st.half_start[0] = 1;
  st.half_start[1] = 1 + in_half_0;
  st.half_start[2] = 1 + dynamic;
  st.packet_of.assign(n, 0);
  st.packets.resize(count);
  st.masses.resize(count);
  st.packets[0] = SolverBody{};
  st.masses[0] = SolverBodyMass{};
  uint32_t next_packet[kHalves] = {st.half_start[0], st.half_start[1]};
  for (uint32_t k = 0; k < dynamic; ++k) {
    const uint32_t i = st.simulated[k];
    const uint32_t p = next_packet[st.side[k]]++;
    st.packet_of[i] = p;
    st.masses[p].body = i;
  }
  for (uint32_t i = 0, p = st.half_start[kHalves]; kinematic > 0 && i < n; ++i) {
    if (bodies.motion[i] != uint8_t(MotionType::Kinematic)) continue;
    st.packet_of[i] = p;
    st.masses[p++].body = i;
  }
}

void load_packets(const BodyStore& bodies, SolverState& st, int participants) {
  const uint32_t count = uint32_t(st.packets.size());
  auto fill_packets = [&](uint32_t begin, uint32_t end) {
    for (uint32_t k = begin; k < end; ++k) {
      SolverBodyMass& mass = st.masses[k];
      const uint32_t i = mass.body;
      SolverBody& b = st.packets[k];
      b.v = bodies.linear_velocity(i);
      b.w = bodies.angular_velocity(i);
      b.dp.setZero();
      b.dtheta.setZero();
      b.dq = Quat::Identity();
      const bool dynamic = bodies.is_dynamic(i);
      mass.inv_mass = dynamic ? bodies.inv_mass[i] : 0;
      const Vec3 inv_i(bodies.inv_ix[i], bodies.inv_iy[i], bodies.inv_iz[i]);
      const Quat q = bodies.orientation(i);
      mass.inv_inertia = dynamic ? rotate_diagonal(q, inv_i) : SymMat3{};
      mass.gyroscopic = dynamic && !(inv_i.x() == inv_i.y() && inv_i.y() == inv_i.z());
    }
  };
  // Block h < kHalves: half h; block kHalves: the kinematic packets. determinism: a block writes
  // only its own packets.
  std::vector<StageSpec>& stages = st.stages;
  stages.assign({{kHalves + 1, 0, 0}});
  st.executor.run(
      stages, std::min(participants, int(kHalves)), [&](const StageSpec&, uint32_t block) {
        fill_packets(st.half_start[block], block < kHalves ? st.half_start[block + 1] : count);
      });
}

}  // namespace elan::detail
