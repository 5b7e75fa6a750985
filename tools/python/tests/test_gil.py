# SPDX-License-Identifier: MIT
"""World.step releases the GIL: a Python thread runs while a large world steps."""

import threading
import time

import pytest

import elan


def test_python_thread_runs_during_a_step(scenes):
    w = elan.World.from_scene_file(str(scenes / "pile4k.json"), threads=1)
    w.step(1)  # warm: the first step allocates
    stamps = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            stamps.append(time.perf_counter())
            time.sleep(0.0005)

    t = threading.Thread(target=tick)
    t.start()
    time.sleep(0.01)
    t0 = time.perf_counter()
    w.step(200)
    t1 = time.perf_counter()
    stop.set()
    t.join()
    # Holding the GIL, the step would let no Python code run between its start and its end;
    # the interpreter's switch interval (5 ms) bounds how late the thread may still run after
    # t0 or how early it may resume before t1, so only stamps well inside count.
    margin = 0.02
    assert t1 - t0 > 4 * margin, "the step is too short to tell"
    inside = [s for s in stamps if t0 + margin < s < t1 - margin]
    assert len(inside) >= 10


def test_other_threads_cannot_use_a_stepping_world(scenes):
    w = elan.World.from_scene_file(str(scenes / "pile4k.json"), threads=1)
    errors = []
    started = threading.Event()

    def step():
        started.set()
        w.step(10)

    t = threading.Thread(target=step)
    t.start()
    started.wait()
    deadline = time.perf_counter() + 5
    while t.is_alive() and time.perf_counter() < deadline:
        try:
            w.body_count
        except elan.Error as e:
            errors.append(e.field)
            break
        time.sleep(0.001)
    t.join()
    assert errors == ["world"]
    assert w.body_count > 0  # usable again once the step is over
