# SPDX-License-Identifier: MIT
"""Bad arguments raise elan.Error naming the field (or TypeError for a wrong type), and no input
crashes the interpreter."""

import itertools
import math

import numpy as np
import pytest

import elan


@pytest.fixture
def world():
    w = elan.World(threads=1)
    w.create_body(w.create_shape("box", half_extents=(5, 1, 5)), motion="static",
                  position=(0, -1, 0))
    return w


def field_of(call):
    with pytest.raises(elan.Error) as e:
        call()
    return e.value.field


def test_fields_are_named(world):
    s = world.create_shape("sphere", radius=0.5)
    assert field_of(lambda: world.create_shape("sphere", radius=-1)) == "shape.radius"
    assert field_of(lambda: world.create_shape("blob")) == "shape.type"
    assert field_of(lambda: world.create_body(s, mass=-1.0)) == "mass"
    assert field_of(lambda: world.create_body(s, motion="flying")) == "motion"
    assert field_of(lambda: world.create_body(s, position=(math.nan, 0, 0))) == "position"
    assert field_of(lambda: world.create_body(12345)) == "shape"
    b = world.create_body(s)
    assert field_of(lambda: world.position(b + 1)) == "body"
    assert field_of(lambda: world.position(999)) == "body"
    assert field_of(lambda: world.set_mass(b, 0.0)) == "mass"
    assert field_of(lambda: world.set_friction(b, -1.0)) == "friction"
    assert field_of(lambda: world.body_at(10**6)) == "index"
    world.destroy_body(b)
    assert field_of(lambda: world.position(b)) == "body"
    assert field_of(lambda: world.create_joint("rope", 1)) == "joint.type"
    assert field_of(lambda: elan.World(substeps=0)) == "substeps"
    assert field_of(lambda: elan.World(timestep=0)) == "timestep"


def test_wrong_types_are_type_errors(world):
    with pytest.raises(TypeError):
        world.create_shape("sphere", radius="big")
    with pytest.raises(TypeError):
        world.position("body")
    with pytest.raises(TypeError):
        world.position(-1)
    with pytest.raises(TypeError):
        world.set_position(0, (1, 2))
    with pytest.raises(TypeError):
        elan.World(gravity=None)


JUNK = [None, -1, 0, 1, 2**40, 2**64 + 5, -(2**70), math.nan, math.inf, -0.0, 1e300, "x",
        (1, 2), (1, 2, 3), (1, 2, 3, 4), (math.nan,) * 3, (0, 0, 0, 0), np.zeros((2, 3)),
        np.zeros(0), [], {}, b"\x89ELANSNP"]


# NumPy warns when pybind11 takes the truth value of an empty array for a bool argument.
@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_no_crash_on_any_bad_input(world):
    """Every method with junk arguments: an exception or a result, never a crash."""
    s = world.create_shape("sphere", radius=0.5)
    b = world.create_body(s, position=(0, 3, 0))
    names = [n for n in dir(world) if not n.startswith("__") and callable(getattr(world, n))]
    names = [n for n in names if n not in ("step",)]
    calls = 0
    for name in names:
        method = getattr(world, name)
        for args in itertools.chain(
            ([j] for j in JUNK),
            ([b, j] for j in JUNK),
            ([s, j] for j in JUNK),
            ([j, j] for j in JUNK[:8]),
            ([b, j, j] for j in JUNK[:8]),
        ):
            try:
                method(*args)
            except (elan.Error, TypeError, ValueError, OverflowError):
                pass
            calls += 1
    world.step(2)  # still sound
    assert calls > 1000
    for j in JUNK:
        if isinstance(j, int) and j > 10:
            continue  # a valid request for many steps, not junk
        try:
            world.step(j)
        except (elan.Error, TypeError, ValueError, OverflowError):
            pass
    for text in ["", "{", "[]", "{\"bodies\": 3}", "{\"bodies\": [{}]}", "\x00", "{\"a\":" * 5000]:
        with pytest.raises(elan.Error):
            elan.World.from_scene_json(text)
