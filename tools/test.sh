#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds and runs the whole test suite: the portable Release build; the golden hashes again in a
# native (-march=native) build, which must give the same bits; the suite under AddressSanitizer
# and UndefinedBehaviorSanitizer (clang), then each libFuzzer target for a short time from that
# build, beside the next build (ELAN_FUZZ_SECONDS, default 20; 0 skips); the threaded tests under
# ThreadSanitizer.
# Installs missing packages first (through tools/setup.sh's list).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
jobs=$(nproc)

packages=(build-essential cmake libeigen3-dev libtbb-dev nlohmann-json3-dev libtinyobjloader-dev
          libgtest-dev libgmock-dev libbenchmark-dev python3 clang
          # the viewer (elan view) and its picture tests under Xvfb on Mesa's software renderer
          libglfw3-dev libimgui-dev libstb-dev libgl-dev libgl1-mesa-dri xvfb xauth
          # the Python package and its tests (Debian's interpreter, /usr/bin/python3)
          pybind11-dev python3-dev python3-numpy python3-pandas python3-distributed python3-pytest
          python3-matplotlib python3-tqdm python3-yaml)
missing=()
for p in "${packages[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${missing[@]}"
fi

# The first build is the one users get from a plain Release configure: portable, with the SIMD
# path chosen at run time for this CPU. It runs every test, under a virtual X server so that the
# viewer's picture tests have a display (they skip without one), and the Python tests. Its files
# are compiled eight at a time as one unit, as in the builds below, which shares the parsing of
# the headers (Eigen, TBB, GoogleTest). With no contraction into FMA, how the code is inlined
# changes no bit, and the golden hashes, made by a build of one file per unit, check that here.
# The test executables are compiled at -O1 (the engine they link at -O3): that takes a third
# less time, and a test's time is spent in the engine. (Not lower: at -O0 the test's copies of
# the header functions, which the linker may take for the engine's, slow the engine down too.)
echo "== Release build (portable) and tests"
cmake -S . -B build/test-release -DCMAKE_BUILD_TYPE=Release -DELAN_TEST_COMPILE_OPTIONS=-O1 \
      -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=8
cmake --build build/test-release -j"$jobs"
# -noreset: by default Xvfb resets when its last client leaves, and a viewer test that connects
# during the reset gets no display.
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
  ctest --test-dir build/test-release -j"$jobs" --output-on-failure --timeout 300

# The same source built for this machine (-march=native) must give the same bits: only the engine
# and the golden-hash tests are built, and each scene's hash is checked against the same constant
# as in the portable build above (one run a scene: the portable build checks that other thread
# counts and broadphases agree). Its files are compiled eight at a time as one unit: with no
# contraction into FMA, how the code is inlined changes no bit.
echo "== Native build (-march=native): the golden hashes"
cmake -S . -B build/test-native -DCMAKE_BUILD_TYPE=Release -DELAN_NATIVE=ON \
      -DELAN_BUILD_TOOLS=OFF -DELAN_BUILD_BENCH=OFF -DELAN_TEST_AREAS=determinism \
      -DELAN_TEST_COMPILE_OPTIONS=-O1 \
      -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=8
cmake --build build/test-native -j"$jobs" --target test_determinism
ctest --test-dir build/test-native -j"$jobs" --output-on-failure --timeout 300 -R "GoldenHash"

# The suite under AddressSanitizer + UndefinedBehaviorSanitizer, with clang, in the build that
# also makes the libFuzzer targets: one instrumented engine serves both. It carries libFuzzer's
# edge coverage (a counter per branch, cheap) but not its comparison tracing (a callback on every
# comparison, which more than doubled the suite's time); the longer runs of docs/fuzzing.md have
# both. -O1 keeps the sanitized physics tests fast enough; -g1 (line tables) is all a sanitizer's
# stack trace reads. The files are compiled eight at a time as one unit, which shares the
# parsing of the headers. No viewer or benchmarks here: the viewer's picture tests would skip (no
# display, and the system's OpenGL driver is not instrumented); its command-line errors, which
# open no window, are still tested through elan.
# Skipped here, each run by the Release build above:
# - the four largest golden-hash scenes (the longest runs under the sanitizers; smaller scenes
#   cover the same stages), and the native build checks their constants too; the three
#   pyramids, whose stages pyramid10 and tower20 run;
# - the tests that repeat a whole run at other thread counts and broadphases to compare hashes:
#   the ThreadSanitizer build below runs them, and the code they reach here is run once by the
#   golden scenes and the stage tests;
# - four long settling runs (a 30x30 joint grid, a 500-body pile, a mixed pile, a 20-row pyramid)
#   whose stages smaller physics tests run;
# - the warm pyramid's allocation count (260 steps of jolt_pyramid): the count is the
#   Release build's to check, ThreadSanitizer runs it too, and pyramid10 and tower20 reach its
#   stages;
# - two more golden-hash scenes, ragdolls and convex_vs_mesh (long under ASan): chains and the
#   ragdoll heap run the same joints, geometry_demo and the geometry tests the same surfaces;
# - the step buffers' accounting over 120 steps of pile4k, which counts bytes, and
#   whose stages pile1k runs; and the time of impact's oracle over 240 paths, whose
#   code the geometry scenes run;
# - more tests whose check is that two runs give the same hashes (at other thread counts or
#   broadphases, run twice in one process, rolled back and run again, loaded at 1 and 2 threads):
#   the ThreadSanitizer build and the Release build run them, and the code they reach is run here
#   by the snapshot, rollback and soak tests that stay; with them the tumbler scene (kinematic
#   bodies, which the API tests move) and the sweep's 20,000-box match (the moving scene's match
#   runs the same code);
# - the public-header check, which reads gcc's include output.
clang_skip='GoldenHash.*"(pile10k|pile4k|heightfield_rain|joint_grid)"|Unit.PublicHeadersIncludeNoTbbOrJson'
asan_skip="$clang_skip"'|GoldenHash.*"(pyramid20|many_pyramids|jolt_pyramid)"'
asan_skip+='|Determinism.HashEqualEveryStepForAnyThreadCountAndBroadphase|Determinism.TumblerHashEqual'
asan_skip+='|GeometryDeterminism.HashEqualEveryStep|GeometryWorld.SameHashesForAnyThreadCount'
asan_skip+='|JointSettling.JointGridHangsFromItsPins|Pile.Pile1kSettlesInItsContainer|Stacking.Pyramid20Stands'
asan_skip+='|StepAllocations.NoneOnceAPyramidIsWarm|GoldenHash.*"(ragdolls|convex_vs_mesh)"'
asan_skip+='|MemoryUse.StepBuffersAreGivenBackWithinTheStep|TimeOfImpact.SurfaceImpactIsTheEarliest'
asan_skip+='|Determinism.SameHashesWhenRunTwiceInProcess|Determinism.OneAndTwoThreadsSideBySide'
asan_skip+='|Rollback.RollingBackAndRunningAgainGivesTheSameHashes|JointDeterminism.SameHashesForAnyThread'
asan_skip+='|Snapshot.LoadedWorldContinuesBitIdenticallyAtOneAndTwoThreads|CrowdDeterminism.SameHash'
asan_skip+='|GoldenHash.*"tumbler"|SweepAndPrune.MatchesBruteForceOnTwentyThousandBoxes'
asan_skip+='|Pile.MixedPileSettlesInItsContainer'
echo "== clang build with ASan + UBSan (and the fuzz targets), and tests"
cmake -S . -B build/test-asan -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
      -DELAN_FUZZ=ON -DELAN_FUZZ_TRACE_CMP=OFF \
      -DELAN_BUILD_BENCH=OFF -DELAN_BUILD_VIEWER=OFF -DELAN_BUILD_PYTHON=OFF \
      -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=8
cmake --build build/test-asan -j"$jobs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  env -u DISPLAY -u WAYLAND_DISPLAY ctest --test-dir build/test-asan -j"$jobs" --output-on-failure \
      --timeout 600 -E "$asan_skip"

fuzz_seconds=${ELAN_FUZZ_SECONDS:-20}
# A fixed seed and run count, from the committed seeds alone: the same inputs on every machine,
# so the test command does not pass or fail by chance (a slower machine runs a prefix of them).
# Open findings are hunted by the longer runs of docs/fuzzing.md, with random seeds.
fuzz_runs=${ELAN_FUZZ_RUNS:-10000}
run_fuzz_targets() {
  for t in scene recording snapshot hull narrowphase; do
    # New inputs go to the build folder, emptied first; the committed seeds are read only.
    rm -rf "build/test-asan/corpus/$t"
    mkdir -p "build/test-asan/corpus/$t"
    log="build/test-asan/fuzz_$t.log"
    if ! ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      "build/test-asan/tests/fuzz/fuzz_$t" -seed=1 -runs="$fuzz_runs" \
        -max_total_time="$fuzz_seconds" -timeout=30 \
        -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="build/test-asan/crash-$t-" \
        "build/test-asan/corpus/$t" "tests/fuzz/corpus/$t" >"$log" 2>&1; then
      tail -n 60 "$log"
      echo "fuzz_$t failed: the input is build/test-asan/crash-$t-* (docs/fuzzing.md)"
      return 1
    fi
    grep -E "stat::number_of_executed_units|stat::new_units_added" "$log" | sed "s/^/fuzz_$t /"
  done
}
# The targets run one after another, on one core, beside the ThreadSanitizer build below, so
# that the other core does not wait idle for them. Sharing a core with the compiler, a target
# takes longer than alone (about 5 s for its 10,000 inputs), so each is allowed 20 s. Their
# report is printed, and a failure stops the command, before the ThreadSanitizer tests.
# One input may take 30 s before it counts as a hang: the scene target still parses the largest
# scenes the format allows, which under the sanitizers beside a build can pass 10 s
# (docs/fuzzing.md).
fuzz_pid=""
if [ "$fuzz_seconds" -gt 0 ]; then
  echo "== libFuzzer targets (the build above), at most ${fuzz_seconds} s each, beside the next build"
  run_fuzz_targets >build/test-asan/fuzz.out 2>&1 &
  fuzz_pid=$!
  trap 'pkill -P "$fuzz_pid" 2>/dev/null; kill "$fuzz_pid" 2>/dev/null || true' EXIT
else
  echo "== libFuzzer targets skipped (ELAN_FUZZ_SECONDS=0)"
fi

# Under TSan (about 10x slower than a native run), skipped:
# - not built (tests/CMakeLists.txt): the unit and stage test files that run no threads
#   (ELAN_SINGLE_THREADED_TESTS), which the two builds above run; and the golden-hash scenes:
#   sanitized, each runs once at one thread (physics_util.hpp), where no race can show, and the
#   ASan build above checks the same constants in a clang build; the determinism tests run scenes
#   at 1-4 threads and both broadphases here;
# - the step buffers' accounting, which runs no threads;
# - the snapshot and rollback format tests (sizes, refused states, resealed bytes, settings),
#   whose threads only step the world they save, as the restore tests that stay do; pile1k run
#   twice in one process, and the sweep's 20,000-box match, whose threaded code the moving
#   scene's match and the determinism tests run;
# - the public-header check, as above.
tsan_skip='Unit.PublicHeadersIncludeNoTbbOrJson'
tsan_skip+='|MemoryUse.StepBuffersAreGivenBackWithinTheStep'
tsan_skip+='|Rollback.(SizeIsEightyOne|AnotherWorldsState|CorruptOrTruncated)|SnapshotSurfaces.Resealed'
tsan_skip+='|Snapshot.(RestoresSettingsStepCountAndShapes|SavingALoadedWorldGivesTheSameBytes)'
tsan_skip+='|Determinism.SameHashesWhenRunTwiceInProcess|SweepAndPrune.MatchesBruteForceOnTwentyThousandBoxes'
echo "== ThreadSanitizer build of the threaded tests (unit, stage, determinism), and tests"
# Only the areas whose tests run threads (docs/sanitizers.md); no tools, benchmarks or fuzz
# drivers. halt_on_error: the first report fails its test.
cmake -S . -B build/test-tsan -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DELAN_SANITIZE_THREAD=ON \
      -DELAN_BUILD_BENCH=OFF -DELAN_BUILD_TOOLS=OFF -DELAN_BUILD_PYTHON=OFF \
      -DELAN_TEST_AREAS="unit;stage;determinism" \
      -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=8
cmake --build build/test-tsan -j"$jobs"
if [ -n "$fuzz_pid" ]; then
  fuzz_status=0
  wait "$fuzz_pid" || fuzz_status=$?
  trap - EXIT
  echo "== libFuzzer targets' report"
  cat build/test-asan/fuzz.out
  [ "$fuzz_status" -eq 0 ] || exit 1
fi
TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:ignore_noninstrumented_modules=1 \
  ctest --test-dir build/test-tsan -j"$jobs" --output-on-failure --timeout 900 \
        -E "$tsan_skip"
echo "== all tests passed (Release, native golden hashes, ASan+UBSan, fuzzing, TSan)"
