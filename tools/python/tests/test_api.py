# SPDX-License-Identifier: MIT
"""The API beyond stepping: shapes, bodies, joints, queries and events, against known geometry."""

import math

import numpy as np
import pytest

import elan


@pytest.fixture
def floor_world():
    w = elan.World(threads=1)
    ground = w.create_body(
        w.create_shape("box", half_extents=(10, 1, 10)), motion="static", position=(0, -1, 0)
    )
    return w, ground


def test_ray_cast_hits_the_box_top(floor_world):
    w, ground = floor_world
    box = w.create_body(w.create_shape("box", half_extents=(0.5, 0.5, 0.5)), position=(2, 3, 0))
    hit = w.cast_ray((2, 10, 0), (0, -1, 0))
    assert hit["body"] == box
    assert hit["distance"] == pytest.approx(6.5, abs=1e-5)  # top face at y = 3.5
    assert hit["normal"] == pytest.approx((0, 1, 0), abs=1e-6)
    hits = w.cast_ray_all((2, 10, 0), (0, -1, 0))
    assert [h["body"] for h in hits] == [box, ground]
    assert w.cast_ray((2, 10, 0), (0, 1, 0)) is None
    assert w.cast_ray((2, 10, 0), (0, -1, 0), 1.0) is None


def test_batched_rays_match_single_rays(floor_world):
    w, ground = floor_world
    sphere = w.create_body(w.create_shape("sphere", radius=1.0), position=(0, 2, 0))
    xs = np.linspace(-3, 3, 61)
    origins = np.stack([xs, np.full_like(xs, 10), np.zeros_like(xs)], axis=1)
    directions = np.tile([0.0, -1.0, 0.0], (len(xs), 1))
    hits = w.cast_rays(origins, directions)
    assert hits.dtype.names == ("body", "distance", "point", "normal")
    assert hits.shape == (61,)
    for i, x in enumerate(xs):
        single = w.cast_ray(origins[i], directions[i])
        assert hits["body"][i] == single["body"]
        assert hits["distance"][i] == np.float32(single["distance"])
        if abs(x) < 0.99:
            assert hits["body"][i] == sphere
            # Sphere top: y = 2 + sqrt(1 - x^2).
            assert hits["distance"][i] == pytest.approx(8 - math.sqrt(1 - x * x), abs=1e-4)
        elif abs(x) > 1.01:
            assert hits["body"][i] == ground
    none = w.cast_rays(origins, -directions, 1.0)
    assert (none["body"] == -1).all() and np.isinf(none["distance"]).all()
    with pytest.raises(elan.Error) as e:
        w.cast_rays(origins, directions[:5])
    assert e.value.field == "directions"


def test_overlaps_and_closest_point(floor_world):
    w, ground = floor_world
    a = w.create_body(w.create_shape("sphere", radius=0.5), position=(0, 1, 0))
    b = w.create_body(w.create_shape("sphere", radius=0.5), position=(5, 1, 0))
    assert list(w.overlap_point((0, 1.2, 0))) == [a]
    assert set(w.overlap_box((-1, 0.5, -1), (1, 1.5, 1))) == {a}
    probe = w.create_shape("sphere", radius=0.25)
    assert list(w.overlap_shape(probe, (5, 1.6, 0))) == [b]
    p = w.closest_point((0, 3, 0), body=a)
    assert p["distance"] == pytest.approx(1.5, abs=1e-5)
    sweep = w.cast_shape(probe, (-3, 1, 0), translation=(6, 0, 0))
    assert sweep["body"] == a
    # Touches when the centres are 0.75 apart: at x = -0.75, fraction 2.25 / 6.
    assert sweep["fraction"] == pytest.approx(2.25 / 6, abs=1e-3)


def test_contact_events_as_structured_arrays(floor_world):
    w, ground = floor_world
    ball = w.create_body(w.create_shape("sphere", radius=0.5), position=(0, 0.6, 0))
    begun = None
    for _ in range(60):
        w.step()
        ev = w.contact_begin_events()
        if len(ev):
            begun = ev
            break
    assert begun is not None
    assert begun.dtype.names == ("body_a", "body_b", "point", "normal", "normal_impulse")
    assert {int(begun["body_a"][0]), int(begun["body_b"][0])} == {ball, ground}
    assert abs(begun["normal"][0][1]) == pytest.approx(1.0, abs=1e-3)
    assert w.contact_end_events().dtype.names == ("body_a", "body_b")
    assert len(w.contacts()) == 1


def test_hinge_joint_pendulum_keeps_its_length():
    w = elan.World(threads=1)
    bob = w.create_body(w.create_shape("sphere", radius=0.1), position=(1, 0, 0))
    j = w.create_joint("ball", bob, None, anchor=(0, 0, 0))
    assert w.joint_count == 1 and w.joint_type(j) == "ball"
    assert w.joint_bodies(j) == (bob, None)
    lowest = 0.0
    for _ in range(60):
        w.step()
        x, y, z = w.position(bob)
        assert math.sqrt(x * x + y * y + z * z) == pytest.approx(1.0, abs=0.01)
        lowest = min(lowest, y)
    assert lowest < -0.98  # released level, it swings through the bottom, 1 m below the pivot
    # The joint holds the bob against gravity and the centripetal pull: a force towards the pivot.
    assert w.joint_force(j) != (0.0, 0.0, 0.0)
    w.destroy_joint(j)
    assert not w.is_valid_joint(j)


def test_hinge_motor_turns():
    w = elan.World(gravity=(0, 0, 0), threads=1)
    wheel = w.create_body(w.create_shape("cylinder", radius=0.5, half_height=0.1))
    j = w.create_joint("hinge", wheel, anchor=(0, 0, 0), axis=(0, 1, 0), motor=(2.0, 100.0))
    w.step(30)
    assert w.angular_velocity(wheel)[1] == pytest.approx(2.0, rel=0.01)
    assert w.joint_coordinate(j) != 0.0


def test_setters_and_getters(floor_world):
    w, ground = floor_world
    s = w.create_shape("capsule", radius=0.2, half_height=0.4)
    b = w.create_body(s, position=(0, 5, 0), mass=3.0, friction=0.7, user_data=42)
    assert w.mass(b) == pytest.approx(3.0)
    assert w.friction(b) == pytest.approx(0.7)
    assert w.user_data(b) == 42
    assert w.shape(b) == s and w.shape_type(s) == "capsule"
    w.set_mass(b, 4.0)
    assert w.mass(b) == pytest.approx(4.0)
    w.set_position(b, (1, 6, 2))
    assert w.position(b) == pytest.approx((1, 6, 2))
    w.set_orientation(b, (0, 0, 1, 0))
    assert w.orientation(b) == pytest.approx((0, 0, 1, 0))
    w.set_linear_velocity(b, (1, 0, 0))
    w.apply_linear_impulse(b, (4, 0, 0))  # dv = J / m = 1
    assert w.linear_velocity(b) == pytest.approx((2, 0, 0))
    w.set_motion_type(b, "kinematic")
    assert w.motion_type(b) == "kinematic"
    w.gravity = (0, -1, 0)
    assert w.gravity == pytest.approx((0, -1, 0))
    w.substeps = 8
    assert w.substeps == 8
    w.broadphase = "tree"
    assert w.broadphase == "tree"
    hull = w.create_shape("convex_hull", points=[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    compound = w.create_shape(
        "compound",
        children=[
            {"type": "sphere", "radius": 0.3, "position": (0.5, 0, 0)},
            {"type": "box", "half_extents": (0.2, 0.2, 0.2), "position": (-0.5, 0, 0)},
        ],
    )
    mesh = w.create_shape(
        "mesh", vertices=[[0, 0, 0], [1, 0, 0], [0, 0, 1]], triangles=[[0, 1, 2]]
    )
    field = w.create_shape("heightfield", heights=np.zeros((3, 4)))
    for shape in (hull, compound):
        w.create_body(shape, position=(3, 3, 3))
    for shape in (mesh, field):
        w.create_body(shape, motion="static", position=(20, 0, 0))
    w.destroy_body(b)
    assert not w.is_valid(b)
    w.step(5)


def test_heightfield_hole_lets_a_ball_fall_through():
    # NaN heights are holes: the triangles at a hole's corners are gone. A ball over the hole
    # falls freely (y0 - g t^2 / 2, 0.4 % more from the substeps' Euler); one beside it rests.
    w = elan.World(threads=1)
    heights = np.zeros((10, 10))
    heights[4, 4] = np.nan
    field = w.create_body(
        w.create_shape("heightfield", heights=heights), motion="static", position=(0, 0, 0)
    )
    ball = w.create_shape("sphere", radius=0.1)
    over = w.create_body(ball, position=(3.6, 1, 3.7))
    beside = w.create_body(ball, position=(1.5, 1, 1.5))
    w.step(60)
    drop = 0.5 * 9.81 * (60 / 60) ** 2
    assert 1 - w.position(over)[1] == pytest.approx(drop, rel=0.01)
    assert w.position(beside)[1] == pytest.approx(0.1, abs=0.005)
    assert w.cast_ray((3.6, 5, 3.7), (0, -1, 0), 5.5) is None
    assert w.cast_ray((2.5, 5, 2.5), (0, -1, 0), 5.5)["body"] == field
