// SPDX-License-Identifier: MIT
// The solver's two halves: the simulated bodies cut in two at the median of their centres along
// the axis of largest spread, so that each half's contacts can be solved by one thread with no
// sync, and only the contacts across the cut wait for both.
//
// perf: a colour-by-colour solve syncs every thread once per colour per pass (16 colours x 24
// passes, about 400 syncs a step on a pile), and a sync costs a cross-core round trip or more;
// the packets of each colour also move between the cores' caches. Solved as two
// halves plus the contacts that join them, a pass needs two syncs, and each core keeps its half's
// packets. This is domain decomposition in its simplest form, a cut through space; Box2D v3's
// constraint graph and Jolt's large-island splitter divide the constraints by colour instead,
// and pay a sync for each colour.
//
// determinism: the cut depends on the scene alone (positions and indices), never on the thread
// count: one thread solves half 0, half 1 and the cut in that order, two solve the halves at once
// and then the cut, with the same bits, since the halves share no dynamic body.
#pragma once

#include <cstdint>
#include <span>

#include "core/base/body_store.hpp"

namespace elan::detail {

// Writes side[k] = 0 or 1 for every body simulated[k] (dense indices): the first n / 2 bodies in
// the order of (centre along the axis of largest spread, index) go to side 0, the rest to side 1.
// A non-finite coordinate sorts last. `keys` is scratch, one per simulated body.
void split_in_halves(const BodyStore& bodies, std::span<const uint32_t> simulated,
                     std::span<uint64_t> keys, std::span<uint8_t> side);

}  // namespace elan::detail
