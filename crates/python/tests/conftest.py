"""Shared fixtures: the `carom` command (to compare the package with it) and
small configurations that run in well under a second.

The command is `$CAROM_BIN` (tests/integration/python.rs sets it to the binary
it was built with), else target/release/carom of this repository; a test that
needs it and finds neither is skipped, or fails when CI is set."""

from __future__ import annotations

import copy
import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]

#: A periodic fluid of 200 discs at η = 0.4, snapshots every time unit.
FLUID = {
    "species": [{"count": 200}],
    "box": {"packing_fraction": 0.4},
    "seed": 7,
    "stop": {"duration": 3},
    "log": {"snapshot_interval": 1, "collision_detail": "full"},
}

#: A walled binary mixture, inelastic: wall collisions and two species.
WALLED = {
    "species": [{"count": 120}, {"count": 60, "radius": 0.7, "mass": 2.0}],
    "box": {"packing_fraction": 0.35, "boundary": "walls"},
    "collision": {"model": "normal", "coefficient": 0.95},
    "seed": 11,
    "stop": {"duration": 2},
    "log": {"snapshot_interval": 0.5, "collision_detail": "full"},
}


def config(base: dict, **changes) -> dict:
    """A deep copy of `base` with top-level fields replaced."""
    c = copy.deepcopy(base)
    c.update(changes)
    return c


@pytest.fixture(scope="session")
def carom_bin() -> str:
    exe = os.environ.get("CAROM_BIN") or str(ROOT / "target" / "release" / "carom")
    if not os.path.exists(exe):
        if os.environ.get("CI"):
            pytest.fail(f"the carom command is missing ({exe}); build it first")
        pytest.skip(f"the carom command is missing ({exe})")
    return exe


@pytest.fixture
def carom_run(carom_bin, tmp_path):
    """Run `carom run` on a configuration dict; returns the log's path."""

    def run(cfg: dict, name: str = "run") -> pathlib.Path:
        cfg_path = tmp_path / f"{name}.json"
        cfg_path.write_text(json.dumps(cfg))
        out = tmp_path / f"{name}.mcap"
        subprocess.run([carom_bin, "run", str(cfg_path), "--out", str(out), "--quiet",
                        "--force"], check=True, capture_output=True)
        return out

    return run
