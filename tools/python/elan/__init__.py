# SPDX-License-Identifier: MIT
"""elan: a deterministic rigid-body physics engine.

The compiled core lives in ``elan._elan``; this package re-exports it. Units are SI throughout
(m, kg, s, rad, N). See docs/python.md.
"""

from elan._elan import (  # noqa: F401
    STEP_BAD_TIMESTEP,
    STEP_COLOR_OVERFLOW,
    STEP_FROZE_NON_FINITE,
    STEP_OK,
    Error,
    World,
)

from elan._columns import BodyColumns, body_columns, positions

World.body_columns = body_columns
World.positions = positions
del body_columns, positions

__all__ = [
    "BodyColumns",
    "Error",
    "World",
    "STEP_OK",
    "STEP_FROZE_NON_FINITE",
    "STEP_COLOR_OVERFLOW",
    "STEP_BAD_TIMESTEP",
]
