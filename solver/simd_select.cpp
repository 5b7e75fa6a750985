// SPDX-License-Identifier: MIT
// Choosing the solver kernels' instruction set: once per world, from CPUID and ELAN_SIMD.
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/base/simd_path.hpp"
#include "elan/error.hpp"
#include "solver/solver_kernels.hpp"

namespace elan::detail {

#if defined(ELAN_DISPATCH)
namespace isa_avx2 {
extern const SolverKernels kSolverKernels;
}
namespace isa_avx512 {
extern const SolverKernels kSolverKernels;
}
#endif

namespace {

#if defined(ELAN_DISPATCH)
const SolverKernels& kernels_of(SimdPath path) {
  switch (path) {
    case SimdPath::Avx512:
      return isa_avx512::kSolverKernels;
    case SimdPath::Avx2:
      return isa_avx2::kSolverKernels;
    default:
      return isa_sse2::kSolverKernels;
  }
}
#else
const SolverKernels& kernels_of(SimdPath) {
  return kSolverKernels;
}
#endif

const SolverKernels& checked(SimdPath path, const char* field) {
  if (!cpu_runs(path)) {
#if defined(ELAN_DISPATCH)
    throw Error(field, std::string("this CPU cannot run the ") + simd_path_name(path) +
                           " path (it runs up to " + simd_path_name(widest_simd_path()) + ")");
#else
    throw Error(field, std::string("this build was compiled for one CPU (ELAN_NATIVE) and has "
                                   "only the native path, not ") +
                           simd_path_name(path));
#endif
  }
  return kernels_of(path);
}

}  // namespace

}  // namespace elan::detail

namespace elan {

const char* simd_path_name(SimdPath path) {
  switch (path) {
    case SimdPath::Best:
      return "best";
    case SimdPath::Sse2:
      return "sse2";
    case SimdPath::Avx2:
      return "avx2";
    case SimdPath::Avx512:
      return "avx512";
    case SimdPath::Native:
      return "native";
  }
  return "unknown";
}

}  // namespace elan

namespace elan::detail {

const SolverKernels& select_solver_kernels(SimdPath want) {
  if (want != SimdPath::Best) return checked(want, "simd");
  const char* env = std::getenv("ELAN_SIMD");
  if (env == nullptr || *env == '\0') return kernels_of(widest_simd_path());
  const std::string_view name(env);
  for (const SimdPath p : {SimdPath::Sse2, SimdPath::Avx2, SimdPath::Avx512, SimdPath::Native}) {
    if (name == simd_path_name(p)) return checked(p, "ELAN_SIMD");
  }
  throw Error("ELAN_SIMD", "'" + std::string(name.substr(0, 32)) +
                               "' is not a SIMD path (sse2, avx2, avx512 or native)");
}

}  // namespace elan::detail
