// SPDX-License-Identifier: MIT
// The solver stages compiled once per instruction set (core/base/isa.hpp), as a table run_step
// calls through: one indirect call per stage, chosen once when the world is made.
#pragma once

#include <cstdint>
#include <span>

#include "core/base/body_store.hpp"
#include "core/base/contact.hpp"
#include "core/base/isa.hpp"
#include "core/base/shape.hpp"
#include "elan/defs.hpp"
#include "solver/solve.hpp"

namespace elan::detail {

struct SolverKernels {
  SimdPath path = SimdPath::Native;
  void (*prepare_contacts)(const BodyStore& bodies, std::span<const ManifoldHead> contacts,
                           std::span<const ManifoldTail> tails, const SolveSettings& settings,
                           SolverState& st) = nullptr;
  void (*solve)(const BodyStore& bodies, std::span<ManifoldHead> contacts,
                std::span<ManifoldTail> tails, const SolveSettings& settings,
                SolverState& state) = nullptr;
  uint32_t (*finalize_bodies)(BodyStore& bodies, std::span<const Shape> shapes,
                              const SolveSettings& settings, SolverState& state) = nullptr;
};

ELAN_ISA_BEGIN
// This unit's instruction set's kernels (solver_kernels.cpp, compiled once per set).
extern const SolverKernels kSolverKernels;
ELAN_ISA_END

// The kernels of path `want`. Best: the path the environment variable ELAN_SIMD names when it is
// set (an Error on field "ELAN_SIMD" when it names no path or one this CPU or build lacks), else
// the widest this CPU runs. Any other path: that one, or an Error on field "simd".
const SolverKernels& select_solver_kernels(SimdPath want);

}  // namespace elan::detail
