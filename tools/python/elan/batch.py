# SPDX-License-Identifier: MIT
"""Many independent simulations as tasks on a Dask distributed cluster.

    import elan.batch
    results = elan.batch.run("sweep.json", workers=2, out="results")   # a pandas DataFrame

Each case of a sweep (see elan.batch_sweep and docs/batch.md) is one task: it loads its scene,
steps it and returns ``elan run``'s summary with the case's parameters. A task depends on its
case alone, so the state hashes are the same whatever the number of workers and wherever the task
runs, and the results come back in sweep order, not in the order the tasks finish. A task whose
worker dies is run again on another (the scheduler's allowed failures), so every result still
comes back, exactly.

The command line, ``python3 -m elan.batch SWEEP`` (what ``elan batch`` runs), writes the table to
``OUT/results.csv``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from typing import Any, Callable, Sequence

from .batch_sweep import Sweep, SweepError, load_sweep, sweep_from_scenes

__all__ = ["run", "run_case", "cases_of", "BatchError", "SweepError", "Sweep", "load_sweep", "main"]

RESULTS_CSV = "results.csv"
TRAJECTORY_DIR = "trajectories"
DEFAULT_RETRIES = 2
TRAJECTORY_HEADER = "step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz"


class BatchError(RuntimeError):
    """A case that could not run: its scene was refused (``.field`` names the scene's field, and
    ``.bad_input`` is true), or its task failed after the retries."""

    def __init__(self, message: str, field: str = "", bad_input: bool = False):
        super().__init__(message)
        self.field = field
        self.bad_input = bad_input


# --- one task -----------------------------------------------------------------------------------


def _trajectory_path(case: dict) -> str:
    t = case["trajectory"]
    return os.path.join(case["out"], TRAJECTORY_DIR, f"case_{case['index']:05d}.{t['format']}")


def _trajectory_bodies(world: Any) -> tuple:
    """The non-static bodies (a trajectory lists them, as ``elan run`` does): ids and indices."""
    ids, indices = [], []
    for i in range(world.body_count):
        body = world.body_at(i)
        if world.motion_type(body) != "static":
            ids.append(body)
            indices.append(i)
    return ids, indices


def _sample(world: Any, ids: list):
    """(bodies, 13): position (of the shape frame, as ``elan run`` reports it), orientation
    [w, x, y, z], linear and angular velocity."""
    import numpy as np

    rows = [
        (*world.position(b), *world.orientation(b), *world.linear_velocity(b), *world.angular_velocity(b))
        for b in ids
    ]
    return np.array(rows, dtype=np.float64).reshape(len(ids), 13)


def _write_trajectory(world: Any, case: dict) -> None:
    """Steps the world ``case['steps']`` steps, sampling every non-static body at step 0, every
    ``every``-th step and the last, into a CSV byte for byte as ``elan run --trajectory`` writes
    it (every value printed so that it reads back to the same bits) or an .npz of arrays (step,
    time, body, and position, orientation [w, x, y, z], linear_velocity, angular_velocity of shape
    (samples, bodies, 3 or 4))."""
    import numpy as np

    t = case["trajectory"]
    steps, every = case["steps"], t["every"]
    dt = float(world.summary()["timestep"])  # s, the engine's value
    # As elan run: %.9g identifies a float, %.17g a double (max_digits10).
    real_format = "%.9g" if world.column("px").dtype.itemsize == 4 else "%.17g"
    real = np.float32 if real_format == "%.9g" else np.float64
    ids, indices = _trajectory_bodies(world)
    samples = []

    def take(step: int) -> None:
        samples.append((step, float(step) * dt, _sample(world, ids)))

    take(0)
    done = 0
    while done < steps:
        n = min(every - done % every, steps - done)
        world.step(n)
        done += n
        if done % every == 0 or done == steps:
            take(done)
    path = _trajectory_path(case)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    # A retried task writes the whole file again: write aside, then rename over, so a reader never
    # sees a half-written file from a worker that died.
    tmp = f"{path}.tmp{os.getpid()}"
    if t["format"] == "npz":
        tmp += ".npz"  # else numpy appends it
        values = np.stack([a for _, _, a in samples]).astype(real)  # exact: the values are Reals
        np.savez_compressed(
            tmp,
            step=np.array([s for s, _, _ in samples], dtype=np.uint64),
            time=np.array([x for _, x, _ in samples], dtype=np.float64),
            body=np.array(indices, dtype=np.uint64),
            position=values[:, :, 0:3],
            orientation=values[:, :, 3:7],
            linear_velocity=values[:, :, 7:10],
            angular_velocity=values[:, :, 10:13],
        )
    else:
        with open(tmp, "w", encoding="ascii", newline="\n") as f:
            f.write(TRAJECTORY_HEADER + "\n")
            for step, time_s, values in samples:
                prefix = f"{step},{'%.17g' % time_s},"
                for row, body in enumerate(indices):
                    f.write(prefix + str(body) + "," + ",".join(real_format % x for x in values[row]) + "\n")
    os.replace(tmp, path)


def _flatten(summary: dict) -> dict:
    """One level of columns: a vector [x, y, z] becomes key_x, key_y, key_z and a nested object
    key.sub, so the table has one number per cell."""
    out: dict = {}
    for key, value in summary.items():
        if isinstance(value, dict):
            for sub, v in _flatten(value).items():
                out[f"{key}.{sub}"] = v
        elif isinstance(value, (list, tuple)) and len(value) == 3:
            for axis, v in zip("xyz", value):
                out[f"{key}_{axis}"] = v
        else:
            out[key] = value
    return out


def run_case(case: dict) -> dict:
    """Runs one case (an item of ``cases_of``) and returns its row: ``case`` (its index), the
    parameters, ``elan run``'s summary, ``task_seconds`` (load, steps and output). A scene the
    engine refuses gives a row with ``error`` and ``error_field`` instead, so that a bad input is
    not retried."""
    import elan

    start = time.perf_counter()
    try:
        world = elan.World.from_scene_json(
            case["scene_text"],
            base_dir=case["base_dir"],
            threads=case.get("threads"),
            broadphase=case["broadphase"],
        )
    except elan.Error as e:
        return {"case": case["index"], "error": str(e), "error_field": getattr(e, "field", "")}
    if case.get("trajectory"):
        _write_trajectory(world, case)
    elif case["steps"]:
        world.step(case["steps"])
    summary = dict(world.summary())
    # determinism: the hash as `elan run` prints it, 16 hex digits, from the exact integer.
    summary["state_hash"] = f"{int(world.state_hash):016x}"
    for key in ("scene", "steps"):  # the case's own columns say these
        summary.pop(key, None)
    row = {"case": case["index"], **_flatten(case["params"]), **_flatten(summary)}
    if case.get("trajectory"):
        row["trajectory"] = _trajectory_path(case)
    row["task_seconds"] = time.perf_counter() - start
    return row


# --- a batch ------------------------------------------------------------------------------------


def _as_sweep(source: Any, steps: int | None = None) -> Sweep:
    if isinstance(source, Sweep):
        return source
    if isinstance(source, (str, os.PathLike)):
        return load_sweep(os.fspath(source))
    if isinstance(source, dict):
        return Sweep(source, "")
    if isinstance(source, Sequence):
        return sweep_from_scenes([os.fspath(s) if isinstance(s, os.PathLike) else s for s in source], steps)
    raise TypeError(f"a batch is a sweep file, a sweep object or a list of scenes, not {type(source).__name__}")


def cases_of(source: Any, out: str | None = None, threads_per_task: int | None = 1, steps: int | None = None) -> list:
    """The cases of a sweep (a path, a dict, a Sweep, or a list of scene paths or objects), in
    sweep order, each a picklable dict that ``run_case`` runs."""
    sweep = _as_sweep(source, steps)
    cases = sweep.cases()
    if sweep.trajectory and out is None:
        raise SweepError(sweep.path, "trajectory", "trajectories are saved to the output folder: give out (--out)")
    for case in cases:
        case["threads"] = threads_per_task
        case["out"] = os.path.abspath(out) if out is not None else None
    return cases


def _progress(total: int, enabled: bool):
    if not enabled:
        return None
    try:
        from tqdm import tqdm
    except ImportError:
        return None
    return tqdm(total=total, file=sys.stderr, unit="sim", desc="elan batch", dynamic_ncols=True)


def _run_local_loop(cases: list, task: Callable, progress: bool) -> list:
    bar = _progress(len(cases), progress)
    rows = []
    for case in cases:
        rows.append(task(case))
        if bar is not None:
            bar.update(1)
    if bar is not None:
        bar.close()
    return rows


def _run_on_cluster(cases: list, task: Callable, client: Any, retries: int, progress: bool) -> list:
    from distributed import as_completed

    # pure=False: every case is its own task even when two cases are equal (a sweep may repeat a
    # case on purpose, to measure); the keys carry the index so the dashboard names them.
    futures = client.map(task, cases, pure=False, retries=retries, key=[f"elan-case-{c['index']}-{os.urandom(4).hex()}" for c in cases])
    bar = _progress(len(cases), progress)
    try:
        if bar is not None:
            for _ in as_completed(futures):
                bar.update(1)
        # determinism: gathered in the order submitted (sweep order), not the order finished.
        return client.gather(futures)
    finally:
        if bar is not None:
            bar.close()


def _describe(case: dict) -> str:
    params = ", ".join(f"{k}={_short(v)}" for k, v in case["params"].items())
    return f"case {case['index']} ({params})"


def _short(v: Any) -> str:
    text = json.dumps(v) if not isinstance(v, str) else v
    return text if len(text) <= 40 else text[:37] + "..."


def run(
    source: Any,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    client: Any = None,
    out: str | None = None,
    threads_per_task: int | None = 1,
    retries: int = DEFAULT_RETRIES,
    progress: bool = True,
    steps: int | None = None,
    task: Callable[[dict], dict] | None = None,
):
    """Runs a batch and returns a pandas DataFrame, one row a case, in sweep order.

    ``source``: a sweep file path (JSON or YAML), a sweep dict, a ``Sweep``, or a list of scenes
    (paths or scene objects; ``steps`` then sets their step count, default 600).
    ``workers``: the local cluster's worker processes (default: the cores); 0 runs every case in
    this process, one after the other, without Dask. ``scheduler``: the address of an existing
    Dask scheduler to use instead (``tcp://host:8786``); ``client``: an existing
    ``distributed.Client`` to use instead. ``out``: a folder for ``results.csv`` and the
    trajectories. ``threads_per_task``: the engine threads of each world (default 1: the workers
    are the parallelism). ``retries``: how many times a failed task is run again (a worker that dies
    is covered by the scheduler's allowed failures, at least this many).

    Raises SweepError for a bad sweep and BatchError for a case whose scene the engine refuses
    (``.field`` names the field) or that failed after the retries.
    """
    cases = cases_of(source, out, threads_per_task, steps)
    if task is None:
        # By its module's name, so that under `python3 -m elan.batch` (where this module is
        # __main__) the workers import elan.batch rather than receive a pickled copy of __main__.
        import importlib

        task = importlib.import_module(f"{__package__ or 'elan'}.batch").run_case
    if client is not None:
        rows = _run_on_cluster(cases, task, client, retries, progress)
    elif scheduler is not None:
        from distributed import Client

        try:
            c = Client(scheduler, timeout="20s")
        except OSError as e:
            raise BatchError(f"cannot connect to the Dask scheduler at {scheduler}: {e}", "scheduler", True) from None
        with c:
            rows = _run_on_cluster(cases, task, c, retries, progress)
    elif workers == 0:
        rows = _run_local_loop(cases, task, progress)
    else:
        import dask
        from distributed import Client, LocalCluster

        n = workers if workers is not None else (os.cpu_count() or 1)
        # A worker that dies takes its running task with it; the scheduler runs the task again
        # elsewhere until it has seen `allowed-failures` deaths with it.
        with dask.config.set({"distributed.scheduler.allowed-failures": max(3, retries)}):
            with LocalCluster(
                n_workers=n,
                threads_per_worker=1,
                processes=True,
                dashboard_address=None,
                silence_logs=50,  # logging.CRITICAL: a restarted worker is expected, not news
            ) as cluster, Client(cluster) as c:
                rows = _run_on_cluster(cases, task, c, retries, progress)
    for case, row in zip(cases, rows):
        if "error" in row:
            raise BatchError(f"{_describe(case)}: {row['error']}", row.get("error_field", ""), True)
    return _table(rows, out)


def _table(rows: list, out: str | None):
    import pandas as pd

    frame = pd.DataFrame(rows)
    if "case" in frame.columns:
        frame = frame.set_index("case", drop=False)
        frame.index.name = None
    if out is not None:
        os.makedirs(out, exist_ok=True)
        frame.to_csv(os.path.join(out, RESULTS_CSV), index=False)
    return frame


# --- the command line ---------------------------------------------------------------------------


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog=os.environ.get("ELAN_BATCH_PROG", "elan batch"),
        description="Run the cases of a sweep file as independent simulations on a Dask cluster "
        "and write their summaries to OUT/results.csv (see docs/batch.md).",
        epilog="Prints one JSON object on stdout at the end; the progress bar goes to stderr. "
        "Exit status: 0 ok, 1 a task failed after its retries, 2 a bad sweep, scene or argument.",
    )
    p.add_argument("sweep", metavar="SWEEP", help="sweep file (.json, or .yaml/.yml)")
    p.add_argument("--workers", type=int, metavar="N", default=None,
                   help="worker processes of the local cluster (default: the cores); 0 runs the "
                   "cases in this process without Dask")
    p.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="use the Dask scheduler at ADDRESS (tcp://host:8786) instead of a local cluster")
    p.add_argument("--out", metavar="DIR", default=None,
                   help="output folder for results.csv and trajectories (default: SWEEP's name "
                   "without its extension, followed by -results, in the current folder)")
    p.add_argument("--threads-per-task", type=int, metavar="T", default=1,
                   help="engine threads of each simulation (default 1)")
    p.add_argument("--retries", type=int, metavar="R", default=DEFAULT_RETRIES,
                   help=f"times a failed task is run again (default {DEFAULT_RETRIES})")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    return p


def main(argv: Sequence[str] | None = None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    prog = parser.prog
    for name, value, low in (("--workers", args.workers, 0), ("--threads-per-task", args.threads_per_task, 1),
                             ("--retries", args.retries, 0)):
        if value is not None and value < low:
            parser.error(f"{name}: must be at least {low}, got {value}")
    if args.workers is not None and args.scheduler is not None:
        parser.error("--workers and --scheduler: give one (the scheduler's cluster has its own workers)")
    out = args.out
    if out is None:
        stem = os.path.splitext(os.path.basename(args.sweep))[0] or "batch"
        out = f"{stem}-results"
    start = time.perf_counter()
    try:
        frame = run(
            args.sweep,
            workers=args.workers,
            scheduler=args.scheduler,
            out=out,
            threads_per_task=args.threads_per_task,
            retries=args.retries,
            progress=not args.no_progress,
        )
    except SweepError as e:
        print(f"{prog}: {e}", file=sys.stderr)
        return 2
    except BatchError as e:
        print(f"{prog}: {args.sweep}: {e}", file=sys.stderr)
        return 2 if e.bad_input else 1
    except KeyboardInterrupt:
        print(f"{prog}: interrupted", file=sys.stderr)
        return 130
    except Exception as e:  # a task that failed after its retries, a worker that kept dying
        print(f"{prog}: {args.sweep}: the batch failed: {type(e).__name__}: {e}", file=sys.stderr)
        return 1
    wall = time.perf_counter() - start
    summary = {
        "sweep": args.sweep,
        "cases": len(frame),
        "workers": args.scheduler if args.scheduler else (args.workers if args.workers is not None else os.cpu_count()),
        "threads_per_task": args.threads_per_task,
        "wall_seconds": wall,
        "simulations_per_second": len(frame) / wall if wall > 0 else math.inf,
        "csv": os.path.join(out, RESULTS_CSV),
    }
    print(json.dumps(summary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
