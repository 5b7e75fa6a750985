#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the generated benchmark scenes into scenes/: many_pyramids, rain, tumbler and towers.

Box2D/Box3D-style joint-free scenes. Seeded, so rerunning gives the same files.
Usage: bench/make_scenes.py [SCENE_DIR]
"""
import json
import math
import os
import random
import sys

DT = 1.0 / 60.0


def static_box(name, half, pos):
    return {"name": name, "motion": "static",
            "shape": {"type": "box", "half_extents": list(half)}, "position": list(pos)}


def random_quat(rng):
    # Shoemake's uniform random rotation, written [w, x, y, z].
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    q = [b * math.cos(2 * math.pi * u3), a * math.sin(2 * math.pi * u2),
         a * math.cos(2 * math.pi * u2), b * math.sin(2 * math.pi * u3)]
    return [round(c, 6) for c in q]


def mixed_shape(rng, size):
    """One of five shapes with a bounding radius of about `size` m."""
    kind = rng.randrange(5)
    s = lambda lo, hi: round(size * rng.uniform(lo, hi), 6)
    if kind == 0:
        return {"type": "sphere", "radius": s(0.7, 1.0)}
    if kind == 1:
        return {"type": "box", "half_extents": [s(0.4, 0.6), s(0.4, 0.6), s(0.4, 0.6)]}
    if kind == 2:
        return {"type": "capsule", "radius": s(0.3, 0.45), "half_height": s(0.3, 0.5)}
    if kind == 3:
        return {"type": "cylinder", "radius": s(0.4, 0.6), "half_height": s(0.3, 0.5)}
    # An irregular hull: 12 points on a jittered ellipsoid.
    ax = [s(0.5, 0.8) for _ in range(3)]
    pts = []
    for _ in range(12):
        d = [rng.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(c * c for c in d)) or 1.0
        pts.append([round(ax[i] * d[i] / n, 6) for i in range(3)])
    return {"type": "convex_hull", "points": pts}


def many_pyramids():
    # Box2D's "many pyramids": 20 small pyramids (base 5, 55 cubes each) on one ground, 8 m apart.
    gens = [{"type": "pyramid", "base": 5, "half_extent": 0.5,
             "origin": [(i % 5 - 2) * 8.0, 0, (i // 5 - 1.5) * 8.0]} for i in range(20)]
    return {"gravity": [0, -9.81, 0], "timestep": DT, "allow_sleep": True,
            "bodies": [static_box("ground", (30, 1, 30), (0, -1, 0))], "generators": gens}


def rain():
    # 2000 mixed shapes (spheres, boxes, capsules, cylinders, hulls) released at heights 3..60 m
    # over a 24 m x 24 m patch of a large floor, so they land over the first ~3.5 s and keep
    # raining onto those already down.
    rng = random.Random(7)
    bodies = [static_box("ground", (40, 1, 40), (0, -1, 0))]
    cells = [(x, z) for x in range(20) for z in range(20)]
    for i in range(2000):
        x, z = cells[i % len(cells)]
        layer = i // len(cells)
        bodies.append({
            "shape": mixed_shape(rng, 0.45),
            "position": [round(-11.4 + 1.2 * x + rng.uniform(-0.1, 0.1), 6),
                         round(3 + 11.5 * layer + rng.uniform(0, 10), 6),
                         round(-11.4 + 1.2 * z + rng.uniform(-0.1, 0.1), 6)],
            "orientation": random_quat(rng),
            "angular_velocity": [round(rng.uniform(-2, 2), 6) for _ in range(3)],
            "friction": 0.6})
    return {"gravity": [0, -9.81, 0], "timestep": DT, "allow_sleep": True, "bodies": bodies}


def tumbler():
    # A closed static box (inner 10 m x 10 m x 4 m, lid included) with a paddle cross turning
    # inside it about the z axis through the box centre at 1 rad/s. The cross is two kinematic
    # boxes, both centred on the axis with the same angular velocity and zero linear velocity:
    # each turns about its own centre, so the two turn together as one rigid cross, exactly,
    # with no per-step driving. Arms reach 4 m, leaving 1 m to the walls (bodies are <= 0.5 m),
    # so nothing is crushed. About 1000 mixed shapes start on a lattice clear of the arms.
    rng = random.Random(11)
    cy = 5.0
    bodies = [static_box("floor", (5.5, 0.5, 2.5), (0, -0.5, 0)),
              static_box("lid", (5.5, 0.5, 2.5), (0, 10.5, 0)),
              static_box("wall_x_neg", (0.5, 5, 2.5), (-5.5, 5, 0)),
              static_box("wall_x_pos", (0.5, 5, 2.5), (5.5, 5, 0)),
              static_box("wall_z_neg", (5, 5, 0.5), (0, 5, -2.5)),
              static_box("wall_z_pos", (5, 5, 0.5), (0, 5, 2.5))]
    for name, half in (("paddle_x", (4.0, 0.15, 1.9)), ("paddle_y", (0.15, 4.0, 1.9))):
        bodies.append({"name": name, "motion": "kinematic",
                       "shape": {"type": "box", "half_extents": list(half)},
                       "position": [0, cy, 0], "angular_velocity": [0, 0, 1.0]})
    step = 0.62
    for iz in range(6):
        for iy in range(15):
            for ix in range(16):
                x = -4.65 + step * ix
                y = 0.4 + step * iy
                z = -1.55 + step * iz
                if abs(x) < 0.55 or abs(y - cy) < 0.55:
                    continue
                bodies.append({"shape": mixed_shape(rng, 0.25),
                               "position": [round(x, 6), round(y, 6), round(z, 6)],
                               "orientation": random_quat(rng)})
    return {"gravity": [0, -9.81, 0], "timestep": DT, "allow_sleep": True, "bodies": bodies}


def towers():
    # Sixteen towers of 0.5 m cubes (125 kg each), 20 to 40 high, on a 4 x 4 grid 4 m apart,
    # each capped by a 0.5 m cube of 2500 kg (twenty cubes' mass): the loaded contacts of the
    # stacking issue (tall columns, heavy on light) in a scene to time and to compare.
    bodies = [static_box("ground", (12, 1, 12), (0, -1, 0))]
    for i in range(16):
        x, z = (i % 4 - 1.5) * 4.0, (i // 4 - 1.5) * 4.0
        height = 20 + (20 * i + 7) // 15
        for k in range(height):
            body = {"shape": {"type": "box", "half_extents": [0.25, 0.25, 0.25]},
                    "position": [x, 0.25 + 0.5 * k, z]}
            if k == height - 1:
                body["name"] = "cap%02d" % i
                body["mass"] = 2500
            bodies.append(body)
    return {"gravity": [0, -9.81, 0], "timestep": DT, "allow_sleep": True, "bodies": bodies}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "scenes")
    for name, make in (("many_pyramids", many_pyramids), ("rain", rain), ("tumbler", tumbler),
                       ("towers", towers)):
        scene = make()
        with open(os.path.join(out, name + ".json"), "w") as f:
            f.write("{\n")
            keys = [k for k in scene if k not in ("bodies", "generators")]
            for k in keys:
                f.write('  "%s": %s,\n' % (k, json.dumps(scene[k])))
            f.write('  "bodies": [\n')
            f.write(",\n".join("    " + json.dumps(b) for b in scene["bodies"]))
            f.write("\n  ]")
            if "generators" in scene:
                f.write(',\n  "generators": [\n')
                f.write(",\n".join("    " + json.dumps(g) for g in scene["generators"]))
                f.write("\n  ]")
            f.write("\n}\n")
        n = len(scene["bodies"]) + sum(g["base"] * (g["base"] + 1) * (2 * g["base"] + 1) // 6
                                       for g in scene.get("generators", []))
        print("%s: %d bodies" % (name, n))


if __name__ == "__main__":
    main()
