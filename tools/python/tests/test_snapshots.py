# SPDX-License-Identifier: MIT
"""Snapshots as bytes and pickle: a restored world continues bit for bit."""

import pickle

import pytest

import elan


def test_pickle_round_trip_continues_bit_for_bit(scenes):
    a = elan.World.from_scene_file(str(scenes / "pile1k.json"), threads=1)
    a.step(30)
    b = pickle.loads(pickle.dumps(a))
    assert b.state_hash == a.state_hash
    assert b.step_count == a.step_count == 30
    assert b.timestep == a.timestep
    for _ in range(3):
        a.step(10)
        b.step(10)
        assert b.state_hash == a.state_hash
        assert a.compare(b) is None
    assert b.summary()["state_hash"] == a.summary()["state_hash"]


def test_snapshot_bytes_restore(scenes):
    w = elan.World.from_scene_file(str(scenes / "pyramid10.json"))
    w.step(10)
    snap = w.save_snapshot()
    assert isinstance(snap, bytes)
    h10 = w.state_hash
    w.step(20)
    h30 = w.state_hash
    w.restore_snapshot(snap)
    assert w.state_hash == h10
    w.step(20)
    assert w.state_hash == h30
    other = elan.World.load_snapshot(snap, threads=1)
    other.step(20)
    assert other.state_hash == h30


def test_rollback(scenes):
    w = elan.World.from_scene_file(str(scenes / "pyramid10.json"))
    w.step(5)
    state = w.save_rollback()
    w.step(10)
    h = w.state_hash
    w.restore_rollback(state)
    w.step(10)
    assert w.state_hash == h


def test_bad_snapshot_bytes(scenes):
    w = elan.World.from_scene_file(str(scenes / "pyramid10.json"))
    snap = w.save_snapshot()
    for bad in (b"", b"hello", snap[:-1], snap[:100], bytes(len(snap))):
        with pytest.raises(elan.Error) as e:
            w.restore_snapshot(bad)
        assert e.value.field == "snapshot"
        with pytest.raises(elan.Error):
            elan.World.load_snapshot(bad)
    flipped = bytearray(snap)
    flipped[len(snap) // 2] ^= 1
    with pytest.raises(elan.Error):
        w.restore_snapshot(bytes(flipped))
    with pytest.raises(TypeError):
        w.restore_snapshot("text")
    with pytest.raises(elan.Error):
        w.restore_rollback(b"nope")
