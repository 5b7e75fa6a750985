# SPDX-License-Identifier: MIT
"""A deterministic replay regression test, as a project that simulates with elan would keep one:
each scene, stepped N times, must end in the state hash recorded in golden_hashes.json, with one
engine thread or two, and again when replayed from the start in the same process. Any change of
behaviour, however small, changes a hash.

    python3 -m pytest examples/python/test_replay_regression.py
    ELAN_UPDATE_GOLDEN=1 python3 -m pytest examples/python/test_replay_regression.py   # re-record

The hashes are those of the portable build (no -march=native), as in the engine's own golden test
(tests/determinism/golden_hashes.cpp); re-record them after a deliberate change of behaviour.
"""

import json
import os
import pathlib

import pytest

import elan

GOLDEN = pathlib.Path(__file__).with_name("golden_hashes.json")
SCENES = pathlib.Path(os.environ.get("ELAN_SCENES", pathlib.Path(__file__).resolve().parents[2] / "scenes"))
UPDATE = os.environ.get("ELAN_UPDATE_GOLDEN") == "1"


def golden() -> dict:
    return json.loads(GOLDEN.read_text())


def hash_after(scene: str, steps: int, threads: int) -> str:
    world = elan.World.from_scene_file(str(SCENES / scene), threads=threads)
    world.step(steps)
    assert world.step_count == steps
    return f"{world.state_hash:016x}"


@pytest.mark.parametrize("name", sorted(golden()))
def test_state_hash_matches_the_golden(name):
    entry = golden()[name]
    got = hash_after(entry["scene"], entry["steps"], threads=1)
    if UPDATE:
        table = golden()
        table[name]["state_hash"] = got
        GOLDEN.write_text(json.dumps(table, indent=2) + "\n")
        return
    assert got == entry["state_hash"], f"{name}: the behaviour changed; if deliberately, re-record"


@pytest.mark.parametrize("name", sorted(golden()))
def test_replay_is_bit_identical_with_other_thread_counts(name):
    entry = golden()[name]
    first = hash_after(entry["scene"], entry["steps"], threads=1)
    assert hash_after(entry["scene"], entry["steps"], threads=2) == first
    assert hash_after(entry["scene"], entry["steps"], threads=1) == first
