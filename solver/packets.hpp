// SPDX-License-Identifier: MIT
// The solver's body packets: which bodies the solve moves, in which half (partition.hpp), and each
// one's state for the step. Two stages, run one after the other by run_step.
#pragma once

#include <cstdint>

#include "core/base/body_store.hpp"
#include "core/base/step_scratch.hpp"
#include "solver/solve.hpp"

namespace elan::detail {

// Stage: the median cut and the packet layout. The simulated bodies are the awake dynamic ones
// that are not frozen; split_in_halves cuts them in two. Packet 0 is the static dummy; then the
// simulated bodies of half 0, of half 1, then every kinematic body, each in index order, so that
// each is one range of packets. Kinematic bodies are apart: contacts of both halves read them, so
// they move in stages of their own (solve()).
//
// Reads: motion types, flags (awake, frozen), positions. Writes: st.simulated (ascending),
// st.side, st.half_start, st.packet_of (0 for a body not in a packet), st.masses[k].body, and
// sizes st.packets and st.masses (load_packets fills them). Serial. Scratch: st.split_keys, taken
// from `scratch` and given back.
void split_halves(const BodyStore& bodies, SolverState& st, StepScratch& scratch);

// Stage: the packets' step constants: velocities, a zero pose change, the world inverse inertia.
//
// Reads: st.masses[k].body, st.half_start; the bodies' velocities, orientations, inverse mass and
// inertia. Writes: st.packets[k] and st.masses[k]'s inverse mass, inverse inertia and gyroscopic
// flag for every packet k > 0. Parallel through st.executor: one block per half and one for the
// kinematic packets; each packet is written by its block alone.
void load_packets(const BodyStore& bodies, SolverState& st, int participants);

}  // namespace elan::detail
