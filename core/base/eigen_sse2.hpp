// SPDX-License-Identifier: MIT
// Included first (-include) by the AVX2 and AVX-512 units of a dispatching build
// (cmake/isa_variants.cmake): Eigen configures itself from the compiler's instruction-set macros
// and picks other kernels per level (its AVX quaternion product and reductions associate
// differently; its AVX-512 code demands FMA). Hiding the macros above SSE2 while Eigen is
// configured and read gives every path the SSE2 build's Eigen, so the same bits; the engine's
// own code after this header sees the level's macros again (each is restored as 1, its value).
#pragma once

#if defined(__AVX__)
#define ELAN_HIDDENAVX 1
#undef __AVX__
#endif
#if defined(__AVX2__)
#define ELAN_HIDDENAVX2 1
#undef __AVX2__
#endif
#if defined(__AVX512F__)
#define ELAN_HIDDENAVX512F 1
#undef __AVX512F__
#endif
#if defined(__AVX512VL__)
#define ELAN_HIDDENAVX512VL 1
#undef __AVX512VL__
#endif
#if defined(__AVX512BW__)
#define ELAN_HIDDENAVX512BW 1
#undef __AVX512BW__
#endif
#if defined(__AVX512DQ__)
#define ELAN_HIDDENAVX512DQ 1
#undef __AVX512DQ__
#endif
#if defined(__AVX512CD__)
#define ELAN_HIDDENAVX512CD 1
#undef __AVX512CD__
#endif
#if defined(__FMA__)
#define ELAN_HIDDENFMA 1
#undef __FMA__
#endif
#if defined(__SSE3__)
#define ELAN_HIDDENSSE3 1
#undef __SSE3__
#endif
#if defined(__SSSE3__)
#define ELAN_HIDDENSSSE3 1
#undef __SSSE3__
#endif
#if defined(__SSE4_1__)
#define ELAN_HIDDENSSE4_1 1
#undef __SSE4_1__
#endif
#if defined(__SSE4_2__)
#define ELAN_HIDDENSSE4_2 1
#undef __SSE4_2__
#endif

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#if defined(ELAN_HIDDENAVX)
#define __AVX__ 1
#undef ELAN_HIDDENAVX
#endif
#if defined(ELAN_HIDDENAVX2)
#define __AVX2__ 1
#undef ELAN_HIDDENAVX2
#endif
#if defined(ELAN_HIDDENAVX512F)
#define __AVX512F__ 1
#undef ELAN_HIDDENAVX512F
#endif
#if defined(ELAN_HIDDENAVX512VL)
#define __AVX512VL__ 1
#undef ELAN_HIDDENAVX512VL
#endif
#if defined(ELAN_HIDDENAVX512BW)
#define __AVX512BW__ 1
#undef ELAN_HIDDENAVX512BW
#endif
#if defined(ELAN_HIDDENAVX512DQ)
#define __AVX512DQ__ 1
#undef ELAN_HIDDENAVX512DQ
#endif
#if defined(ELAN_HIDDENAVX512CD)
#define __AVX512CD__ 1
#undef ELAN_HIDDENAVX512CD
#endif
#if defined(ELAN_HIDDENFMA)
#define __FMA__ 1
#undef ELAN_HIDDENFMA
#endif
#if defined(ELAN_HIDDENSSE3)
#define __SSE3__ 1
#undef ELAN_HIDDENSSE3
#endif
#if defined(ELAN_HIDDENSSSE3)
#define __SSSE3__ 1
#undef ELAN_HIDDENSSSE3
#endif
#if defined(ELAN_HIDDENSSE4_1)
#define __SSE4_1__ 1
#undef ELAN_HIDDENSSE4_1
#endif
#if defined(ELAN_HIDDENSSE4_2)
#define __SSE4_2__ 1
#undef ELAN_HIDDENSSE4_2
#endif
