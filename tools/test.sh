#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds and runs the whole test suite twice: Release, then Debug under AddressSanitizer and
# UndefinedBehaviorSanitizer. Installs missing packages first (through tools/setup.sh's list).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
jobs=$(nproc)

packages=(build-essential cmake libeigen3-dev libtbb-dev nlohmann-json3-dev libtinyobjloader-dev
          libgtest-dev libgmock-dev libbenchmark-dev python3
          # the viewer (elan view) and its picture tests under Xvfb on Mesa's software renderer
          libglfw3-dev libimgui-dev libstb-dev libgl-dev libgl1-mesa-dri xvfb xauth)
missing=()
for p in "${packages[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${missing[@]}"
fi

# Release is tuned for this CPU, as tools/setup.sh builds it (with AVX-512, sixteen SIMD lanes and
# the transposed lane loads); the sanitized Debug build below is portable, so both code paths run.
echo "== Release build (-march=native) and tests"
cmake -S . -B build/test-release -DCMAKE_BUILD_TYPE=Release -DELAN_NATIVE=ON
cmake --build build/test-release -j"$jobs"
# Under a virtual X server, so that the viewer's picture tests have a display (they skip without).
xvfb-run -a ctest --test-dir build/test-release -j"$jobs" --output-on-failure --timeout 300

echo "== Debug build with AddressSanitizer + UndefinedBehaviorSanitizer, and tests"
# -O1 keeps the sanitized physics tests fast enough; benchmarks are not built here. -g1 (line
# tables, no variables) is all a sanitizer's stack trace reads, and builds faster than -g. The
# engine's files are compiled four at a time as one unit here (the test files always are), which
# shares the parsing of Eigen and TBB. The Release build above compiles the engine file by file,
# as users build it.
cmake -S . -B build/test-asan -DCMAKE_BUILD_TYPE=Debug -DELAN_SANITIZE=ON -DELAN_BUILD_BENCH=OFF \
      -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=4
cmake --build build/test-asan -j"$jobs"
# The viewer's picture tests skip here (no DISPLAY): the system's OpenGL driver they would load
# is not instrumented; its command-line errors, which open no window, are still tested.
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  env -u DISPLAY -u WAYLAND_DISPLAY ctest --test-dir build/test-asan -j"$jobs" --output-on-failure --timeout 600
echo "== all tests passed (Release and ASan+UBSan)"
