"""carom.open_log: run facts, snapshots, /thermo and collisions as numpy arrays;
compact and full logs of one run give the same velocities."""

from __future__ import annotations

import numpy as np
import pytest

import carom
from conftest import FLUID, WALLED, config


def test_facts_snapshots_and_thermo(carom_run):
    log = carom.open_log(carom_run(WALLED))
    assert log.run["seed"] == 11 and log.run["n_discs"] == 180
    assert log.facts is not None
    assert log.summary["stop_reason"] == "time"
    snaps = list(log.snapshots())
    assert [s["time"] for s in snaps] == [0.0, 0.5, 1.0, 1.5, 2.0]
    assert [s["time"] for s in log.snapshots(0.4, 1.0)] == [0.5, 1.0]
    assert snaps[0]["x"].dtype == np.float64 and snaps[0]["x"].shape == (180,)
    th = log.thermo()
    assert th["time"].dtype == np.float64 and th["collisions"].dtype == np.int64
    assert th["collisions"][-1] == log.summary["pair_collisions"] + log.summary["wall_collisions"]
    assert np.all(np.diff(th["time"]) >= 0)


def test_collisions_as_a_structured_array(carom_run):
    log = carom.open_log(carom_run(WALLED))
    c = log.collisions()
    assert c.dtype == carom.COLLISION_DTYPE
    assert len(c) == log.summary["logged_collisions"]
    assert np.array_equal(c["ordinal"], np.arange(len(c)))
    assert np.all(np.diff(c["time"]) >= 0)
    walls = c["kind"] == 1
    assert walls.any() and (~walls).any()
    assert np.all(c["j"][walls] == 2**32 - 1)
    # A pair conserves momentum (equal masses within a species; m from the snapshot).
    m = next(log.snapshots())["mass"]
    p = c[~walls]
    mi, mj = m[p["i"]], m[p["j"]]
    before = mi * p["vix_before"] + mj * p["vjx_before"]
    after = mi * p["vix_after"] + mj * p["vjx_after"]
    assert np.allclose(before, after, rtol=0, atol=1e-12)
    window = log.collisions(0.5, 1.0)
    assert len(window) > 0 and window["time"].min() >= 0.5 and window["time"].max() <= 1.0
    assert np.array_equal(window, c[(c["time"] >= 0.5) & (c["time"] <= 1.0)])


@pytest.mark.parametrize("cfg", [FLUID, WALLED], ids=["fluid", "walled"])
def test_compact_and_full_logs_give_the_same_velocities(cfg, carom_run):
    full = carom.open_log(carom_run(cfg, "full")).collisions()
    compact_cfg = config(cfg, log=dict(cfg["log"], collision_detail="compact"))
    compact = carom.open_log(carom_run(compact_cfg, "compact")).collisions()
    assert len(full) == len(compact) > 0
    for k in ("ordinal", "kind", "time", "i", "j", "vix_before", "viy_before",
              "vjx_before", "vjy_before", "vix_after", "viy_after", "vjx_after",
              "vjy_after"):
        assert np.array_equal(full[k], compact[k]), k


def test_a_missing_file_raises_oserror(tmp_path):
    with pytest.raises(OSError):
        carom.open_log(tmp_path / "none.mcap")
