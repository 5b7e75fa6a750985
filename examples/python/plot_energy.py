#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Steps a scene and plots its kinetic energy against time with matplotlib (the Agg backend, so
no display is needed), and writes the plot to a PNG.

    python3 examples/python/plot_energy.py scenes/spheres_in_box.json --steps 600 --out energy.png
"""

import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

import elan  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?", default=os.path.join(HERE, "..", "..", "scenes", "spheres_in_box.json"))
    parser.add_argument("--steps", type=int, default=600)
    parser.add_argument("--threads", type=int, default=None, help="engine threads (default: all cores)")
    parser.add_argument("--out", default="energy.png")
    args = parser.parse_args()

    world = elan.World.from_scene_file(args.scene, threads=args.threads)
    dt = world.summary()["timestep"]  # s per step
    times, energy, awake = [0.0], [world.summary()["kinetic_energy"]], [world.summary()["awake"]]
    for _ in range(args.steps):
        world.step()
        summary = world.summary()
        times.append(world.step_count * dt)
        energy.append(summary["kinetic_energy"])  # J
        awake.append(summary["awake"])

    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
    top.plot(times, energy)
    top.set_ylabel("kinetic energy (J)")
    top.set_title(os.path.basename(args.scene))
    bottom.plot(times, awake, color="tab:orange")
    bottom.set_ylabel("awake bodies")
    bottom.set_xlabel("time (s)")
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    print(f"{args.out}: {args.steps} steps, kinetic energy {energy[0]:.4g} J -> {energy[-1]:.4g} J")


if __name__ == "__main__":
    main()
