# SPDX-License-Identifier: MIT
"""The core the batch runner relies on: scene loading, stepping, the state hash and summary()
agreeing with `elan run`, and elan.Error with its field."""

import json
import subprocess

import pytest

import elan


def run_elan(elan_bin, scene, steps, *extra):
    out = subprocess.run(
        [elan_bin, "run", str(scene), "--steps", str(steps), *extra],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    return json.loads(out)


@pytest.mark.parametrize("broadphase", ["sap", "tree"])
def test_same_state_hash_and_summary_as_elan_run(elan_bin, scenes, broadphase):
    scene = scenes / "pile1k.json"
    expected = run_elan(elan_bin, scene, 60, "--broadphase", broadphase, "--threads", "1")
    world = elan.World.from_scene_file(str(scene), threads=1, broadphase=broadphase)
    world.step(60)
    assert world.step_count == 60
    assert world.state_hash == int(expected["state_hash"], 16)
    summary = world.summary()
    assert list(summary) == list(expected)
    timing = {"wall_seconds", "ms_per_step", "profile_ms"}
    for key in expected:
        if key not in timing:
            assert summary[key] == expected[key], key


def test_from_scene_json_matches_the_file(scenes):
    path = scenes / "pile1k.json"
    a = elan.World.from_scene_file(str(path))
    b = elan.World.from_scene_json(path.read_text(), base_dir=str(scenes))
    a.step(10)
    b.step(5)
    b.step(5)
    assert a.state_hash == b.state_hash


def test_thread_count_does_not_change_the_bits(scenes):
    path = str(scenes / "pile1k.json")
    hashes = set()
    for threads in (1, 2, None):
        w = elan.World.from_scene_file(path, threads=threads)
        w.step(30)
        hashes.add(w.state_hash)
    assert len(hashes) == 1


def test_bad_scene_names_the_field():
    bad = '{"bodies": [{"shape": {"type": "sphere", "radius": -1}, "position": [0, 0, 0]}]}'
    with pytest.raises(elan.Error) as e:
        elan.World.from_scene_json(bad)
    assert e.value.field == "shape.radius"
    assert isinstance(e.value, ValueError)
    with pytest.raises(elan.Error) as e:
        elan.World.from_scene_json("{not json")
    assert e.value.field == "scene"
    with pytest.raises(elan.Error) as e:
        elan.World.from_scene_file("/nonexistent/scene.json")
    assert e.value.field == "scene"


def test_bad_keyword_arguments(scenes):
    path = str(scenes / "pile1k.json")
    with pytest.raises(elan.Error) as e:
        elan.World.from_scene_file(path, broadphase="octree")
    assert e.value.field == "broadphase"
    with pytest.raises(elan.Error) as e:
        elan.World.from_scene_file(path, threads=-1)
    assert e.value.field == "threads"
    w = elan.World.from_scene_file(path)
    with pytest.raises(elan.Error) as e:
        w.step(-1)
    assert e.value.field == "n"
    with pytest.raises(elan.Error) as e:
        w.step(1, dt=float("nan"))
    assert e.value.field == "dt"
    with pytest.raises(TypeError):
        w.step("ten")
