# SPDX-License-Identifier: MIT
# Run-time dispatch (ELAN_DISPATCH; ARCHITECTURE.md, "SIMD paths"): the hot units of a stage
# library are compiled once more per x86-64 level above the baseline, into the library.
#
# Each level's units get -DELAN_ISA=isa_<level> (core/base/isa.hpp: their functions live in that
# namespace), the level's flags, and Eigen as the SSE2 build reads it (core/base/eigen_sse2.hpp).
# No fused multiply-add on any path (it rounds once where the SSE2 path rounds twice): the engine
# uses no FMA intrinsic, -ffp-contract=off keeps the compiler from fusing, and Eigen never sees
# __FMA__. (-mno-fma would be clearer, but clang's -mno-fma turns AVX-512 off.) The AVX-512 level
# is what the transposed lane loads of solver/body_lanes.hpp need (F, VL) and x86-64-v4 names.
set(ELAN_ISA_FLAGS_avx2 -mavx -mavx2 -mbmi -mbmi2 -mpopcnt -msse3 -mssse3 -msse4.1 -msse4.2)
set(ELAN_ISA_FLAGS_avx512 ${ELAN_ISA_FLAGS_avx2} -mavx512f -mavx512vl -mavx512bw -mavx512dq
                          -mavx512cd)

# elan_isa_variants(<library> <source>...): the sources (already in <library>, as its SSE2 path)
# compiled again per level into <library>. Their objects pass through cmake/isa_rename.sh.
function(elan_isa_variants library)
  foreach(level avx2 avx512)
    set(objects ${library}_${level})
    add_library(${objects} OBJECT ${ARGN})
    # elan_base brings the include directories, Eigen and TBB, as to every stage library.
    target_link_libraries(${objects} PRIVATE elan_options elan_base)
    target_compile_definitions(${objects} PRIVATE ELAN_ISA=isa_${level})
    target_compile_options(${objects} PRIVATE ${ELAN_ISA_FLAGS_${level}} -include
                           ${PROJECT_SOURCE_DIR}/core/base/eigen_sse2.hpp)
    set(launcher sh ${PROJECT_SOURCE_DIR}/cmake/isa_rename.sh isa_${level} ${CMAKE_NM}
                 ${CMAKE_OBJCOPY})
    if(CMAKE_CXX_COMPILER_LAUNCHER)
      list(APPEND launcher ${CMAKE_CXX_COMPILER_LAUNCHER})
    endif()
    set_target_properties(${objects} PROPERTIES POSITION_INDEPENDENT_CODE ON
                                                CXX_COMPILER_LAUNCHER "${launcher}")
    target_sources(${library} PRIVATE $<TARGET_OBJECTS:${objects}>)
  endforeach()
endfunction()
