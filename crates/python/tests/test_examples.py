"""The examples in examples/python run as their docstrings say, on a small system,
and what they print is true: the figures exist and g(r) agrees with freud's."""

from __future__ import annotations

import re
import subprocess
import sys

from conftest import ROOT


def test_fluid_example_runs_and_agrees_with_freud(tmp_path):
    out = subprocess.run(
        [sys.executable, str(ROOT / "examples" / "python" / "fluid.py"),
         "--n", "400", "--duration", "6", "--out", str(tmp_path)],
        check=True, capture_output=True, text=True).stdout
    for png in ("speeds.png", "gr.png"):
        assert (tmp_path / png).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", png
    assert (tmp_path / "fluid.mcap").exists()
    ran = re.search(r"ran N = 400, η = 0.6: (\d+) collisions to t = 6\b", out)
    assert ran and int(ran.group(1)) > 0, out
    kt = float(re.search(r"kT = ([0-9.]+)", out).group(1))
    assert abs(kt - 1) < 0.05, out
    rms, worst = map(float, re.search(r"rms ([0-9.]+) σ, max \|Δ\| ([0-9.]+) σ", out).groups())
    # The same frames and bins: the two estimators differ far below carom's error.
    assert rms < 0.5 and worst < 2, out
