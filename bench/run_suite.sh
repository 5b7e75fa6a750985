#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The benchmark suite in one command: builds Release (-march=native) into build/bench, runs the
# calibration kernels, the scenes, the joint scenes, the geometry scenes (convex_vs_mesh,
# heightfield_rain, compounds), the pile sweep and the Bullet peer in one interleaved run,
# measures peak RSS of elan and Bullet on pile10k in separate processes, and writes CSVs, a
# Markdown summary and plots to bench/results/<cpu-model>/ (the raw output stays in its raw/,
# which git ignores). Needs gnuplot for the plots (tools/setup.sh installs gnuplot-nox).
# Usage: bench/run_suite.sh [--quick|--full]   (quick: under 3 minutes on 2 cores)
# Environment: ELAN_BENCH_BUILD (build dir, default build/bench), ELAN_BENCH_JOBS (default 1).
set -euo pipefail
if ! command -v gnuplot >/dev/null; then
  echo "bench/run_suite.sh: gnuplot is needed for the plots: apt-get install gnuplot-nox" >&2
  exit 2
fi

mode=quick
for arg in "$@"; do
  case "$arg" in
    --quick) mode=quick ;;
    --full) mode=full ;;
    *) echo "usage: bench/run_suite.sh [--quick|--full]" >&2; exit 2 ;;
  esac
done

root=$(cd "$(dirname "$0")/.." && pwd)
build=${ELAN_BENCH_BUILD:-$root/build/bench}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DELAN_NATIVE=ON -DELAN_BUILD_TESTS=OFF \
  >/dev/null
targets="bench_scenes elan_cli"
if grep -q '^ELAN_BULLET_DYNAMICS:FILEPATH=/' "$build/CMakeCache.txt"; then
  targets="$targets bullet_runner"
fi
# shellcheck disable=SC2086
cmake --build "$build" --target $targets -j"${ELAN_BENCH_JOBS:-1}" >/dev/null

cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed -e 's/([^)]*)//g' \
  | tr 'A-Z' 'a-z' | sed -e 's/[^a-z0-9]\{1,\}/-/g' -e 's/^-//' -e 's/-$//')
out="$root/bench/results/$cpu"
raw="$out/raw"
mkdir -p "$raw"
uptime >"$raw/uptime_start.txt"

if [ "$mode" = quick ]; then
  args=(--warmup=10 --steps=10 --reps=5 --calib_reps=5 --sweep=1000,2000,4000,8000,16000
        --sweep_warmup=20 --sweep_steps=5 --sweep_reps=1 --allpairs_max=4000
        --joint_warmup=30 --joint_steps=5 --geometry_warmup=60 --geometry_steps=5)
  rss_steps=100
else
  args=(--warmup=120 --steps=60 --reps=5 --calib_reps=7 --sweep=1000,2000,4000,8000,16000,32000
        --sweep_warmup=60 --sweep_steps=10 --sweep_reps=3 --allpairs_max=16000
        --joint_warmup=120 --joint_steps=30 --geometry_warmup=120 --geometry_steps=20)
  rss_steps=300
fi
echo "${args[*]}" >"$raw/args.txt"

# Random interleaving shuffles every (benchmark, repetition): 1- and 2-thread runs of a scene, the
# calibration kernels and Bullet alternate over the whole run, so load from other processes falls
# on all of them alike; the report takes medians.
"$build/bench/bench_scenes" "${args[@]}" --benchmark_enable_random_interleaving=true \
  --benchmark_out="$raw/bench.json" --benchmark_out_format=json >"$raw/bench.txt" 2>&1

# Peak RSS, each engine alone in its process on the same scene file and step count.
/usr/bin/time -v "$build/tools/elan" run "$root/scenes/pile10k.json" --steps "$rss_steps" \
  --threads 1 >"$raw/rss_elan.json" 2>"$raw/rss_elan.txt"
if [ -x "$build/bench/peer/bullet_runner" ]; then
  /usr/bin/time -v "$build/bench/peer/bullet_runner" "$root/scenes/pile10k.json" \
    --steps "$rss_steps" >"$raw/rss_bullet.json" 2>"$raw/rss_bullet.txt"
fi
uptime >"$raw/uptime_end.txt"

# The CSVs, then summary.md and the plots from them; fails if a plot cannot be drawn.
python3 "$root/bench/report.py" --raw "$raw" --out "$out" --build "$build" --mode "$mode" \
  --rss-steps "$rss_steps"
echo "results: $out/summary.md (raw/ is not committed)"
