// SPDX-License-Identifier: MIT
// The table of this instruction set's solver kernels. A portable build compiles this unit once per
// level with the stages' units (solver/CMakeLists.txt), so each level's table points at its own
// copies.
#include "solver/solver_kernels.hpp"

#include <string_view>

#include "solver/bundles.hpp"

namespace elan::detail {
ELAN_ISA_BEGIN

namespace {
#define ELAN_ISA_STRING_(x) #x
#define ELAN_ISA_STRING(x) ELAN_ISA_STRING_(x)
constexpr SimdPath this_path() {
  constexpr std::string_view name = ELAN_ISA_STRING(ELAN_ISA);
  if (name == "isa_sse2") return SimdPath::Sse2;
  if (name == "isa_avx2") return SimdPath::Avx2;
  if (name == "isa_avx512") return SimdPath::Avx512;
  return SimdPath::Native;
}
#undef ELAN_ISA_STRING
#undef ELAN_ISA_STRING_
}  // namespace

const SolverKernels kSolverKernels = {this_path(), &prepare_contacts, &solve, &finalize_bodies};

ELAN_ISA_END
}  // namespace elan::detail
