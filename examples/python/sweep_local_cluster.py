#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A parameter sweep on a local Dask cluster: balls dropped onto a pyramid of boxes, for three
restitutions, two frictions and four seeds (where the balls start), 24 simulations. Prints, per
restitution and friction, the mean over the seeds of what is still moving at the end.

    python3 examples/python/sweep_local_cluster.py --workers 2
    elan batch examples/python/pile_sweep.json --workers 2      # the same, from the shell

The sweep is pile_sweep.json next to this file; docs/batch.md describes the format.
"""

import argparse
import os

from elan import batch

HERE = os.path.dirname(os.path.abspath(__file__))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sweep", default=os.path.join(HERE, "pile_sweep.json"))
    parser.add_argument("--workers", type=int, default=2, help="worker processes (default 2)")
    parser.add_argument("--steps", type=int, default=None, help="override the sweep's steps")
    parser.add_argument("--out", default=None, help="also write OUT/results.csv")
    args = parser.parse_args()

    sweep = batch.load_sweep(args.sweep)
    if args.steps is not None:
        sweep.defaults["steps"] = args.steps
    results = batch.run(sweep, workers=args.workers, out=args.out)

    # One row per simulation, in sweep order; the summary's columns beside the parameters.
    print(results[["restitution", "friction", "seed", "state_hash", "kinetic_energy", "awake"]].to_string(index=False))
    table = results.groupby(["restitution", "friction"])[["kinetic_energy", "awake"]].mean()
    print("\nmean over the seeds:")
    print(table.to_string())


# The cluster's worker processes are started by spawning Python anew: the guard keeps them from
# running the sweep themselves when they import this file.
if __name__ == "__main__":
    main()
