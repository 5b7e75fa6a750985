# SPDX-License-Identifier: MIT
"""Shared fixtures: the source tree (for scenes) and the elan command the tests compare with."""

import os
import pathlib
import shutil

import pytest

SOURCE_DIR = pathlib.Path(
    os.environ.get("ELAN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[3])
)


@pytest.fixture
def scenes():
    return SOURCE_DIR / "scenes"


@pytest.fixture
def elan_bin():
    path = os.environ.get("ELAN_BIN") or shutil.which("elan")
    if not path:
        pytest.skip("the elan command was not built (ELAN_BIN unset)")
    return path
