# SPDX-License-Identifier: MIT
"""Free fall and a bounce through the Python API, against closed forms.

The integrator is semi-implicit Euler on substeps of h = dt / substeps: from rest, after N
substeps v = g N h exactly (up to float rounding), and x = x0 + g h^2 N (N + 1) / 2, which is
the closed form g t^2 / 2 plus g h t / 2: a first-order error, at most g dt t / 2 for any
substep count. The tolerances below are those bounds, not fitted numbers.
"""

import math

import pytest

import elan

G = 9.81
DT = 1.0 / 60.0


def test_free_fall():
    w = elan.World(gravity=(0, -G, 0), threads=1)
    ball = w.create_body(w.create_shape("sphere", radius=0.5), position=(1, 100, -2))
    steps = 60
    w.step(steps)
    t = steps * DT
    vx, vy, vz = w.linear_velocity(ball)
    x, y, z = w.position(ball)
    # Float32 sums of 240 substep increments: relative rounding ~240 * 2^-24 < 1e-4.
    assert vy == pytest.approx(-G * t, rel=1e-4)
    assert (vx, vz) == (0.0, 0.0)
    assert (x, z) == (pytest.approx(1.0), pytest.approx(-2.0))
    exact = 100 - 0.5 * G * t * t
    bound = 0.5 * G * DT * t  # semi-implicit Euler's O(dt) error, see the module docstring
    assert abs(y - exact) <= bound + 1e-4
    # ... and the error is really first order, of the sign semi-implicit Euler gives (it falls
    # ahead of the exact curve): it cannot pass by being anywhere within a loose band.
    assert y < exact
    assert w.step_count == steps


def test_bounce_height_follows_restitution():
    e = 0.5
    h = 5.0  # m of free fall before the sphere touches the ground
    w = elan.World(gravity=(0, -G, 0), threads=1)
    ground = w.create_shape("box", half_extents=(10, 1, 10))
    w.create_body(ground, motion="static", position=(0, -1, 0), restitution=e)
    ball = w.create_body(
        w.create_shape("sphere", radius=0.5), position=(0, h + 0.5, 0), restitution=e
    )
    impact = 0.0
    apex = 0.0
    rising = False
    for _ in range(240):
        w.step()
        vy = w.linear_velocity(ball)[1]
        impact = max(impact, -vy)
        if vy > 0:
            rising = True
        if rising:
            apex = max(apex, w.position(ball)[1] - 0.5)
    v_exact = math.sqrt(2 * G * h)
    # The impact speed is sampled once a step: it is off by at most one step of gravity.
    assert impact == pytest.approx(v_exact, abs=G * DT)
    # Rebound apex e^2 h: the rebound speed e v carries the same one-step error e g dt, and
    # the apex (e v)^2 / (2 g) moves by e v * e g dt / g; plus the O(dt) position error of the
    # rise (g dt t / 2 with t = e v / g).
    t_rise = e * v_exact / G
    bound = e * v_exact * e * DT + 0.5 * G * DT * t_rise + 0.01
    assert apex == pytest.approx(e * e * h, abs=bound)
    assert apex > 0.5 * e * e * h  # it did bounce, well above resting


def test_bodies_come_to_rest_on_the_ground():
    w = elan.World(threads=1)
    w.create_body(w.create_shape("box", half_extents=(10, 1, 10)), motion="static",
                  position=(0, -1, 0))
    box = w.create_body(w.create_shape("box", half_extents=(0.5, 0.5, 0.5)), position=(0, 2, 0))
    w.step(300)
    assert w.position(box)[1] == pytest.approx(0.5, abs=0.02)  # resting on the ground's top
    assert w.kinetic_energy < 1e-3


def test_allow_sleep_can_be_switched_between_steps():
    # A box at rest sleeps after the sleep time (0.5 s) with sleeping on; switched off, every body
    # wakes and stays awake; back on, it sleeps again after the full time at rest.
    w = elan.World(threads=1)
    w.create_body(w.create_shape("box", half_extents=(10, 1, 10)), motion="static",
                  position=(0, -1, 0))
    box = w.create_body(w.create_shape("box", half_extents=(0.5, 0.5, 0.5)), position=(0, 0.5, 0))
    w.step(120)
    assert w.allow_sleep and not w.is_awake(box)
    w.allow_sleep = False
    assert not w.allow_sleep and w.is_awake(box)
    w.step(120)
    assert w.is_awake(box)
    w.allow_sleep = True
    w.step(120)
    assert not w.is_awake(box)
