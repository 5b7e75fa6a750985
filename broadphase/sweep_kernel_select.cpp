// SPDX-License-Identifier: MIT
// Choosing the sweep's kernel by SIMD path (sweep_kernel.hpp).
#include "broadphase/sweep_kernel.hpp"
#include "core/base/simd_path.hpp"

namespace elan::detail {

#if defined(ELAN_DISPATCH)
namespace isa_avx2 {
void sweep_strips(const SweepStrips&, std::size_t, std::size_t, DeepSieve*,
                  ScratchVector<uint64_t>&);
}
namespace isa_avx512 {
void sweep_strips(const SweepStrips&, std::size_t, std::size_t, DeepSieve*,
                  ScratchVector<uint64_t>&);
}
#endif

SweepKernel sweep_kernel(SimdPath path) {
#if defined(ELAN_DISPATCH)
  switch (resolved_simd_path(path)) {
    case SimdPath::Avx512:
      return &isa_avx512::sweep_strips;
    case SimdPath::Avx2:
      return &isa_avx2::sweep_strips;
    default:
      return &isa_sse2::sweep_strips;
  }
#else
  (void)path;
  return &sweep_strips;
#endif
}

}  // namespace elan::detail
