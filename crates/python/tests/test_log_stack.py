"""Log.snapshot_stack: the snapshots stacked into frames x N arrays, equal to
the frames one at a time, and refused with MemoryError when too large;
Log.thermo(frame=True) as a pandas DataFrame, and a clear ImportError without
pandas."""

from __future__ import annotations

import sys

import numpy as np
import pytest

import carom
from conftest import FLUID, WALLED


@pytest.mark.parametrize("cfg", [FLUID, WALLED], ids=["fluid", "walled"])
def test_the_stack_holds_the_snapshots(cfg, carom_run):
    log = carom.open_log(carom_run(cfg))
    snaps = list(log.snapshots(0.4, 1.5))
    s = log.snapshot_stack(0.4, 1.5)
    n = log.run["n_discs"]
    assert s["x"].shape == (len(snaps), n) and s["image"].shape == (len(snaps), n, 2)
    assert s["x"].dtype == np.float64 and s["image"].dtype == np.int32
    assert np.array_equal(s["time"], [f["time"] for f in snaps])
    for k, f in enumerate(snaps):
        for name in ("x", "y", "vx", "vy", "radius", "image"):
            assert np.array_equal(s[name][k], f[name]), (k, name)
        assert tuple(s["box"][k]) == tuple(f["box"])
    assert np.array_equal(s["species"], snaps[0]["species"])
    assert np.array_equal(s["mass"], snaps[0]["mass"])
    everything = log.snapshot_stack()
    assert len(everything["time"]) == len(list(log.snapshots()))


def test_a_stack_too_large_is_refused_with_the_numbers(carom_run):
    log = carom.open_log(carom_run(FLUID))
    frames, n = 4, 200                        # t = 0, 1, 2, 3
    per_frame = n * 48 + 24
    assert len(log.snapshot_stack(max_bytes=frames * per_frame)["time"]) == frames
    with pytest.raises(MemoryError) as e:
        log.snapshot_stack(max_bytes=frames * per_frame - 1)
    text = str(e.value)
    for part in ("4 frames", "200 discs", "48 bytes per disc", "max_bytes",
                 "at most 3 frames", "narrow t0 and t1"):
        assert part in text, (part, text)
    # A narrower window fits.
    assert len(log.snapshot_stack(1.0, 3.0, max_bytes=3 * per_frame)["time"]) == 3


def test_an_empty_window_stacks_no_frames(carom_run):
    s = carom.open_log(carom_run(FLUID)).snapshot_stack(10.0, 20.0)
    assert s["x"].shape == (0, 200) and s["time"].shape == (0,)


def test_thermo_as_a_dataframe_and_without_pandas(carom_run, monkeypatch):
    pandas = pytest.importorskip("pandas")
    log = carom.open_log(carom_run(FLUID))
    arrays = log.thermo()
    df = log.thermo(frame=True)
    assert isinstance(df, pandas.DataFrame)
    assert list(df.columns) == list(arrays)
    for k, v in arrays.items():
        assert np.array_equal(df[k].to_numpy(), v, equal_nan=v.dtype.kind == "f"), k
    monkeypatch.setitem(sys.modules, "pandas", None)   # import pandas now fails
    assert isinstance(log.thermo(), dict)
    with pytest.raises(ImportError, match="needs pandas"):
        log.thermo(frame=True)
