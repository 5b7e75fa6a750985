#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the generated benchmark scenes into scenes/: many_pyramids, rain, tumbler and towers,
and the geometry scenes convex_vs_mesh, heightfield_rain, compounds and geometry_demo (with the
OBJ files of scenes/meshes/ that geometry_demo loads).

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


def grid(count, spacing, origin, body):
    return {"type": "grid", "count": list(count), "spacing": list(spacing),
            "origin": [round(c, 6) for c in origin], "body": body}


# The five convex shapes of the geometry scenes, about 0.4 m across their bounding radius; the
# hull is an irregular octahedron-like cloud, so that no two of them are alike in contact.
CONVEX = [
    {"type": "sphere", "radius": 0.4},
    {"type": "box", "half_extents": [0.35, 0.3, 0.4]},
    {"type": "capsule", "radius": 0.25, "half_height": 0.3},
    {"type": "cylinder", "radius": 0.35, "half_height": 0.3},
    {"type": "convex_hull", "points": [[0.4, 0, 0], [-0.35, 0.05, 0], [0, 0.4, 0.05],
                                       [0.05, -0.3, 0], [0, 0, 0.45], [0, 0.05, -0.35],
                                       [0.2, 0.2, 0.2], [-0.2, -0.2, -0.15]]},
]
# A quarter turn between the shapes' orientations, so boxes and cylinders do not land flat.
TILTS = [[1, 0, 0, 0], [0.92388, 0.38268, 0, 0], [0.92388, 0, 0, 0.38268],
         [0.92388, 0.2706, 0.2706, 0], [0.8660254, 0, 0.5, 0]]


def convex_rain(count, spacing, origin, offset, velocity=None):
    """One grid per convex shape, each shifted by `offset` from the last so they interleave."""
    gens = []
    for k, shape in enumerate(CONVEX):
        body = {"shape": shape, "orientation": TILTS[k], "friction": 0.6}
        if velocity:
            body["linear_velocity"] = velocity
        at = [origin[i] + k * offset[i] for i in range(3)]
        gens.append(grid(count, spacing, at, body))
    return gens


def convex_vs_mesh():
    """Jolt's ConvexVsMesh idea: 2560 convex bodies dropped on a terrain mesh of 100,352
    triangles (224 x 224 cells of 1 m)."""
    terrain = {"type": "terrain", "shape": "mesh", "cells": [224, 224], "spacing": [1, 1],
               "origin": [-112, 0, -112], "amplitude": 2, "wavelength": 24}
    return {"gravity": [0, -9.81, 0], "timestep": DT, "allow_sleep": True, "bodies": [],
            "generators": [terrain] + convex_rain([16, 2, 16], [5, 3, 5], [-40, 4, -40],
                                                  [1, 0.6, 1])}


def heightfield_rain():
    """3000 convex bodies raining on a heightfield of 256 x 256 cells (0.5 m)."""
    terrain = {"type": "terrain", "shape": "heightfield", "cells": [256, 256],
               "spacing": [0.5, 0.5], "origin": [-64, 0, -64], "amplitude": 1.5,
               "wavelength": 16}
    return {"gravity": [0, -9.81, 0], "timestep": DT, "allow_sleep": True, "bodies": [],
            "generators": [terrain] + convex_rain([10, 6, 10], [4, 2.5, 4], [-20, 4, -20],
                                                  [0.8, 0.5, 0.8], [0, -4, 0])}


def box(half, at, q=None):
    c = {"shape": {"type": "box", "half_extents": half}, "position": at}
    if q:
        c["orientation"] = q
    return c


def table():
    legs = [box([0.04, 0.2, 0.04], [sx * 0.44, 0.2, sz * 0.29]) for sx in (-1, 1) for sz in (-1, 1)]
    return {"type": "compound", "children": [box([0.5, 0.05, 0.35], [0, 0.45, 0])] + legs}


def chair():
    legs = [box([0.03, 0.21, 0.03], [sx * 0.21, 0.21, sz * 0.21]) for sx in (-1, 1) for sz in (-1, 1)]
    return {"type": "compound", "children": [box([0.25, 0.03, 0.25], [0, 0.45, 0])] + legs +
            [box([0.25, 0.25, 0.03], [0, 0.73, -0.22])]}


def l_shape():
    return {"type": "compound", "children": [box([0.2, 0.2, 0.2], at) for at in
                                             ([0, 0, 0], [0.4, 0, 0], [0.8, 0, 0], [0, 0.4, 0])]}


def dumbbell():
    bar = {"shape": {"type": "cylinder", "radius": 0.05, "half_height": 0.35},
           "orientation": [0.70710678, 0, 0, 0.70710678]}
    bells = [{"shape": {"type": "sphere", "radius": 0.18}, "position": [sx * 0.42, 0, 0]}
             for sx in (-1, 1)]
    return {"type": "compound", "children": [bar] + bells}


def compounds():
    """Box2D's compound pile (junkyard): 1024 compounds of 3 to 6 children (tables, chairs, L
    shapes, dumbbells) falling on a ground box."""
    gens = []
    for k, (shape, at) in enumerate(((table(), [-19, 1, -19]), (chair(), [1, 1, -19]),
                                     (l_shape(), [-19, 1.2, 1]), (dumbbell(), [1, 1.2, 1]))):
        body = {"shape": shape, "orientation": TILTS[k], "friction": 0.6}
        gens.append(grid([8, 4, 8], [2.2, 1.6, 2.2], at, body))
    return {"gravity": [0, -9.81, 0], "timestep": DT, "allow_sleep": True,
            "bodies": [static_box("ground", [40, 1, 40], [0, -1, 0])], "generators": gens}


def geometry_demo():
    """Every new shape once: a ramp mesh, a bowl (an OBJ mesh), a heightfield ground, a hull and
    a compound child from an OBJ file, and compounds sliding, rolling and settling."""
    ramp = {"name": "ramp", "motion": "static", "position": [-6, 0.6, -5],
            "shape": {"type": "mesh",
                      "vertices": [[-4, 3, -1.5], [2, 0, -1.5], [2, 0, 1.5], [-4, 3, 1.5]],
                      "triangles": [[0, 2, 1], [0, 3, 2]]}}
    bowl = {"name": "bowl", "motion": "static", "position": [5, 3.2, 4],
            "shape": {"type": "mesh", "file": "meshes/bowl.obj"}}
    bodies = [ramp, bowl]
    bodies.append({"name": "table", "shape": table(), "position": [0, 0.8, 6]})
    for i in range(4):
        bodies.append({"shape": dumbbell(), "position": [-9 + 1.2 * i, 5.5 + 0.5 * i, -5],
                       "orientation": [0.70710678, 0, 0.70710678, 0]})
    for i in range(3):
        bodies.append({"shape": chair(), "position": [4 + 0.8 * i, 5 + 1.2 * i, 4],
                       "orientation": TILTS[i]})
    for i in range(6):
        bodies.append({"shape": CONVEX[i % 5], "position": [5.5 + 0.3 * i, 8 + 1.0 * i, 3.5],
                       "friction": 0.6})
    bodies.append({"name": "gem", "shape": {"type": "convex_hull", "file": "meshes/wedge.obj"},
                   "position": [0, 3, 6]})
    bodies.append({"name": "hammer", "position": [-2, 2, 2], "shape": {"type": "compound", "children": [
        {"shape": {"type": "cylinder", "radius": 0.05, "half_height": 0.5}},
        {"shape": {"type": "convex_hull", "file": "meshes/wedge.obj"}, "position": [0, 0.6, 0]}]}})
    ground = {"type": "terrain", "shape": "heightfield", "cells": [32, 32], "spacing": [1, 1],
              "origin": [-16, -0.5, -16], "amplitude": 0.3, "wavelength": 10}
    return {"gravity": [0, -9.81, 0], "timestep": DT, "allow_sleep": True, "bodies": bodies,
            "generators": [ground]}


def bowl_obj():
    """A hemispherical bowl of radius 3 m opening up, its rim at y = 0: 24 segments, 6 rings of
    quads and a fan of triangles at the bottom."""
    seg, rings, r = 24, 6, 3.0
    lines = ["# a hemispherical bowl, radius 3 m, rim at y = 0 (bench/make_scenes.py)"]
    for k in range(rings):  # ring k at polar angle from the rim down
        a = (math.pi / 2) * k / rings
        for i in range(seg):
            b = 2 * math.pi * i / seg
            lines.append("v %.6f %.6f %.6f" % (r * math.cos(a) * math.cos(b), -r * math.sin(a),
                                               r * math.cos(a) * math.sin(b)))
    lines.append("v 0 %.6f 0" % -r)
    for k in range(rings - 1):
        for i in range(seg):
            a, b = k * seg + i + 1, k * seg + (i + 1) % seg + 1
            lines.append("f %d %d %d %d" % (a, b, b + seg, a + seg))
    bottom = rings * seg + 1
    for i in range(seg):
        a, b = (rings - 1) * seg + i + 1, (rings - 1) * seg + (i + 1) % seg + 1
        lines.append("f %d %d %d" % (a, b, bottom))
    return "\n".join(lines) + "\n"


# A wedge (a triangular prism), written with quads and negative indices.
WEDGE_OBJ = """# a wedge: a triangular prism 0.6 m long (bench/make_scenes.py)
v -0.2 -0.15 -0.3
v 0.2 -0.15 -0.3
v 0 0.2 -0.3
v -0.2 -0.15 0.3
v 0.2 -0.15 0.3
v 0 0.2 0.3
f -6 -4 -5
f -3 -2 -1
f 1 2 5 4
f 2 3 6 5
f 3 1 4 6
"""


def write_scene(path, scene):
    with open(path, "w") as f:
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


def generated_bodies(g):
    if g["type"] == "pyramid":
        return g["base"] * (g["base"] + 1) * (2 * g["base"] + 1) // 6
    if g["type"] == "grid":
        return g["count"][0] * g["count"][1] * g["count"][2]
    return 1  # terrain


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
                       ("convex_vs_mesh", convex_vs_mesh), ("heightfield_rain", heightfield_rain),
                       ("compounds", compounds), ("geometry_demo", geometry_demo),
                       ("towers", towers)):
        scene = make()
        write_scene(os.path.join(out, name + ".json"), scene)
        n = len(scene["bodies"]) + sum(generated_bodies(g) for g in scene.get("generators", []))
        print("%s: %d bodies" % (name, n))
    os.makedirs(os.path.join(out, "meshes"), exist_ok=True)
    with open(os.path.join(out, "meshes", "bowl.obj"), "w") as f:
        f.write(bowl_obj())
    with open(os.path.join(out, "meshes", "wedge.obj"), "w") as f:
        f.write(WEDGE_OBJ)


if __name__ == "__main__":
    main()
