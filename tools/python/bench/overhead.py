# SPDX-License-Identifier: MIT
"""Costs of the Python binding (docs/python.md, bench/results/*/python.md).

1. Stepping overhead: pile1k stepped from Python (one step(n) call, and n step() calls from a
   Python loop), the wall time of the calls against `elan run`'s ms_per_step (C++), and against
   the time spent inside the engine's World::step in the same process (the summary's
   wall_seconds, the clock `elan run` reports): the binding's own cost, free of run-to-run noise.
2. Reading 1M positions through the zero-copy views: fetching px, py, pz (no copy), and, for
   comparison, a reduction over them and a copy into an (n, 3) array.

Usage: PYTHONPATH=build/tools/python python3 tools/python/bench/overhead.py [--scene PATH]
       [--steps N] [--threads T] [--bodies N] [--elan build/tools/elan] [--repeats R]
"""

import argparse
import json
import statistics
import subprocess
import time

import elan


def python_run(scene, steps, threads, loop):
    """ms per step of the Python calls (wall) and inside World::step (the engine's clock)."""
    w = elan.World.from_scene_file(scene, threads=threads)
    t0 = time.perf_counter()
    if loop:
        for _ in range(steps):
            w.step()
    else:
        w.step(steps)
    wall = time.perf_counter() - t0
    return wall * 1000 / steps, w.summary()["wall_seconds"] * 1000 / steps


def cpp_run(elan_bin, scene, steps, threads):
    cmd = [elan_bin, "run", scene, "--steps", str(steps)]
    if threads:
        cmd += ["--threads", str(threads)]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)["ms_per_step"]


def stepping(elan_bin, scene, steps, threads, repeats):
    """Runs of `elan run`, step(n) and a Python loop of step(), interleaved so that the load of
    the machine falls on all three alike; medians."""
    cpp, call, loop, call_in, loop_in = [], [], [], [], []
    for _ in range(repeats):
        if elan_bin:
            cpp.append(cpp_run(elan_bin, scene, steps, threads))
        wall, engine = python_run(scene, steps, threads, loop=False)
        call.append(wall)
        call_in.append(wall / engine - 1)
        wall, engine = python_run(scene, steps, threads, loop=True)
        loop.append(wall)
        loop_in.append(wall / engine - 1)
    med = statistics.median
    rows = []
    base = med(cpp) if cpp else None
    for mode, t, inside in (("step(n), one call", call, call_in),
                            ("step() in a Python loop", loop, loop_in)):
        vs = f"{(med(t) / base - 1) * 100:+.2f} %" if base else "-"
        rows.append((mode, med(t), vs, med(inside) * 100))
    return base, rows


def reading(bodies, repeats=50):
    w = elan.World(gravity=(0, 0, 0), threads=1)
    s = w.create_shape("sphere", radius=0.1)
    side = int(round(bodies ** (1 / 3))) + 1
    n = 0
    for i in range(side):
        for j in range(side):
            for k in range(side):
                if n == bodies:
                    break
                w.create_body(s, position=(i * 0.5, j * 0.5, k * 0.5), awake=False)
                n += 1
    times = {"views": [], "mean": [], "copy": []}
    for _ in range(repeats):
        t0 = time.perf_counter()
        px, py, pz = w.column("px"), w.column("py"), w.column("pz")
        t1 = time.perf_counter()
        m = (px.mean(), py.mean(), pz.mean())
        t2 = time.perf_counter()
        p = w.positions()
        t3 = time.perf_counter()
        times["views"].append(t1 - t0)
        times["mean"].append(t2 - t1)
        times["copy"].append(t3 - t2)
        del m, p
    return w.body_count, {k: statistics.median(v) * 1000 for k, v in times.items()}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="scenes/pile1k.json")
    ap.add_argument("--steps", type=int, default=300)
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--bodies", type=int, default=1_000_000)
    ap.add_argument("--elan", default=None, help="the elan command, for the C++ baseline")
    ap.add_argument("--repeats", type=int, default=7)
    a = ap.parse_args()
    print(f"stepping {a.scene}, {a.steps} steps, threads={a.threads or 'all'}, "
          f"medians of {a.repeats} interleaved runs")
    base, rows = stepping(a.elan, a.scene, a.steps, a.threads, a.repeats)
    if base:
        print(f"\nelan run (C++): {base:.3f} ms/step\n")
    print("| from Python | ms/step (wall of the calls) | vs elan run | vs World::step inside |")
    print("|---|---|---|---|")
    for mode, t, vs, inside in rows:
        print(f"| {mode} | {t:.3f} | {vs} | {inside:+.3f} % |")
    n, t = reading(a.bodies)
    print(f"\nreading the positions of {n} bodies (median of 50)")
    print("| operation | ms |")
    print("|---|---|")
    print(f"| px, py, pz views (zero copy) | {t['views']:.4f} |")
    print(f"| mean of each column | {t['mean']:.3f} |")
    print(f"| copy into an (n, 3) float64 array (positions()) | {t['copy']:.3f} |")


if __name__ == "__main__":
    main()
