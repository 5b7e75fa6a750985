// SPDX-License-Identifier: MIT
#include "core/base/simd_path.hpp"

#include <cstdlib>
#include <string_view>
#include <utility>

namespace elan::detail {

#if defined(ELAN_DISPATCH)
// What each path's units are compiled with (cmake/isa_variants.cmake): the CPU must have all of
// it. __builtin_cpu_supports also asks the OS (XGETBV) whether it saves the AVX and AVX-512
// registers.
bool cpu_runs(SimdPath path) {
  __builtin_cpu_init();
  switch (path) {
    case SimdPath::Sse2:
      return true;
    case SimdPath::Avx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") &&
             __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("popcnt");
    case SimdPath::Avx512:
      return cpu_runs(SimdPath::Avx2) && __builtin_cpu_supports("avx512f") &&
             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512cd");
    default:
      return false;
  }
}

SimdPath widest_simd_path() {
  if (cpu_runs(SimdPath::Avx512)) return SimdPath::Avx512;
  if (cpu_runs(SimdPath::Avx2)) return SimdPath::Avx2;
  return SimdPath::Sse2;
}
#else
bool cpu_runs(SimdPath path) {
  return path == SimdPath::Native;
}
SimdPath widest_simd_path() {
  return SimdPath::Native;
}
#endif

namespace {

SimdPath read_process_simd_path() {
  const char* env = std::getenv("ELAN_SIMD");
  if (env != nullptr) {
    const std::string_view name(env);
    // The names of simd_path_name (elan/defs.hpp), which lives with the solver.
    constexpr std::pair<std::string_view, SimdPath> kNames[] = {{"sse2", SimdPath::Sse2},
                                                                {"avx2", SimdPath::Avx2},
                                                                {"avx512", SimdPath::Avx512},
                                                                {"native", SimdPath::Native}};
    for (const auto& [text, path] : kNames) {
      if (name == text && cpu_runs(path)) return path;
    }
  }
  return widest_simd_path();
}

}  // namespace

SimdPath process_simd_path() {
  static const SimdPath path = read_process_simd_path();
  return path;
}

}  // namespace elan::detail
