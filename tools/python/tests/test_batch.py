# SPDX-License-Identifier: MIT
"""elan.batch on a Dask LocalCluster: the same state hashes as running the cases one by one in
this process, every result back exactly when a worker dies mid-batch, results in sweep order,
trajectories as `elan run --trajectory` writes them, and the command line's exit statuses."""

import csv
import functools
import json
import os
import subprocess
import sys
import time

import numpy as np
import pytest

# The batch runner's own dependencies (Debian: python3-distributed, python3-pandas).
cloudpickle = pytest.importorskip("cloudpickle")
pytest.importorskip("distributed")
pytest.importorskip("pandas")

import elan
from elan import batch

# The task wrappers below run on the workers, which cannot import this file by its name: they
# are sent by value.
cloudpickle.register_pickle_by_value(sys.modules[__name__])

SCENE = {
    "bodies": [{"motion": "static", "shape": {"type": "box", "half_extents": [6, 1, 6]}, "position": [0, -1, 0]}],
}
PILE = {"count": [2, 2, 2], "spacing": [1.1, 1.1, 1.1], "origin": [-0.55, 0.6, -0.55], "jitter": 0.05,
        "random_orientation": True, "body": {"shape": {"type": "box", "half_extents": [0.4, 0.4, 0.4]}}}
STEPS = 40


def sweep(**grid):
    """24 cases by default: friction x restitution x seed, a small pile falling onto the ground."""
    grid = grid or {"friction": [0.1, 0.6, 1.0], "restitution": [0.0, 0.5], "seed": [1, 2, 3, 4]}
    return {"scene": SCENE, "steps": STEPS, "piles": [PILE], "grid": grid}


def one_by_one(cases):
    """The reference: each case loaded and stepped here, with the plain API."""
    hashes = []
    for case in cases:
        world = elan.World.from_scene_json(case["scene_text"], base_dir=case["base_dir"], threads=1)
        world.step(case["steps"])
        hashes.append(f"{world.state_hash:016x}")
    return hashes


@pytest.fixture(scope="module")
def client():
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                      silence_logs=50) as cluster, Client(cluster) as c:
        yield c


def test_twenty_four_cases_on_two_workers_match_one_by_one_in_process():
    cases = batch.cases_of(sweep())
    assert len(cases) >= 20
    expected = one_by_one(cases)
    # The parameters matter: every case ends in another state (else the test could not tell a
    # case run with another's parameters).
    assert len(set(expected)) == len(cases)
    frame = batch.run(sweep(), workers=2, progress=False)
    assert list(frame["case"]) == list(range(len(cases)))
    assert list(frame["state_hash"]) == expected
    # And the same with more engine threads per task: the bits do not depend on them.
    frame = batch.run(sweep(), workers=0, threads_per_task=2, progress=False)
    assert list(frame["state_hash"]) == expected


def _dies_once(marker_dir, victims, case):
    """Runs the case, except that the first attempt of each victim kills its worker process
    mid-batch (os._exit: no exception, no clean-up, as a crash or the OOM killer would)."""
    if case["index"] in victims:
        try:
            fd = os.open(os.path.join(marker_dir, f"killed-{case['index']}"), os.O_CREAT | os.O_EXCL | os.O_WRONLY)
        except FileExistsError:
            pass
        else:
            os.close(fd)
            os._exit(1)
    return batch.run_case(case)


def test_a_worker_killed_mid_batch_still_yields_every_result_exactly(client, tmp_path):
    cases = batch.cases_of(sweep())
    expected = one_by_one(cases)
    victims = (3, 17)
    task = functools.partial(_dies_once, str(tmp_path), victims)
    frame = batch.run(sweep(), client=client, task=task, progress=False)
    # The workers did die: each victim's first attempt left its marker and never returned.
    assert sorted(os.listdir(tmp_path)) == sorted(f"killed-{v}" for v in victims)
    assert list(frame["case"]) == list(range(len(cases)))
    assert list(frame["state_hash"]) == expected


def _slow_first(case):
    """Earlier cases take longer, so they finish after later ones."""
    time.sleep(0.05 * (8 - case["index"]))
    row = batch.run_case(case)
    row["finished"] = time.time()
    return row


def test_results_come_in_sweep_order_not_completion_order(client):
    doc = sweep(friction=[0.2, 0.4, 0.6, 0.8], restitution=[0.0, 1.0])
    frame = batch.run(doc, client=client, task=_slow_first, progress=False)
    assert list(frame["case"]) == list(range(8))
    assert list(frame["friction"]) == [0.2, 0.2, 0.4, 0.4, 0.6, 0.6, 0.8, 0.8]
    assert list(frame["restitution"]) == [0.0, 1.0] * 4
    # The order was not the completion order: some later case finished before an earlier one.
    finished = list(frame["finished"])
    assert finished != sorted(finished)
    assert list(frame["state_hash"]) == one_by_one(batch.cases_of(doc))


def test_a_list_of_scenes_gives_elan_runs_hashes(elan_bin, scenes):
    paths = [str(scenes / "pyramid10.json"), str(scenes / "tower20.json")]
    frame = batch.run(paths, workers=0, steps=30, progress=False)
    for path, row in zip(paths, frame.itertuples()):
        out = json.loads(subprocess.run([elan_bin, "run", path, "--steps", "30", "--threads", "1"],
                                        check=True, capture_output=True, text=True).stdout)
        assert row.state_hash == out["state_hash"]
        assert row.scene == path
        assert row.kinetic_energy == out["kinetic_energy"]


def read_elan_trajectory(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


@pytest.mark.parametrize("fmt", ["csv", "npz"])
def test_trajectories_hold_what_elan_run_writes(elan_bin, tmp_path, fmt):
    doc = dict(sweep(seed=[7]), steps=12, trajectory={"format": fmt, "every": 5})
    frame = batch.run(doc, workers=0, out=str(tmp_path / "out"), progress=False)
    case = batch.cases_of(doc, out=str(tmp_path / "out"))[0]
    scene = tmp_path / "scene.json"
    scene.write_text(case["scene_text"])
    reference = tmp_path / "ref.csv"
    subprocess.run([elan_bin, "run", str(scene), "--steps", "12", "--trajectory", str(reference),
                    "--every", "5", "--threads", "1"], check=True, capture_output=True)
    header, expected = read_elan_trajectory(reference)
    path = frame["trajectory"][0]
    assert path == str(tmp_path / "out" / "trajectories" / f"case_00000.{fmt}")
    if fmt == "csv":
        # Byte for byte: the same bodies, steps and digits.
        assert open(path, "rb").read() == reference.read_bytes()
        _, got = read_elan_trajectory(path)
    else:
        data = np.load(path)
        samples, bodies = data["position"].shape[:2]
        assert list(data["step"]) == [0, 5, 10, 12]
        got = np.concatenate([
            np.repeat(data["step"], bodies)[:, None].astype(float),
            np.repeat(data["time"], bodies)[:, None],
            np.tile(data["body"], samples)[:, None].astype(float),
            *(data[k].reshape(samples * bodies, -1) for k in
              ("position", "orientation", "linear_velocity", "angular_velocity")),
        ], axis=1)
    # Steps 0, 5, 10 and the last, 12; the 8 pile bodies (the ground is static); the values to
    # the bit, as both sides print them so that they read back exactly.
    assert got.shape == (4 * 8, 16)
    # step, time (a double, %.17g) and body exactly; the state as the engine's Real, which the
    # CSV's %.9g identifies (for a float build) and the .npz stores as is.
    np.testing.assert_array_equal(got[:, :3], expected[:, :3])
    real = np.dtype(elan.World.from_scene_json(case["scene_text"]).column("px").dtype)
    np.testing.assert_array_equal(got[:, 3:].astype(real), expected[:, 3:].astype(real))
    assert (tmp_path / "out" / "results.csv").is_file()


def run_cli(args, **kw):
    return subprocess.run([sys.executable, "-m", "elan.batch", *args], capture_output=True, text=True, **kw)


def test_command_line_writes_the_table_and_prints_a_summary(tmp_path):
    path = tmp_path / "sweep.json"
    path.write_text(json.dumps(sweep(friction=[0.3, 0.9], seed=[1, 2])))
    out = tmp_path / "out"
    done = run_cli([str(path), "--workers", "2", "--out", str(out), "--no-progress"])
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)
    assert summary["cases"] == 4 and summary["csv"] == str(out / "results.csv")
    import pandas as pd

    table = pd.read_csv(out / "results.csv", dtype={"state_hash": str})
    assert list(table["state_hash"]) == one_by_one(batch.cases_of(str(path)))


BAD_SWEEPS = [
    ({"scene": SCENE, "grid": {"restitution": [0.5, 1.5]}}, "grid.restitution[1]"),
    ({"scene": SCENE, "cases": [{"gravity": [0, -9.81]}]}, "cases[0].gravity"),
]


@pytest.mark.parametrize("doc,field", BAD_SWEEPS, ids=[f for _, f in BAD_SWEEPS])
def test_bad_sweep_exits_2_naming_the_file_and_the_field(tmp_path, doc, field):
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(doc))
    done = run_cli([str(path), "--workers", "0", "--out", str(tmp_path / "out")])
    assert done.returncode == 2
    assert f"{path}: {field}: " in done.stderr
    assert done.stdout == ""


def test_scene_the_engine_refuses_exits_2_naming_the_case_and_the_field(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text(json.dumps({"scene": SCENE, "steps": 1,
                                "grid": {"/bodies/0/shape/half_extents": [[1, 1, 1], [1, -2, 1]]}}))
    done = run_cli([str(path), "--workers", "0", "--out", str(tmp_path / "out")])
    assert done.returncode == 2
    assert "case 1 (" in done.stderr and "shape.half_extents" in done.stderr
    with pytest.raises(batch.BatchError) as info:
        batch.run(str(path), workers=0, progress=False)
    assert "half_extents" in info.value.field


def test_bad_options_exit_2(tmp_path):
    path = tmp_path / "s.json"
    path.write_text(json.dumps(sweep(seed=[1])))
    assert run_cli([str(path), "--workers", "-1"]).returncode == 2
    assert run_cli([str(path), "--threads-per-task", "0"]).returncode == 2
    assert run_cli([str(tmp_path / "missing.json")]).returncode == 2


def test_elan_batch_runs_the_python_runner(elan_bin, tmp_path):
    done = subprocess.run([elan_bin, "--help"], capture_output=True, text=True)
    assert "batch SWEEP.json" in done.stdout
    done = subprocess.run([elan_bin, "batch", "--help"], capture_output=True, text=True)
    assert done.returncode == 0 and "--threads-per-task" in done.stdout and "usage: elan batch" in done.stdout
    path = tmp_path / "bad.json"
    path.write_text(json.dumps({"scene": SCENE, "friction": -1}))
    done = subprocess.run([elan_bin, "batch", str(path), "--workers", "0"], capture_output=True, text=True)
    assert done.returncode == 2
    assert f"elan batch: {path}: friction: must be a number from 0 to 100, got -1" in done.stderr
    path.write_text(json.dumps(sweep(seed=[3, 4])))
    out = tmp_path / "out"
    done = subprocess.run([elan_bin, "batch", str(path), "--workers", "0", "--out", str(out), "--no-progress"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["cases"] == 2
