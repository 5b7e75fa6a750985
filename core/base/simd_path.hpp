// SPDX-License-Identifier: MIT
// Which SIMD paths this CPU runs, and the path of the stages that have no world to ask (the
// narrowphase's dispatched kernels). The solver's choice per world is solver/solver_kernels.hpp.
#pragma once

#include "elan/defs.hpp"

namespace elan::detail {

// True when this CPU (and its OS, which must save the wider registers) runs `path` and this build
// has it: Sse2, Avx2 and Avx512 in a dispatching build (ELAN_DISPATCH), Native otherwise.
bool cpu_runs(SimdPath path);

// The widest path cpu_runs: Native in a build without dispatch.
SimdPath widest_simd_path();

// The path the environment variable ELAN_SIMD names when it names one the CPU runs, else the
// widest. Read once per process. Every path gives the same bits, so a stage that follows this
// rather than its world's WorldDef::simd changes no result, only its speed.
SimdPath process_simd_path();

// `path`, or process_simd_path() for Best.
inline SimdPath resolved_simd_path(SimdPath path) {
  return path == SimdPath::Best ? process_simd_path() : path;
}

}  // namespace elan::detail
