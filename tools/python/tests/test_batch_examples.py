# SPDX-License-Identifier: MIT
"""The examples in examples/python run, with quick settings: the energy plot writes a PNG, the
replay regression test passes, and the sweep prints its table."""

import subprocess
import sys

import pytest
from conftest import SOURCE_DIR

# The examples' dependencies (Debian: python3-distributed, python3-pandas, python3-matplotlib).
for module in ("distributed", "pandas", "matplotlib"):
    pytest.importorskip(module)

EXAMPLES = SOURCE_DIR / "examples" / "python"


def run(args, cwd):
    done = subprocess.run([sys.executable, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    return done


def test_plot_energy_writes_a_png(tmp_path):
    png = tmp_path / "energy.png"
    done = run([EXAMPLES / "plot_energy.py", SOURCE_DIR / "scenes" / "pyramid10.json", "--steps", "30",
                "--threads", "1", "--out", png], tmp_path)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "30 steps" in done.stdout


def test_replay_regression_example_passes(tmp_path):
    done = run(["-m", "pytest", "-q", "-p", "no:cacheprovider", EXAMPLES / "test_replay_regression.py"], tmp_path)
    assert "6 passed" in done.stdout


def test_sweep_on_a_local_cluster_prints_its_table(tmp_path):
    done = run([EXAMPLES / "sweep_local_cluster.py", "--workers", "2", "--steps", "20", "--out", tmp_path / "out"],
               tmp_path)
    assert "mean over the seeds" in done.stdout
    assert (tmp_path / "out" / "results.csv").is_file()
    lines = (tmp_path / "out" / "results.csv").read_text().splitlines()
    assert len(lines) == 1 + 24
