#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the abuse scenes into scenes/abuse/: what users do build, at the edges of the supported
ranges (docs/limits.md), each beside a normal scene of the same size to compare step times with.

  spawn100           100 unit boxes created at one point, on a floor
  tiny_on_huge       a 1 mm box resting on a 1 km box, which rests on a floor
  heavy_on_light     a 1e6 kg box resting on a 1 kg box, on a floor
  fast_bodies        a ball at 1e4 m/s towards a wall, one at 1e4 m/s down onto the floor, and a
                     capsule and a box spinning at 1e4 rad/s
  high_gravity       gravity 1e4 m/s^2 on a pyramid of 15 boxes
  reference_pile100  100 unit boxes in a 5 x 4 x 5 grid a little apart, on a floor: the normal
                     pile of spawn100's size

Usage: bench/make_abuse_scenes.py [SCENE_DIR]
"""
import json
import os
import sys

FLOOR = {"name": "floor", "motion": "static",
         "shape": {"type": "box", "half_extents": [50, 1, 50]}, "position": [0, -1, 0]}


def box(half, pos, **extra):
    body = {"shape": {"type": "box", "half_extents": list(half)}, "position": list(pos)}
    body.update(extra)
    return body


def scene(bodies, gravity=(0, -9.81, 0), generators=None):
    s = {"gravity": list(gravity), "timestep": 1.0 / 60.0, "allow_sleep": True, "bodies": bodies}
    if generators:
        s["generators"] = generators
    return s


def scenes():
    out = {}
    out["spawn100"] = scene([FLOOR] + [box([0.5, 0.5, 0.5], [0, 2, 0]) for _ in range(100)])
    out["reference_pile100"] = scene(
        [FLOOR] + [box([0.5, 0.5, 0.5], [1.1 * x - 2.2, 0.5 + 1.1 * y, 1.1 * z - 2.2])
                   for x in range(5) for y in range(4) for z in range(5)])
    # The big box's density keeps its mass (5e8 kg) inside the supported range (1e9 kg).
    out["tiny_on_huge"] = scene([
        FLOOR | {"shape": {"type": "box", "half_extents": [2000, 1, 2000]}},
        box([500, 500, 500], [0, 500, 0], density=0.5, name="huge"),
        box([0.0005, 0.0005, 0.0005], [0, 1000.0005, 0], name="tiny"),
    ])
    out["heavy_on_light"] = scene([
        FLOOR,
        box([0.5, 0.5, 0.5], [0, 0.5, 0], density=1, name="light"),
        box([0.5, 0.5, 0.5], [0, 1.5, 0], density=1e6, name="heavy"),
    ])
    out["fast_bodies"] = scene([
        FLOOR,
        {"name": "wall", "motion": "static", "shape": {"type": "box", "half_extents": [0.5, 5, 5]},
         "position": [20, 5, 0]},
        {"name": "bullet", "shape": {"type": "sphere", "radius": 0.1}, "position": [0, 1, 0],
         "linear_velocity": [1e4, 0, 0]},
        {"name": "dropped", "shape": {"type": "sphere", "radius": 0.1}, "position": [5, 10, 5],
         "linear_velocity": [0, -1e4, 0]},
        {"name": "spinning_capsule", "shape": {"type": "capsule", "radius": 0.2, "half_height": 0.5},
         "position": [-5, 3, 0], "angular_velocity": [1e4, 0, 0]},
        {"name": "spinning_box", "shape": {"type": "box", "half_extents": [0.5, 0.2, 0.3]},
         "position": [-5, 3, 5], "angular_velocity": [0, 1e4, 5e3]},
    ])
    out["high_gravity"] = scene([FLOOR], gravity=(0, -1e4, 0),
                                generators=[{"type": "pyramid", "base": 5, "half_extent": 0.5,
                                             "origin": [0, 0, 0]}])
    return out


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "scenes")
    folder = os.path.join(root, "abuse")
    os.makedirs(folder, exist_ok=True)
    for name, s in scenes().items():
        with open(os.path.join(folder, name + ".json"), "w") as f:
            json.dump(s, f, indent=None, separators=(", ", ": "))
            f.write("\n")


if __name__ == "__main__":
    main()
