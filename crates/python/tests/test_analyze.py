"""carom.analyze: the dict of `carom analyze --json`, with its options."""

from __future__ import annotations

import json
import subprocess

import pytest

import carom
from conftest import FLUID, WALLED


@pytest.mark.parametrize("cfg", [FLUID, WALLED], ids=["fluid", "walled"])
def test_analyze_returns_the_commands_json(cfg, carom_run, carom_bin):
    path = carom_run(cfg)
    cmd = subprocess.run([carom_bin, "analyze", "--json", "--quiet", str(path)],
                         check=True, capture_output=True, text=True)
    assert carom.analyze(path) == json.loads(cmd.stdout)


def test_analyze_takes_the_commands_options(carom_run, carom_bin):
    path = carom_run(FLUID)
    cmd = subprocess.run([carom_bin, "analyze", "--json", "--quiet", "--equilibrate", "1",
                          "--bins", "20", "--no-structure", str(path)],
                         check=True, capture_output=True, text=True)
    got = carom.analyze(path, equilibrate=1.0, bins=20, structure=False)
    assert got == json.loads(cmd.stdout)
    assert got != carom.analyze(path)
    with pytest.raises(ValueError, match="bins"):
        carom.analyze(path, bins=3)
