// SPDX-License-Identifier: MIT
// The instruction set a translation unit is compiled for, as a namespace. A portable build
// compiles the hot solver units once per x86-64 level (ELAN_DISPATCH; cmake/isa_variants.cmake
// passes -DELAN_ISA=isa_avx2 or isa_avx512 with that level's flags); the default compile of the
// same units is the SSE2 path, and a native build (-march=native) has the one path isa_native.
// Functions compiled per level are declared and defined between ELAN_ISA_BEGIN and ELAN_ISA_END,
// so each level's copy has its own name (elan::detail::isa_avx2::solve, ...) and callers in one
// unit reach their own level's copy unqualified. Inline functions and templates the units share
// (the engine's headers, Eigen, the standard library) are renamed per level after compiling
// (cmake/isa_rename.sh): the linker must never merge an AVX-512 copy with the SSE2 one.
#pragma once

#if !defined(ELAN_ISA)
#if defined(ELAN_DISPATCH)
#define ELAN_ISA isa_sse2
#else
#define ELAN_ISA isa_native
#endif
#endif

#define ELAN_ISA_BEGIN inline namespace ELAN_ISA {
#define ELAN_ISA_END }

// The first opening of the level's namespace in every unit must say `inline`.
namespace elan::detail {
ELAN_ISA_BEGIN
ELAN_ISA_END
}  // namespace elan::detail
