# SPDX-License-Identifier: MIT
"""Zero-copy column views and the bulk setters."""

import gc

import numpy as np
import pytest

import elan

COLUMNS = ["px", "py", "pz", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz"]


@pytest.fixture
def world(scenes):
    return elan.World.from_scene_file(str(scenes / "pile1k.json"), threads=1)


def test_views_are_the_columns(world):
    cols = world.body_columns()
    assert cols._fields == tuple(COLUMNS)
    for name, arr in zip(COLUMNS, cols):
        assert arr.__array_interface__["data"][0] == world._column_address(name)
        assert arr.shape == (world.body_count,)
        assert not arr.flags.writeable
        assert not arr.flags.owndata
        with pytest.raises(ValueError):
            arr[0] = 1.0


def test_view_shows_new_positions_without_fetching_again(world):
    py = world.column("py")
    address = py.__array_interface__["data"][0]
    before = py.copy()
    world.step(10)
    assert py.__array_interface__["data"][0] == address == world._column_address("py")
    assert not np.array_equal(before, py)  # the pile fell: the same array shows it
    ids = world.body_ids()
    for i in (0, 100, len(ids) - 1):
        assert py[i] == np.float32(world.center_of_mass(int(ids[i]))[1])


def test_view_keeps_the_world_alive(scenes):
    w = elan.World.from_scene_file(str(scenes / "pile1k.json"))
    vy = w.column("vy")
    w.step(5)
    expected = vy.copy()
    del w
    gc.collect()
    assert np.array_equal(vy, expected)  # the base object still owns the column


def test_bulk_setter_moves_the_bodies(world):
    px, py, pz = world.column("px"), world.column("py"), world.column("pz")
    pos = np.stack([px, py, pz], axis=1).astype(np.float64)
    pos[:, 1] += 10.0
    ids = world.body_ids()
    dynamic = [i for i in range(len(ids)) if world.motion_type(int(ids[i])) == "dynamic"]
    old = world.center_of_mass(int(ids[dynamic[0]]))
    world.set_center_of_mass_positions(pos)
    new = world.center_of_mass(int(ids[dynamic[0]]))
    assert new[1] == pytest.approx(old[1] + 10.0, abs=1e-4)
    assert py[dynamic[0]] == pytest.approx(old[1] + 10.0, abs=1e-4)  # the view shows it too
    v = np.zeros((len(ids), 3))
    v[:, 0] = 2.0
    world.set_linear_velocities(v)
    assert world.linear_velocity(int(ids[dynamic[0]]))[0] == pytest.approx(2.0)
    world.set_angular_velocities(np.zeros((len(ids), 3)))


def test_bulk_setters_check_the_shape(world):
    n = world.body_count
    for bad in (np.zeros((n, 2)), np.zeros((n + 1, 3)), np.zeros(n), [[1, 2, 3]], "abc"):
        with pytest.raises(elan.Error) as e:
            world.set_center_of_mass_positions(bad)
        assert e.value.field == "positions"
    bad = np.zeros((n, 3))
    bad[3, 1] = np.nan
    with pytest.raises(elan.Error) as e:
        world.set_linear_velocities(bad)
    assert e.value.field == "linear_velocities"
    with pytest.raises(elan.Error) as e:
        world.column("pq")
    assert e.value.field == "column"
