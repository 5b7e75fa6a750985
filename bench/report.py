#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The benchmark report of bench/results/<cpu>/, in two steps.

1. With --raw: turns a bench_scenes JSON run (and the peak-RSS runs) into small CSVs in --out: a
   CSV per scene, calibration.csv, paired.csv, paired_bullet.csv, sweep.csv, memory.csv and
   meta.csv (machine, compiler, flags, arguments, load). bench/run_suite.sh calls it so.
2. Always: writes summary.md and the plots (gnuplot SVG) from those CSVs alone, so the summary
   and its plots can be regenerated from the committed files: `bench/report.py --out DIR`.

A plot that cannot be drawn is an error (exit status 1 with the reason), never a silent gap:
tools/setup.sh installs gnuplot-nox."""
import argparse
import csv
import datetime
import glob
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys

# The stage timers of elan::StepProfile, in the step's order, as bench/scenes.cpp reports them
# (<stage>_ms counters): `color` is the colouring alone; `split`, `packets`, `bundles` and `prepare`
# are the solver's other stages before the solve.
STAGES = ["bounds", "pairs", "collide", "islands", "split", "packets", "color", "bundles", "prepare",
          "solve", "ccd", "finalize"]
# A scene CSV written before those four had timers of their own lacks their columns; its `color`
# column is then the whole of the solver's preparation (split, packets, colour, bundles, prepare).
LEGACY_STAGES = ("split", "packets", "bundles", "prepare")
STACKS = ("pyramid", "tower")  # scenes whose top body must stay put (moved < 5 cm)
# A scene whose 1-thread step takes less than this, ms, measures nothing but the loop around it (a
# tower of 21 bodies asleep: 4-7 us a step): the tables' two decimals show 0.00 or 0.01 and its
# speedup is noise. It is left out of the tables and the plots, and named below them.
MEASURES_NOTHING_MS = 0.02
SCENE_HEADER = (["threads", "ms", "ms_min", "ms_max"] + [s + "_ms" for s in STAGES] +
                ["bodies", "pairs", "contacts", "colors", "awake", "state_hash", "errors",
                 "top_drift_cm", "top_drop_cm", "expected_drop_cm", "bullet_ms",
                 "bullet_top_drift_cm", "bullet_top_drop_cm", "joints", "max_move_m",
                 "bullet_max_move_m", "bullet_joints_left"])
NOT_SCENES = {"calibration", "paired", "paired_bullet", "sweep", "memory", "meta"}
MEMORY_PARTS = ("bodies", "shapes", "broadphase", "contacts", "solver", "api", "scratch")


def fail(message):
    sys.exit(f"report.py: {message}")


def median(xs):
    return statistics.median(xs) if xs else float("nan")


def num(x):
    """A CSV cell as a float; empty or unparsable cells are NaN."""
    try:
        return float(x)
    except (TypeError, ValueError):
        return float("nan")


def fmt(x, digits=2):
    if x is None or x != x:
        return "—"
    return f"{x:.{digits}f}"


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


# ---------------------------------------------------------------------------------------------
# Step 1: a raw run into CSVs.

def load_runs(path):
    """{benchmark name: [run dict per repetition]}, errors kept as run['error']."""
    with open(path) as f:
        data = json.load(f)
    runs = {}
    for b in data["benchmarks"]:
        if b.get("run_type") == "aggregate":
            continue
        name = b["name"].split("/iterations:")[0]
        runs.setdefault(name, []).append(b)
    return runs


def cache_value(build, key):
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as f:
            for line in f:
                if line.startswith(key + ":"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return ""


def peak_rss_kib(path):
    try:
        with open(path) as f:
            m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", f.read())
        return int(m.group(1)) if m else None
    except OSError:
        return None


def tables_from_raw(a):
    runs = load_runs(os.path.join(a.raw, "bench.json"))
    names = list(runs)

    def ok(name):
        return [r for r in runs.get(name, []) if not r.get("error_occurred")]

    def med(name, key):
        return median([r[key] for r in ok(name) if key in r])

    def f4(x):
        return "" if x is None or x != x else f"{x:.4f}"

    # Calibration: median time per kernel and thread count; the ceiling is t1 / t2.
    rows = []
    for k in ("fma", "stream"):
        t1, t2 = med(f"calib/{k}/threads:1", "real_time"), med(f"calib/{k}/threads:2", "real_time")
        rows.append([k, f"{t1:.3f}", f"{t2:.3f}", f"{t1 / t2 if t2 else float('nan'):.3f}"])
    write_csv(os.path.join(a.out, "calibration.csv"), ["kernel", "ms_1t", "ms_2t", "speedup"], rows)

    # Paired: each repetition ran two things back to back (1 and 2 threads; elan and Bullet),
    # seconds apart where the random interleaving puts them minutes apart; the median of the ratios.
    def paired_rows(prefix, ratio, times):
        out = []
        for n in names:
            rs = [r for r in ok(n) if ratio in r]
            if n.startswith(prefix) and rs:
                ratios = [r[ratio] for r in rs]
                out.append([n[len(prefix):], len(rs)] + [f4(median([r[t] for r in rs])) for t in times] +
                           [f4(median(ratios)), f4(min(ratios)), f4(max(ratios))])
        return out
    write_csv(os.path.join(a.out, "paired.csv"),
              ["name", "pairs", "ms_1t", "ms_2t", "speedup", "speedup_min", "speedup_max"],
              paired_rows("paired/", "speedup", ("ms_1t", "ms_2t")))
    write_csv(os.path.join(a.out, "paired_bullet.csv"),
              ["name", "pairs", "ms_1t", "ms_bullet", "ratio", "ratio_min", "ratio_max"],
              paired_rows("paired-bullet/", "bullet_ratio", ("ms_1t", "ms_bullet")))

    # One CSV per scene: a row per thread count.
    scenes = [n.split("/")[1] for n in names if n.startswith("elan/") and n.endswith("threads:1")]
    for s in scenes:
        rows = []
        bullet = f"bullet/{s}"
        for t in (1, 2):
            n = f"elan/{s}/threads:{t}"
            good = ok(n)
            r0 = good[0] if good else runs[n][0]
            h = (int(r0.get("hash_hi", 0)) << 32) | int(r0.get("hash_lo", 0))
            times = [r["ms_per_step"] for r in good if "ms_per_step" in r]
            rows.append([t, f4(med(n, "ms_per_step")), f4(min(times) if times else None),
                         f4(max(times) if times else None)] +
                        [f4(med(n, st + "_ms")) for st in STAGES] +
                        [int(r0.get("bodies", 0)), int(r0.get("pairs", 0)), int(r0.get("contacts", 0)),
                         int(r0.get("colors", 0)), int(r0.get("awake", 0)), f"{h:016x}",
                         len(runs[n]) - len(good), f4(r0.get("top_drift_cm", 0)),
                         f4(r0.get("top_drop_cm", 0)), f4(r0.get("expected_drop_cm", 0)),
                         f4(med(bullet, "ms_per_step")), f4(med(bullet, "top_drift_cm")),
                         f4(med(bullet, "top_drop_cm")), int(r0.get("joints", 0)),
                         f4(r0.get("max_move_m")), f4(med(bullet, "max_move_m")),
                         f4(med(bullet, "joints_left"))])
        write_csv(os.path.join(a.out, s + ".csv"), SCENE_HEADER, rows)

    # Sweep: ms per step against N for each engine/broadphase/thread count.
    rows = []
    for n in names:
        m = re.match(r"sweep/([a-z-]+)/N:(\d+)(?:/threads:(\d))?$", n)
        if m:
            engine = "bullet" if m.group(1) == "bullet" else "elan"
            rows.append([engine, "dbvt" if engine == "bullet" else m.group(1), m.group(3) or "1",
                         int(m.group(2)), f4(med(n, "ms_per_step"))])
    rows.sort(key=lambda r: (r[0], r[1], r[2], r[3]))
    write_csv(os.path.join(a.out, "sweep.csv"), ["engine", "broadphase", "threads", "n", "ms"], rows)

    # Memory on pile10k: heap per body in process, elan's by part, peak RSS in separate processes.
    rows = [["heap_elan", f4(med("memory/elan/pile10k", "heap_bytes_per_body")), "B/body"],
            ["heap_bullet", f4(med("memory/bullet/pile10k", "heap_bytes_per_body")), "B/body"]]
    rows += [["part_" + p, f4(med("memory/elan/pile10k", "mem_" + p)), "B/body"] for p in MEMORY_PARTS]
    for engine in ("elan", "bullet"):
        rss = peak_rss_kib(os.path.join(a.raw, f"rss_{engine}.txt"))
        rows.append([f"rss_{engine}", "" if rss is None else rss, "KiB"])
    rows.append(["rss_steps", a.rss_steps, "steps"])
    write_csv(os.path.join(a.out, "memory.csv"), ["measure", "value", "unit"], rows)

    # What ran, where and how.
    def read(p):
        try:
            with open(os.path.join(a.raw, p)) as f:
                return f.read().strip()
        except OSError:
            return ""
    cxx = cache_value(a.build, "CMAKE_CXX_COMPILER")
    try:
        cxx_version = subprocess.run([cxx, "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    except (OSError, IndexError):
        cxx_version = cxx
    try:
        rev = subprocess.run(["git", "-C", os.path.dirname(os.path.abspath(__file__)), "rev-parse", "--short",
                              "HEAD"], capture_output=True, text=True).stdout.strip()
    except OSError:
        rev = ""
    with open("/proc/cpuinfo") as f:
        cpu = re.search(r"model name\s*:\s*(.*)", f.read()).group(1)
    flags = (cache_value(a.build, "CMAKE_CXX_FLAGS") + " " + cache_value(a.build, "CMAKE_CXX_FLAGS_RELEASE") +
             " -march=native -ffp-contract=off -fno-fast-math -fno-math-errno -fopenmp-simd").strip()
    meta = [["date", datetime.datetime.now().isoformat(timespec="seconds")], ["mode", a.mode],
            ["commit", rev], ["cpu", cpu], ["cores", os.cpu_count()],
            ["os", f"{platform.system()} {platform.release()}"], ["compiler", cxx_version], ["flags", flags],
            ["bullet", "Debian's libbullet 3.24 (float, distribution build)"], ["arguments", read("args.txt")],
            ["load_start", read("uptime_start.txt")], ["load_end", read("uptime_end.txt")]]
    write_csv(os.path.join(a.out, "meta.csv"), ["key", "value"], meta)


# ---------------------------------------------------------------------------------------------
# Step 2: the summary and the plots from the CSVs.

def gnuplot(script, out_path):
    """Draws one SVG; any failure ends the report with gnuplot's own message."""
    if shutil.which("gnuplot") is None:
        fail(f"cannot draw {os.path.basename(out_path)}: gnuplot is not installed "
             "(apt-get install gnuplot-nox; tools/setup.sh installs it)")
    p = subprocess.run(["gnuplot"], input=script, text=True, capture_output=True)
    if p.returncode != 0 or not os.path.isfile(out_path) or os.path.getsize(out_path) == 0:
        fail(f"cannot draw {os.path.basename(out_path)}: gnuplot exited {p.returncode}: "
             f"{p.stderr.strip() or 'no output file'}")
    # gnuplot ends lines with spaces and the file with a blank line; keep the committed SVGs clean.
    with open(out_path) as f:
        lines = [line.rstrip() for line in f.read().split("\n")]
    while lines and not lines[-1]:
        lines.pop()
    with open(out_path, "w") as f:
        f.write("\n".join(lines) + "\n")


def gp_string(s):
    return "'" + s.replace("'", "''") + "'"


def summarize(out, mode_arg):
    def path(name):
        return os.path.join(out, name)

    for required in ("meta.csv", "calibration.csv", "sweep.csv"):
        if not os.path.isfile(path(required)):
            fail(f"{path(required)} is missing: run bench/run_suite.sh, or report.py --raw")
    meta = {r["key"]: r["value"] for r in read_csv(path("meta.csv"))}
    calib = {r["kernel"]: (num(r["ms_1t"]), num(r["ms_2t"]), num(r["speedup"]))
             for r in read_csv(path("calibration.csv"))}
    nan3 = (float("nan"),) * 3
    fma, stream = calib.get("fma", nan3), calib.get("stream", nan3)
    paired = {r["name"]: r for r in read_csv(path("paired.csv"))} if os.path.isfile(path("paired.csv")) else {}
    paired_bullet = ({r["name"]: r for r in read_csv(path("paired_bullet.csv"))}
                     if os.path.isfile(path("paired_bullet.csv")) else {})
    memory = ({r["measure"]: r["value"] for r in read_csv(path("memory.csv"))}
              if os.path.isfile(path("memory.csv")) else {})
    paired_ceiling = num(paired.get("calib/fma", {}).get("speedup"))

    scene_rows = {}
    for f in sorted(glob.glob(path("*.csv"))):
        name = os.path.basename(f)[:-4]
        if name in NOT_SCENES:
            continue
        rows = read_csv(f)
        if not rows or "threads" not in rows[0] or "ms" not in rows[0]:
            continue
        rows = sorted(rows, key=lambda r: int(r["threads"]))
        if len(rows) != 2:
            fail(f"{f}: expected a row for 1 and for 2 threads, got {len(rows)}")
        scene_rows[name] = [{k: (v if k == "state_hash" else num(v)) for k, v in r.items()} for r in rows]
    shown = [s for s, (r1, _) in scene_rows.items() if not r1["ms"] < MEASURES_NOTHING_MS]
    left_out = [s for s in scene_rows if s not in shown]

    sweep = {}
    for r in read_csv(path("sweep.csv")):
        key = f"{'bullet' if r['engine'] == 'bullet' else r['broadphase']} {r['threads']}t"
        sweep.setdefault(key, {})[int(r["n"])] = num(r["ms"])

    def verdict(drift, drop, expected):
        """A stack stands when its top drifted < 5 cm sideways and dropped no more than its built-in
        gaps (+ 5 cm)."""
        if drift != drift or drop != drop:
            return "—"
        ok = drift < 5 and drop < expected + 5
        return f"{'stands' if ok else 'moved'} (drift {drift:.1f} cm, drop {drop:.1f} of {expected:.0f} cm)"

    # Plots.
    plots = []
    if sweep:
        ns = sorted({n_ for pts in sweep.values() for n_ in pts})
        blocks, series = [], []
        for i, (key, pts) in enumerate(sorted(sweep.items())):
            blocks.append(f"$s{i} << EOD\n" + "".join(f"{n_} {ms}\n" for n_, ms in sorted(pts.items())
                                                      if ms == ms) + "EOD\n")
            series.append(f"$s{i} using 1:2 with linespoints lw 2 pt 7 title {gp_string(key)}")
        target = path("sweep.svg")
        gnuplot("".join(blocks) +
                "set terminal svg size 900,560 dynamic noenhanced font 'sans,14'\n"
                f"set output {gp_string(target)}\n"
                "set logscale xy\nset xlabel 'bodies N'\nset ylabel 'ms per step'\n"
                "set xtics (" + ", ".join(f"'{n_ // 1000}k' {n_}" if n_ % 1000 == 0 else f"'{n_}' {n_}"
                                          for n_ in ns) + ")\n"
                f"set xrange [{ns[0] * 0.8}:{ns[-1] * 1.25}]\nset format y '%g'\nset key left top\nset grid\n"
                "set title 'Pile sweep: ms per step against N (median)'\n"
                "plot " + ", ".join(series) + "\n", target)
        plots.append(("sweep.svg", "ms per step of the generated pile against its body count, per "
                                   "broadphase and thread count, and Bullet"))
    if shown:
        # Horizontal bars, the scene names on the y axis: long names stay level and readable.
        data = "$d << EOD\n" + "".join(
            f"{i} \"{s}\" {scene_rows[s][0]['ms'] / scene_rows[s][1]['ms']:.4f}\n"
            for i, s in enumerate(shown)) + "EOD\n"
        target = path("speedup.svg")
        lines = [f"$d using ({fma[2]:.4f}):1 with lines lw 2 title 'ceiling: FMA kernel'"
                 if fma[2] == fma[2] else "",
                 f"$d using ({stream[2]:.4f}):1 with lines lw 2 dt 2 title 'ceiling: streaming kernel'"
                 if stream[2] == stream[2] else "",
                 "$d using (2):1 with lines dt 3 title 'ideal'"]
        gnuplot(data +
                f"set terminal svg size 900,{200 + 40 * len(shown)} dynamic noenhanced font 'sans,14'\n"
                f"set output {gp_string(target)}\n"
                "set style fill solid 0.6\nset grid xtics\nset xlabel '2-thread speedup (t1 / t2)'\n"
                f"set xrange [0:3]\nset yrange [{len(shown) - 0.5}:-0.5]\nset ytics nomirror\n"
                "set key outside bottom center horizontal\n"
                "set title 'elan 2-thread speedup per scene against the calibrated ceiling'\n"
                "plot $d using (0):1:(0):3:($1 - 0.3):($1 + 0.3):ytic(2) with boxxyerror title 'elan', " +
                ", ".join(l for l in lines if l) + "\n", target)
        plots.append(("speedup.svg", "2-thread speedup of every scene in the table, with the "
                                     "machine's ceiling measured in the same run"))

    # Summary.
    L = []
    cpu = meta.get("cpu", "")
    L.append(f"# Benchmark results: {cpu}\n")
    L.append(f"- date: {meta.get('date', '')}, mode `{meta.get('mode', mode_arg)}`, commit `{meta.get('commit', '')}`")
    L.append(f"- CPU: {cpu}, {meta.get('cores', '')} logical cores; {meta.get('os', '')}")
    L.append(f"- compiler: {meta.get('compiler', '')}; flags: `{meta.get('flags', '')}`; "
             f"Bullet: {meta.get('bullet', '')}")
    L.append(f"- bench_scenes arguments: `{meta.get('arguments', '')}`")
    L.append(f"- load at start: `{meta.get('load_start', '')}`; at end: `{meta.get('load_end', '')}`")
    L.append("- The machine is shared (2 cores, other agents building at the same time): every (benchmark, "
             "repetition) is randomly interleaved and the figures are medians. Treat single figures as ±20 %; "
             "the paired speedups below are steadier.")
    L.append("- Each scene run: fresh world, `warmup` steps untimed, then `steps` timed; state hash after both "
             "must match across thread counts, broadphases and repetitions (else the benchmark errors). "
             "`awake` is the count of awake bodies at the end: a scene that is asleep by then times its "
             "sleeping cost, and its `-no-sleep` row (allow_sleep off) times its work.\n")
    L.append("## Calibration (2-thread ceiling of this machine, same run)\n")
    L.append("| kernel | 1 thread ms | 2 threads ms | speedup |\n| --- | --- | --- | --- |")
    for k, (t1, t2, s) in calib.items():
        L.append(f"| {k} | {fmt(t1)} | {fmt(t2)} | {fmt(s)} |")
    L.append("\n## Scenes (ms per step, median)\n")
    L.append("| scene | bodies | awake | elan 1t | elan 2t | speedup | % of FMA / stream ceiling | Bullet 1t | "
             "Bullet / elan 1t | contacts | colours | top of stack elan / Bullet | hash 1t = 2t |")
    L.append("|" + " --- |" * 13)
    for s in shown:
        r1, r2 = scene_rows[s]
        sp = r1["ms"] / r2["ms"]
        stand = ""
        if any(k in s for k in STACKS):
            stand = (f"{verdict(r1['top_drift_cm'], r1['top_drop_cm'], r1['expected_drop_cm'])} / "
                     f"{verdict(r1['bullet_top_drift_cm'], r1['bullet_top_drop_cm'], r1['expected_drop_cm'])}")
        same = "yes" if r1["state_hash"] == r2["state_hash"] and not r1["errors"] and not r2["errors"] else "**NO**"
        L.append(f"| {s} | {fmt(r1['bodies'], 0)} | {fmt(r1['awake'], 0)} | {fmt(r1['ms'])} | {fmt(r2['ms'])} | "
                 f"{fmt(sp)} | {fmt(100 * sp / fma[2], 0)} / {fmt(100 * sp / stream[2], 0)} | "
                 f"{fmt(r1['bullet_ms'])} | {fmt(r1['bullet_ms'] / r1['ms'])} | {fmt(r1['contacts'], 0)} | "
                 f"{fmt(r1['colors'], 0)} | {stand} | {same} |")
    if left_out:
        L.append(f"\nLeft out, under {MEASURES_NOTHING_MS} ms a step at 1 thread (they time the loop around "
                 f"the step, not the engine; their CSVs are kept): {', '.join(left_out)}.")
    jointed = [s for s in shown if scene_rows[s][0].get("joints", 0) > 0]
    if jointed:
        L.append("\n## Joint scenes\n")
        L.append("The same scene file in both engines; Bullet's constraints as docs/benchmarks.md maps them. "
                 "`farthest move` is the farthest any body went from its start by the end (m): a blown-up "
                 "scene shows there. The paired ratio, where present, is in the table of paired runs below.\n")
        L.append("| scene | bodies | joints | elan 1t | elan 2t | Bullet 1t | Bullet / elan 1t | "
                 "farthest move elan / Bullet | Bullet's joints left |")
        L.append("|" + " --- |" * 9)
        for s in jointed:
            r1, r2 = scene_rows[s]
            L.append(f"| {s} | {fmt(r1['bodies'], 0)} | {fmt(r1['joints'], 0)} | {fmt(r1['ms'])} | "
                     f"{fmt(r2['ms'])} | {fmt(r1['bullet_ms'])} | {fmt(r1['bullet_ms'] / r1['ms'])} | "
                     f"{fmt(r1.get('max_move_m'))} / {fmt(r1.get('bullet_max_move_m'))} | "
                     f"{fmt(r1.get('bullet_joints_left'), 0)} |")
    if paired:
        L.append("\n## 2-thread speedup from paired runs\n")
        L.append("Each repetition runs 1 thread and 2 threads back to back (the order alternating), so both see "
                 "the same load; the speedup is the median of the pairs' ratios, against the FMA kernel "
                 "measured the same way.\n")
        L.append("| run | pairs | 1 thread ms | 2 threads ms | speedup (median) | range | % of paired FMA ceiling |")
        L.append("|" + " --- |" * 7)
        for k, v in sorted(paired.items(), key=lambda kv: not kv[0].startswith("calib/")):
            L.append(f"| {k} | {v['pairs']} | {fmt(num(v['ms_1t']))} | {fmt(num(v['ms_2t']))} | "
                     f"{fmt(num(v['speedup']))} | {fmt(num(v['speedup_min']))}-{fmt(num(v['speedup_max']))} | "
                     f"{fmt(100 * num(v['speedup']) / paired_ceiling, 0)} |")
    if paired_bullet:
        L.append("\n## Bullet against elan from paired runs\n")
        L.append("Each repetition runs elan at 1 thread and Bullet back to back (the order alternating); the "
                 "ratio is the median of the pairs' ratios.\n")
        L.append("| scene | pairs | elan 1t ms | Bullet ms | Bullet / elan (median) | range |")
        L.append("|" + " --- |" * 6)
        for k, v in paired_bullet.items():
            L.append(f"| {k} | {v['pairs']} | {fmt(num(v['ms_1t']))} | {fmt(num(v['ms_bullet']))} | "
                     f"{fmt(num(v['ratio']))} | {fmt(num(v['ratio_min']))}-{fmt(num(v['ratio_max']))} |")
    L.append("\n## Stages at 1 thread (ms per step, median)\n")
    L.append("| scene | " + " | ".join(STAGES) + " |\n| --- |" + " --- |" * len(STAGES))
    legacy = [s for s in shown if any(st + "_ms" not in scene_rows[s][0] for st in LEGACY_STAGES)]
    for s in shown:
        r1 = scene_rows[s][0]
        cells = [fmt(r1.get(st + "_ms"), 3) for st in STAGES]
        if s in legacy:
            cells[STAGES.index("color")] += " \\*"
        L.append(f"| {s} | " + " | ".join(cells) + " |")
    if legacy:
        L.append("\n\\* Measured before the solver's stages had timers of their own: there `color` is the "
                 "whole of the solver's preparation (" + ", ".join(("split", "packets", "colour", "bundles",
                                                                     "prepare")) +
                 "), and those columns are empty.")
    L.append("\n## Pile sweep (ms per step, median; generated mixed-shape pile in a container)\n")
    ns = sorted({n_ for pts in sweep.values() for n_ in pts})
    L.append("| series | " + " | ".join(str(n_) for n_ in ns) + " |\n| --- |" + " --- |" * len(ns))
    for key, pts in sorted(sweep.items()):
        L.append(f"| {key} | " + " | ".join(fmt(pts.get(n_)) for n_ in ns) + " |")

    heap_elan, heap_bullet = num(memory.get("heap_elan")), num(memory.get("heap_bullet"))
    mem_parts = [(p, num(memory.get("part_" + p))) for p in MEMORY_PARTS]
    rss_elan, rss_bullet = memory.get("rss_elan", ""), memory.get("rss_bullet", "")
    if memory:
        L.append("\n## Memory, pile10k\n")
        L.append(f"- heap held by a live world after the scene's steps: elan {fmt(heap_elan, 0)} B/body, "
                 f"Bullet {fmt(heap_bullet, 0)} B/body (glibc mallinfo2, in process)")
        if all(v == v for _, v in mem_parts):
            L.append("- elan's by part (buffer capacities, B/body; the contacts part holds the contact list's "
                     "manifold heads, the tails of those with more than one point, the body pair cache's poses, "
                     "the pairs found apart (the separation cache) and the step's changes to the list (the "
                     "contact events); scratch is the step's scratch, which the bounding boxes, the sweep's "
                     "buffers and the pair list, the collide stage's buffers and then the solver's islands, "
                     "colourings, bundles and rows use in turn): " +
                     ", ".join(f"{part} {fmt(v, 0)}" for part, v in mem_parts) +
                     f"; sum {fmt(sum(v for _, v in mem_parts), 0)}")
        L.append(f"- peak RSS, separate processes, {memory.get('rss_steps', '')} steps, 1 thread, both parsing the "
                 f"scene with elan::load_scene: elan {rss_elan or '—'} KiB, Bullet {rss_bullet or '—'} KiB")

    L.append("\n## Targets of the issue\n")
    jp, p4, p10 = scene_rows.get("jolt_pyramid"), scene_rows.get("pile4k"), scene_rows.get("pile10k")
    L.append("| target | measured | met |\n| --- | --- | --- |")
    if jp:
        v = verdict(jp[0]["top_drift_cm"], jp[0]["top_drop_cm"], jp[0]["expected_drop_cm"])
        L.append(f"| jolt_pyramid ≤ 6 ms/step at 1 thread, standing | {fmt(jp[0]['ms'])} ms, top {v} | "
                 f"{'yes' if jp[0]['ms'] <= 6 and v.startswith('stands') else 'no: ' + fmt(jp[0]['ms'] / 6) + '× the time'} |")
    if p4:
        # The target is at 1 thread; elan at 2 threads against Bullet's 1 is shown beside it.
        ratio = p4[0]["bullet_ms"] / p4[0]["ms"]
        ratio_2t = p4[0]["bullet_ms"] / p4[1]["ms"]
        unpaired = f"{fmt(ratio)}× from the medians (elan 2t vs Bullet 1t: {fmt(ratio_2t)}×)"
        pb = paired_bullet.get("pile4k")
        if pb:
            # The paired ratio decides: its two runs were seconds apart, under one load.
            ratio = num(pb["ratio"])
            unpaired = (f"paired: {fmt(ratio)}× (median of {pb['pairs']}, range {fmt(num(pb['ratio_min']))}-"
                        f"{fmt(num(pb['ratio_max']))}); " + unpaired)
        L.append(f"| pile4k ≥ 6× faster than Bullet at 1 thread | {unpaired} | "
                 f"{'yes' if ratio >= 6 else 'no: ' + fmt(6 / ratio) + '× short'} |")
    if p10:
        sp = p10[0]["ms"] / p10[1]["ms"]
        frac = sp / fma[2]
        # The repetitions' spread shows how much of the figure is the machine's load. The paired
        # figure, where present, decides: its two halves ran under the same load.
        measured = (f"ratio of the interleaved runs' medians {fmt(sp)}×, {fmt(100 * frac, 0)} % of FMA ceiling "
                    f"{fmt(fma[2])} (repetitions: 1t {fmt(p10[0]['ms_min'])}-{fmt(p10[0]['ms_max'])} ms, "
                    f"2t {fmt(p10[1]['ms_min'])}-{fmt(p10[1]['ms_max'])} ms)")
        pp = paired.get("elan/pile10k")
        if pp:
            sp = num(pp["speedup"])
            frac = sp / paired_ceiling
            measured = (f"paired: {fmt(sp)}× (median of {pp['pairs']}, range {fmt(num(pp['speedup_min']))}-"
                        f"{fmt(num(pp['speedup_max']))}), {fmt(100 * frac, 0)} % of the paired FMA ceiling "
                        f"{fmt(paired_ceiling)}; " + measured)
        L.append(f"| pile10k 2-thread speedup ≥ 1.6× and ≥ 80 % of ceiling | {measured} | "
                 f"{'yes' if sp >= 1.6 and frac >= 0.8 else 'no'} |")
    # The issue counts store + broadphase + contacts + solver; the shapes are the scene's own
    # geometry (pile10k's are 10k distinct boxes, hulls, spheres and capsules), shown apart.
    parts = dict(mem_parts)
    if memory and all(v == v for v in parts.values()):
        engine = sum(v for part, v in parts.items() if part != "shapes")
        L.append(f"| engine memory ≤ 1 KiB/body on pile10k | {fmt(engine, 0)} B/body (bodies, broadphase, "
                 f"contacts, solver, api, scratch; shapes {fmt(parts['shapes'], 0)} more, heap in all "
                 f"{fmt(heap_elan, 0)}) | {'yes' if engine <= 1024 else 'no: ' + fmt(engine / 1024) + '× over'} |")
    if rss_elan and rss_bullet:
        L.append(f"| peak RSS below Bullet's on pile10k | {rss_elan} vs {rss_bullet} KiB | "
                 f"{'yes' if int(rss_elan) < int(rss_bullet) else 'no'} |")
    if plots:
        L.append("\n## Plots\n")
        for p, what in plots:
            L.append(f"- [{p}]({p}): {what}")
        L.append("")
        L.extend(f"![{p}]({p})" for p, _ in plots)
    L.append("\nReproduce: `bench/run_suite.sh --" + meta.get("mode", mode_arg) + "`. This file and the plots "
             "are drawn from the CSVs beside them (`bench/report.py --out DIR` redraws them); the raw Google "
             "Benchmark JSON stays in `raw/`, which is not committed.")
    with open(path("summary.md"), "w") as f:
        f.write("\n".join(L) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True, help="bench/results/<cpu>: the CSVs, summary.md and plots")
    ap.add_argument("--raw", help="a run's raw files (bench.json, rss_*.txt, ...): write the CSVs from them first")
    ap.add_argument("--build", default="", help="the benchmark build directory (compiler and flags)")
    ap.add_argument("--mode", default="quick")
    ap.add_argument("--rss-steps", type=int, default=300)
    a = ap.parse_args()
    if a.raw:
        tables_from_raw(a)
    summarize(a.out, a.mode)


if __name__ == "__main__":
    main()
