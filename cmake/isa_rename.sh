#!/bin/sh
# SPDX-License-Identifier: MIT
# Compiler launcher of the per-instruction-set units (cmake/isa_variants.cmake):
#   isa_rename.sh SUFFIX NM OBJCOPY COMPILER ARGS...
# runs the compile, then renames every weak function the object defines (the inline functions and
# template instances it emits: the engine's headers, Eigen, the standard library) to NAME.SUFFIX,
# definitions and this object's calls alike. The linker keeps one copy of a weak function by
# name; without the rename it could keep the AVX-512 copy for the SSE2 path, or the SSE2 copy
# for the AVX-512 path. Objects of one level share the suffix, so they still share their copies.
set -e
suffix=$1
nm_tool=$2
objcopy_tool=$3
shift 3
"$@"
out=
prev=
for arg in "$@"; do
  if [ "$prev" = "-o" ]; then out=$arg; fi
  prev=$arg
done
[ -n "$out" ] || exit 0
map="$out.isa-rename"
"$nm_tool" --defined-only -P "$out" | awk -v s="$suffix" '$2 == "W" { print $1, $1 "." s }' >"$map"
if [ -s "$map" ]; then "$objcopy_tool" --redefine-syms="$map" "$out"; fi
rm -f "$map"
