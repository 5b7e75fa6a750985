#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Batch throughput: simulations per second for 200 small scenes (a seeded pile of 8 boxes
falling onto the ground, 60 steps each), run by a plain loop in one process, and by elan.batch
on a Dask LocalCluster of 1 and of 2 workers. Each is timed from the first task submitted to the
last result back; starting the cluster is timed apart. Prints a Markdown table.

    PYTHONPATH=build/p/tools/python /usr/bin/python3 tools/python/bench/batch_throughput.py
"""

import argparse
import os
import platform
import statistics
import time

import elan
from elan import batch

SCENE = {"bodies": [{"motion": "static", "shape": {"type": "box", "half_extents": [6, 1, 6]}, "position": [0, -1, 0]}]}
PILE = {"count": [2, 2, 2], "spacing": [1.1, 1.1, 1.1], "origin": [-0.55, 0.6, -0.55], "jitter": 0.05,
        "random_orientation": True, "body": {"shape": {"type": "box", "half_extents": [0.4, 0.4, 0.4]}}}


def sweep(n, steps):
    return {"scene": SCENE, "steps": steps, "piles": [PILE], "grid": {"seed": list(range(n))}}


def plain_loop(cases):
    """What a user would write without elan.batch: load, step, summarise, one after the other."""
    hashes = []
    for case in cases:
        world = elan.World.from_scene_json(case["scene_text"], threads=1)
        world.step(case["steps"])
        world.summary()
        hashes.append(f"{world.state_hash:016x}")
    return hashes


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--scenes", type=int, default=200)
    parser.add_argument("--steps", type=int, default=60)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    from distributed import Client, LocalCluster

    doc = sweep(args.scenes, args.steps)
    cases = batch.cases_of(doc)
    reference = None
    rows = []

    times = []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        reference = plain_loop(cases)
        times.append(time.perf_counter() - t0)
    rows.append(("plain loop, one process", "-", statistics.median(times), None))

    for workers in (1, 2):
        t0 = time.perf_counter()
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                          silence_logs=50) as cluster, Client(cluster) as client:
            client.wait_for_workers(workers)
            startup = time.perf_counter() - t0
            # One small batch first, so that every worker has imported elan (as the plain loop's
            # process has): the timed runs then measure the batch, not the imports.
            batch.run(sweep(workers * 2, 1), client=client, progress=False)
            times = []
            for _ in range(args.repeat):
                t0 = time.perf_counter()
                frame = batch.run(doc, client=client, progress=False)
                times.append(time.perf_counter() - t0)
                assert list(frame["state_hash"]) == reference, "a batch gave other hashes than the loop"
        rows.append((f"elan.batch, LocalCluster of {workers}", str(workers), statistics.median(times), startup))

    base = rows[0][2]
    print(f"{args.scenes} scenes x {args.steps} steps (8 boxes falling onto the ground), "
          f"median of {args.repeat}; {platform.processor() or platform.machine()}, {os.cpu_count()} cores\n")
    print("| run | workers | seconds | simulations/s | vs plain loop | cluster start (s) |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for name, workers, seconds, startup in rows:
        start = f"{startup:.2f}" if startup is not None else "-"
        print(f"| {name} | {workers} | {seconds:.2f} | {args.scenes / seconds:.0f} | {base / seconds:.2f}x | {start} |")
    print("\nEvery batch gave the plain loop's 200 state hashes, in the same order.")


if __name__ == "__main__":
    main()
