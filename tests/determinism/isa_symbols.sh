#!/bin/sh
# SPDX-License-Identifier: MIT
# The SIMD paths of a dispatching build stay apart (core/base/isa.hpp, cmake/isa_rename.sh):
#   isa_symbols.sh NM OBJDUMP BINARY "AVX2 OBJECTS" "AVX512 OBJECTS"   (object lists ;-separated)
# 1. Every function an AVX2 or AVX-512 object defines for the linker (T, W) and every vtable it
#    emits carries its level's tag (the isa_<level> namespace or the .isa_<level> suffix), so no
#    copy of an inline function or template can stand in for the SSE2 one.
# 2. In the linked BINARY, no global function without an AVX tag touches a ymm or zmm register:
#    the SSE2 path and everything outside the solver's kernels run on any x86-64.
# 3. The AVX-512 kernels do use zmm registers (so 2 checked something).
set -eu
nm_tool=$1
objdump_tool=$2
binary=$3
fail=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

check_objects() {
  tag=$1
  list=$2
  old_ifs=$IFS
  IFS=';'
  for o in $list; do
    IFS=$old_ifs
    "$nm_tool" --defined-only -P "$o" |
      awk -v t="$tag" -v f="$o" '($2 == "T" || $2 == "W" || ($2 == "V" && $1 ~ /^_ZTV/)) && index($1, t) == 0 {
        print f ": " $1 " (" $2 ") has no " t " tag" }' >>"$tmp/untagged"
    IFS=';'
  done
  IFS=$old_ifs
}
: >"$tmp/untagged"
check_objects isa_avx2 "$4"
check_objects isa_avx512 "$5"
if [ -s "$tmp/untagged" ]; then
  echo "FAIL: per-level objects define shared symbols:"
  head -20 "$tmp/untagged"
  fail=1
fi

"$nm_tool" --defined-only -P "$binary" | awk '$2 == "T" || $2 == "W" { print $1 }' | sort -u \
  >"$tmp/globals"
"$objdump_tool" -d --no-show-raw-insn "$binary" |
  awk '/^[0-9a-f]+ <.*>:$/ { name = substr($2, 2, length($2) - 3); next }
       /%[yz]mm[0-9]/ { print name }' | sort -u >"$tmp/wide"
comm -12 "$tmp/globals" "$tmp/wide" | grep -v 'isa_avx' >"$tmp/leaks" || true
if [ -s "$tmp/leaks" ]; then
  echo "FAIL: functions outside the AVX paths use ymm/zmm registers:"
  head -20 "$tmp/leaks"
  fail=1
fi
if ! grep -q 'isa_avx512' "$tmp/wide"; then
  echo "FAIL: no AVX-512 kernel in $binary uses a zmm or ymm register"
  fail=1
fi
[ "$fail" -eq 0 ] && echo "ok: $(grep -c isa_avx "$tmp/wide") AVX functions, all tagged"
exit "$fail"
