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


def _mcap_collisions(path):
    """Every /collisions record of a full log, read with the independent `mcap`
    reader (no carom code), as a dict of lists in the schema's field names."""
    from mcap.reader import NonSeekingReader
    from mcap_ros2.decoder import DecoderFactory

    out: dict[str, list] = {}
    decoders: dict = {}
    with open(path, "rb") as f:
        for schema, channel, message in NonSeekingReader(f).iter_messages():
            if channel.topic != "/collisions":
                continue
            if channel.id not in decoders:
                decoders[channel.id] = DecoderFactory().decoder_for(
                    channel.message_encoding, schema)
            m = decoders[channel.id](message.data)
            n = len(m.time)
            out.setdefault("ordinal", []).extend(
                m.first_ordinal + k * m.stride for k in range(n))
            for name in ("time", "kind", "i", "j", "nx", "ny", "vix_before",
                         "viy_before", "vjx_before", "vjy_before", "vix_after",
                         "viy_after", "vjx_after", "vjy_after", "energy_lost",
                         "virial"):
                out.setdefault(name, []).extend(getattr(m, name))
    return out


@pytest.mark.parametrize("cfg", [FLUID, WALLED], ids=["fluid", "walled"])
def test_collisions_equal_the_mcap_readers_records(cfg, carom_run):
    """Every field of every record, bit for bit, against the mcap package's
    decoding of the same full log; a wall's impulse is -n * virial, a pair's
    (not stored in a full record) 0."""
    path = carom_run(cfg)
    c = carom.open_log(path).collisions()
    want = _mcap_collisions(path)
    assert len(c) == len(want["time"]) > 0
    for name, values in want.items():
        assert np.array_equal(c[name], np.array(values, dtype=c.dtype[name])), name
    walls = c["kind"] == 1
    assert np.array_equal(c["impulse_x"][walls], -c["nx"][walls] * c["virial"][walls])
    assert np.array_equal(c["impulse_y"][walls], -c["ny"][walls] * c["virial"][walls])
    assert not c["impulse_x"][~walls].any() and not c["impulse_y"][~walls].any()


def test_compact_collisions_carry_the_stored_impulses(carom_run):
    """A compact record stores the impulse Δp_i: the velocities change by it,
    v_i' = v_i + Δp_i/m_i (compared with the replayed velocities to rounding)."""
    cfg = config(WALLED, log=dict(WALLED["log"], collision_detail="compact"))
    log = carom.open_log(carom_run(cfg))
    c = log.collisions()
    m = next(log.snapshots())["mass"][c["i"]]
    assert np.allclose(c["vix_after"], c["vix_before"] + c["impulse_x"] / m,
                       rtol=0, atol=1e-12)
    assert np.allclose(c["viy_after"], c["viy_before"] + c["impulse_y"] / m,
                       rtol=0, atol=1e-12)
    assert np.abs(c["impulse_x"]).max() > 0


def test_collisions_in_an_empty_window_and_a_log_without_collisions(carom_run):
    log = carom.open_log(carom_run(FLUID))
    none = log.collisions(10.0, 20.0)
    assert none.dtype == carom.COLLISION_DTYPE and none.shape == (0,)
    quiet = carom.open_log(carom_run(config(FLUID, log=dict(FLUID["log"], collisions=False)),
                                     "quiet"))
    assert len(quiet.collisions()) == 0
