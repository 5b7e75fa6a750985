# SPDX-License-Identifier: MIT
"""The body columns as one named tuple of zero-copy views."""

from typing import NamedTuple

import numpy as np


class BodyColumns(NamedTuple):
    """Read-only NumPy views of the engine's body columns, in dense index order (row i is
    ``World.body_ids()[i]``). Positions are the centres of mass (m), orientations the principal
    axes (unit quaternion w, x, y, z), velocities m/s and rad/s, world frame. The arrays' buffers
    are the engine's own memory: they show new values after every step without being fetched
    again, and are invalid after create_body, destroy_body or restore_snapshot."""

    px: np.ndarray
    py: np.ndarray
    pz: np.ndarray
    qw: np.ndarray
    qx: np.ndarray
    qy: np.ndarray
    qz: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    vz: np.ndarray
    wx: np.ndarray
    wy: np.ndarray
    wz: np.ndarray


def body_columns(self) -> BodyColumns:
    """Every body column as a zero-copy, read-only view (see BodyColumns)."""
    return BodyColumns(*self._body_columns())


def positions(self) -> np.ndarray:
    """A copy of the centres of mass as an (n, 3) float64 array, m, world (dense index order)."""
    return np.stack(self._body_columns()[0:3], axis=1).astype(np.float64)
