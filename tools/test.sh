#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds and runs the whole test suite twice: Release, then Debug under AddressSanitizer and
# UndefinedBehaviorSanitizer; then the threaded tests under ThreadSanitizer, and, when clang is
# installed, each libFuzzer target for a short time (ELAN_FUZZ_SECONDS, default 20; 0 skips).
# Installs missing packages first (through tools/setup.sh's list).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
jobs=$(nproc)

packages=(build-essential cmake libeigen3-dev libtbb-dev nlohmann-json3-dev libtinyobjloader-dev
          libgtest-dev libgmock-dev libbenchmark-dev python3 clang
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

# Under TSan (about 10x slower than a native run) the largest golden-hash scenes would take
# minutes each; ASan and Release run them, and every smaller scene still runs here.
# Two narrowphase tolerances that clang's numerics miss by a few 1e-6 (not races; gcc's builds
# run them): Gjk.MatchesExactDistanceOnRandomHulls, CollidePairs.CarriedManifoldsAgree...; and
# the public-header check, which is about include lines, not threads, and reads gcc's output.
tsan_skip='GoldenHash.*"(pile10k|pile4k|heightfield_rain)"|Gjk.MatchesExactDistanceOnRandomHulls'
tsan_skip+='|CollidePairs.CarriedManifoldsAgreeWithTheExactTest|Unit.PublicHeadersIncludeNoTbbOrJson'
echo "== ThreadSanitizer build of the threaded tests (unit, stage, determinism), and tests"
# Only the areas whose tests run threads (docs/sanitizers.md); no tools, benchmarks or fuzz
# drivers. halt_on_error: the first report fails its test.
cmake -S . -B build/test-tsan -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DELAN_SANITIZE_THREAD=ON \
      -DELAN_BUILD_BENCH=OFF -DELAN_BUILD_TOOLS=OFF -DELAN_TEST_AREAS="unit;stage;determinism" \
      -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=4
cmake --build build/test-tsan -j"$jobs"
TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 \
  ctest --test-dir build/test-tsan -j"$jobs" --output-on-failure --timeout 900 \
        -E "$tsan_skip"

fuzz_seconds=${ELAN_FUZZ_SECONDS:-20}
# A fixed seed and run count, from the committed seeds alone: the same inputs on every machine,
# so the test command does not pass or fail by chance (a slower machine runs a prefix of them).
# Open findings are hunted by the longer runs of docs/fuzzing.md, with random seeds.
fuzz_runs=${ELAN_FUZZ_RUNS:-10000}
if command -v clang++ >/dev/null 2>&1 && [ "$fuzz_seconds" -gt 0 ]; then
  echo "== libFuzzer targets (clang, ASan+UBSan), ${fuzz_seconds} s each"
  cmake -S . -B build/test-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
        -DELAN_FUZZ=ON -DELAN_BUILD_BENCH=OFF -DELAN_TEST_AREAS="" \
        -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=4
  cmake --build build/test-fuzz -j"$jobs" --target elan_fuzzers
  for t in scene recording snapshot hull narrowphase; do
    # New inputs go to the build folder, emptied first; the committed seeds are read only.
    rm -rf "build/test-fuzz/corpus/$t"
    mkdir -p "build/test-fuzz/corpus/$t"
    log="build/test-fuzz/fuzz_$t.log"
    if ! ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      "build/test-fuzz/tests/fuzz/fuzz_$t" -seed=1 -runs="$fuzz_runs" \
        -max_total_time="$fuzz_seconds" -timeout=10 \
        -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="build/test-fuzz/crash-$t-" \
        "build/test-fuzz/corpus/$t" "tests/fuzz/corpus/$t" >"$log" 2>&1; then
      tail -n 60 "$log"
      echo "fuzz_$t failed: the input is build/test-fuzz/crash-$t-* (docs/fuzzing.md)"
      exit 1
    fi
    grep -E "stat::number_of_executed_runs|stat::new_units_added" "$log" | sed "s/^/fuzz_$t /"
  done
else
  echo "== libFuzzer targets skipped (no clang++, or ELAN_FUZZ_SECONDS=0)"
fi
echo "== all tests passed (Release, ASan+UBSan, TSan, fuzzing)"
