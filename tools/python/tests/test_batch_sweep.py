# SPDX-License-Identifier: MIT
"""Sweep files (elan.batch_sweep): the order of the cases, what each parameter changes in the
scene, the seeded piles, and a message naming the file and the field for every kind of bad sweep."""

import json
import math

import pytest

from elan import batch_sweep
from elan.batch_sweep import SplitMix64, Sweep, SweepError, load_sweep

GROUND = {"motion": "static", "shape": {"type": "box", "half_extents": [5, 1, 5]}, "position": [0, -1, 0]}


def small_scene():
    return {
        "bodies": [dict(GROUND), {"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "position": [0, 2, 0]}],
        "generators": [
            {"type": "grid", "count": [2, 1, 1], "spacing": [2, 2, 2], "origin": [3, 1, 0],
             "body": {"shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}}},
            {"type": "pyramid", "base": 2, "origin": [-3, 0, 0]},
        ],
        "joints": [{"type": "ball", "bodies": [1, 2], "anchor": [1, 1.5, 0]}],
    }


PILE = {"count": [2, 3, 1], "spacing": [1.5, 1.5, 1.5], "origin": [0, 4, 0], "jitter": 0.2,
        "random_orientation": True, "body": {"shape": {"type": "box", "half_extents": [0.3, 0.3, 0.3]}}}


def test_cases_then_grid_with_the_last_grid_key_fastest():
    sweep = Sweep({"scene": small_scene(), "steps": 7,
                   "grid": {"friction": [0.1, 0.2], "restitution": [0.0, 0.5, 1.0]},
                   "cases": [{"gravity": 9.81}, {"gravity": [0, -1.62, 0], "steps": 3}]})
    points = [p for p, _ in sweep.points()]
    assert len(points) == 2 * 2 * 3
    expected = [(g, f, e) for g in ([0.0, -9.81, 0.0], [0, -1.62, 0]) for f in (0.1, 0.2) for e in (0.0, 0.5, 1.0)]
    assert [(p["gravity"], p["friction"], p["restitution"]) for p in points] == expected
    assert [p["steps"] for p in points] == [7] * 6 + [3] * 6
    cases = sweep.cases()
    assert [c["index"] for c in cases] == list(range(12))
    assert [c["steps"] for c in cases] == [7] * 6 + [3] * 6


def test_parameters_set_every_material_and_the_world():
    sweep = Sweep({"scene": small_scene(), "friction": 0.8, "restitution": 0.25, "gravity": [1, -2, 3],
                   "timestep": 0.01, "substeps": 3, "iterations": 5, "allow_sleep": False,
                   "/bodies/1/linear_velocity": [4, 0, 0]})
    scene = json.loads(sweep.cases()[0]["scene_text"])
    assert scene["gravity"] == [1, -2, 3]
    assert (scene["timestep"], scene["substeps"], scene["iterations"], scene["allow_sleep"]) == (0.01, 3, 5, False)
    for body in scene["bodies"] + [scene["generators"][0]["body"]]:
        assert (body["friction"], body["restitution"]) == (0.8, 0.25)
    # A pyramid has no material keys: its cubes keep the default material.
    assert "friction" not in scene["generators"][1]
    assert scene["bodies"][1]["linear_velocity"] == [4, 0, 0]
    # The scene given is not changed.
    assert "friction" not in small_scene()["bodies"][0]


def test_no_parameters_leaves_the_scene_as_loaded(scenes):
    path = scenes / "pyramid10.json"
    sweep = Sweep({"scene": str(path), "steps": 1})
    assert json.loads(sweep.cases()[0]["scene_text"]) == json.loads(path.read_text())


def test_splitmix64_matches_its_reference_outputs():
    # The first outputs for seed 1234567 of the reference implementation (Vigna's splitmix64.c).
    rng = SplitMix64(1234567)
    assert [rng.next_u64() for _ in range(3)] == [6457827717110365317, 3203168211198807973, 9817491932198370423]
    u = SplitMix64(0).uniform()
    assert 0.0 <= u < 1.0


def test_piles_are_a_function_of_the_seed():
    def bodies(seed):
        sweep = Sweep({"scene": small_scene(), "piles": [PILE], "seed": seed})
        return json.loads(sweep.cases()[0]["scene_text"])["bodies"]

    a, b, c = bodies(5), bodies(5), bodies(6)
    assert a == b
    assert a != c
    pile = a[2:]
    assert len(a) == 2 + 6 and len(pile) == 6
    # x fastest, then y: body 1 of the pile is one spacing along x from body 0, within the jitter.
    for i, body in enumerate(pile):
        ix, iy = i % 2, i // 2
        base = [1.5 * ix, 4 + 1.5 * iy, 0]
        assert all(abs(p - q) <= 0.2 for p, q in zip(body["position"], base))
        assert math.isclose(sum(x * x for x in body["orientation"]), 1.0, rel_tol=1e-12)
    # Not all on the grid points: the jitter is there.
    assert any(body["position"][0] != 1.5 * (i % 2) for i, body in enumerate(pile))


def test_pile_bodies_shift_the_joints_that_name_generated_bodies():
    sweep = Sweep({"scene": small_scene(), "piles": [PILE]})
    scene = json.loads(sweep.cases()[0]["scene_text"])
    # Body 1 is an explicit body and stays; body 2 was the grid's first, now after 6 pile bodies.
    assert scene["joints"][0]["bodies"] == [1, 8]


def test_yaml_gives_the_same_cases_as_json(tmp_path, scenes):
    doc = {"scene": str(scenes / "pyramid10.json"), "steps": 4, "grid": {"friction": [0.25, 0.5]}}
    (tmp_path / "s.json").write_text(json.dumps(doc))
    (tmp_path / "s.yaml").write_text(
        f"scene: {scenes / 'pyramid10.json'}\nsteps: 4\ngrid:\n  friction: [0.25, 0.5]\n"
    )
    a = [c["scene_text"] for c in load_sweep(str(tmp_path / "s.json")).cases()]
    b = [c["scene_text"] for c in load_sweep(str(tmp_path / "s.yaml")).cases()]
    assert a == b and len(a) == 2


def test_scene_paths_are_relative_to_the_sweep_file(tmp_path):
    (tmp_path / "scenes").mkdir()
    (tmp_path / "scenes" / "a.json").write_text(json.dumps(small_scene()))
    (tmp_path / "s.json").write_text(json.dumps({"scene": "scenes/a.json", "steps": 1}))
    case = load_sweep(str(tmp_path / "s.json")).cases()[0]
    assert case["params"]["scene"] == "scenes/a.json"
    assert case["base_dir"] == str(tmp_path / "scenes")


BAD = [
    ({"scene": "S", "grid": {"friction": [0.5, -1]}}, "grid.friction[1]"),
    ({"scene": "S", "grid": {"friction": []}}, "grid.friction"),
    ({"scene": "S", "grid": {"frction": [0.5]}}, "grid.frction[0]"),
    ({"scene": "S", "restitution": 2}, "restitution"),
    ({"scene": "S", "gravity": [0, "x", 0]}, "gravity"),
    ({"scene": "S", "steps": 1.5}, "steps"),
    ({"scene": "S", "steps": True}, "steps"),
    ({"scene": "S", "cases": [{"steps": 3}, {"timestep": 0}]}, "cases[1].timestep"),
    ({"scene": "S", "grid": {"steps": [1]}, "cases": [{"steps": 3}]}, "cases[0].steps"),
    ({"scene": "S", "grid": {"seed": [1, 2]}}, "grid.seed"),
    ({"scene": "S", "piles": [{"count": [2, 0, 1], "spacing": [1, 1, 1], "body": {}}]}, "piles[0].count"),
    ({"scene": "S", "piles": [{"count": [1, 1, 1], "spacing": [1, 1, 1]}]}, "piles[0].body"),
    ({"scene": "S", "piles": [{"count": [1, 1, 1], "spacing": [1, 1, 1], "body": {"name": "x"}}]}, "piles[0].body.name"),
    ({"scene": "S", "trajectory": {"format": "hdf5"}}, "trajectory.format"),
    ({"scene": "S", "trajectory": {"every": 0}}, "trajectory.every"),
    ({"scene": "S", "broadphase": "octree"}, "broadphase"),
    ({"steps": 3}, "scene"),
    ({"scene": "missing.json"}, "scene"),
    ({"scene": "S", "/bodies/9/friction": 1}, "/bodies/9/friction"),
]


@pytest.mark.parametrize("doc,field", BAD, ids=[f for _, f in BAD])
def test_bad_sweep_names_the_file_and_the_field(tmp_path, doc, field):
    (tmp_path / "S").write_text(json.dumps(small_scene()))
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(SweepError) as info:
        load_sweep(str(path)).cases()
    assert info.value.field == field
    assert str(info.value).startswith(f"{path}: {field}: ")


def test_malformed_and_duplicate_keys_are_refused(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{"scene": "a.json", "steps": 3,}')
    with pytest.raises(SweepError, match="malformed JSON"):
        load_sweep(str(path))
    path.write_text('{"scene": "a.json", "steps": 3, "steps": 4}')
    with pytest.raises(SweepError) as info:
        load_sweep(str(path))
    assert info.value.field == "steps"
    assert batch_sweep.PARAMETERS[0] == "scene"
