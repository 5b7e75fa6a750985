#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes bench/cliffs/cylinders500_pile_drop.json: 500 cylinders (radius 0.3, half height 0.3,
the cylinders of cylinders500_one_point.json) on a lattice of 7 x 7 per layer, 0.9 m apart (more
than the 0.85 m a tilted cylinder spans, so none overlaps at the start), each tilted at random,
over a walled floor of 6.8 m x 6.8 m inside, so they fall into a pile about four deep, as
scenes/pile1k.json does for mixed shapes. Seeded: rerunning gives the same file.

The settled pile, cylinders500_pile.json, is that scene's poses after 240 steps (4 s: the
pile's kinetic energy is then under 1 J), at rest: the first steps of a fresh world from it cost
what a settled pile's steps cost, in the same window of steps that cylinders500_one_point is
timed over (its first 3):

  bench/make_cylinder_pile.py
  elan run bench/cliffs/cylinders500_pile_drop.json --steps 240 --threads 1 \
      --trajectory /tmp/pile.csv --every 240
  bench/make_cylinder_pile.py --settled /tmp/pile.csv

Usage: bench/make_cylinder_pile.py [OUT_DIR] | --settled TRAJECTORY.csv [OUT_DIR]
"""
import json
import os
import random
import sys

from make_scenes import random_quat, static_box


def cylinder_pile_drop():
    rng = random.Random(42)
    inner = 3.4  # half the inner width of the walls, m
    bodies = [static_box("ground", (inner + 1, 1, inner + 1), (0, -1, 0)),
              static_box("wall_x_neg", (0.5, 5, inner), (-inner - 0.5, 5, 0)),
              static_box("wall_x_pos", (0.5, 5, inner), (inner + 0.5, 5, 0)),
              static_box("wall_z_neg", (inner + 1, 5, 0.5), (0, 5, -inner - 0.5)),
              static_box("wall_z_pos", (inner + 1, 5, 0.5), (0, 5, inner + 0.5))]
    for i in range(500):
        layer, cell = divmod(i, 49)
        ix, iz = divmod(cell, 7)
        bodies.append({"shape": {"type": "cylinder", "radius": 0.3, "half_height": 0.3},
                       "position": [round(0.9 * (ix - 3) + rng.uniform(-0.02, 0.02), 6),
                                    round(0.5 + 0.9 * layer, 6),
                                    round(0.9 * (iz - 3) + rng.uniform(-0.02, 0.02), 6)],
                       "orientation": random_quat(rng)})
    return {"gravity": [0, -9.81, 0], "timestep": 1.0 / 60.0, "allow_sleep": True,
            "bodies": bodies}


def settled(trajectory):
    """The drop scene with each cylinder at its pose of the trajectory's last step, at rest."""
    scene = cylinder_pile_drop()
    rows = {}
    with open(trajectory) as f:
        header = f.readline().strip().split(",")
        for line in f:
            r = dict(zip(header, line.strip().split(",")))
            rows[int(r["body"])] = r  # the last step's row of each body wins
    for i, body in enumerate(scene["bodies"]):
        r = rows.get(i)
        if r is None or body.get("motion") == "static":
            continue
        body["position"] = [float(r["px"]), float(r["py"]), float(r["pz"])]
        body["orientation"] = [float(r["qw"]), float(r["qx"]), float(r["qy"]), float(r["qz"])]
    return scene


def main():
    args = sys.argv[1:]
    if args and args[0] == "--settled":
        scene, name, args = settled(args[1]), "cylinders500_pile.json", args[2:]
    else:
        scene, name = cylinder_pile_drop(), "cylinders500_pile_drop.json"
    out = args[0] if args else os.path.join(os.path.dirname(__file__), "cliffs")
    path = os.path.join(out, name)
    with open(path, "w") as f:
        json.dump(scene, f, separators=(",", ":"))
        f.write("\n")
    print(path)


if __name__ == "__main__":
    main()
