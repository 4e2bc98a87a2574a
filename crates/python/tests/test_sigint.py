"""A real SIGINT (os.kill) to a Python process running a simulation: the
process ends with KeyboardInterrupt; a logged run leaves a log that open_log
reads and `carom resume` continues to its end; an unlogged run leaves a
consistent state that runs on."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time


import numpy as np
import pytest

import carom

#: A fluid big enough that a run to t = 10⁵ takes far longer than the test.
CONFIG = {"species": [{"count": 3000}], "box": {"packing_fraction": 0.4}, "seed": 5,
          "log": {"snapshot_interval": 0.5, "checkpoint_interval": 1,
                  "flush_seconds": 0.1}}

LOGGED = f"""
import sys, carom
sim = carom.Simulation({CONFIG!r})
sim.run(until=1e5, log=sys.argv[1])
"""

#: Runs, prints its state at the interrupt (time, energy, momentum) to stdout,
#: then checks the state and runs on.
UNLOGGED = f"""
import sys, json
import numpy as np
import carom
sim = carom.Simulation({CONFIG!r})
k0 = sim.kinetic_energy
print("running", flush=True)
try:
    sim.run(until=1e5)
except KeyboardInterrupt:
    s = sim.state
    p = [float(np.sum(s["mass"] * s["vx"])), float(np.sum(s["mass"] * s["vy"]))]
    # No two discs overlap (minimum image in the periodic box).
    lx, ly = s["box"]
    x, y = s["x"], s["y"]
    close = 0
    for i in range(len(x)):
        dx = x[i + 1:] - x[i]; dx -= lx * np.round(dx / lx)
        dy = y[i + 1:] - y[i]; dy -= ly * np.round(dy / ly)
        close += int(np.sum(dx * dx + dy * dy < (1 - 1e-9) * (2 * 0.5) ** 2))
    t = sim.time
    n = sim.run(until=t + 0.5)
    print(json.dumps({{"time": t, "k0": k0, "k": sim.kinetic_energy, "p": p,
                       "overlaps": close, "more": n, "t_after": sim.time}}))
    raise
"""


def start(script: str, *args: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", script, *args], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def wait_for(cond, what: str, seconds: float = 120) -> None:
    end = time.monotonic() + seconds
    while not cond():
        assert time.monotonic() < end, f"timed out waiting for {what}"
        time.sleep(0.05)


def interrupt(p: subprocess.Popen) -> tuple[str, str]:
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    assert p.returncode != 0, (out, err)
    assert "KeyboardInterrupt" in err, err
    return out, err


def test_sigint_finishes_a_logged_run_that_resume_continues(carom_bin, tmp_path):
    path = tmp_path / "run.mcap"
    p = start(LOGGED, str(path))
    # The log exists and has grown past its first flushes.
    wait_for(lambda: path.exists() and path.stat().st_size > 200_000, "the log to grow")
    interrupt(p)
    log = carom.open_log(path)
    assert log.summary is not None and log.summary["stop_reason"] == "interrupted"
    snaps = list(log.snapshots())
    assert len(snaps) >= 2
    assert len(log.collisions()) > 0
    t_end = snaps[-1]["time"] + 1.0
    r = subprocess.run([carom_bin, "resume", str(path), "--until", str(t_end), "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    resumed = carom.open_log(path)
    assert resumed.summary["stop_reason"] != "interrupted"
    assert list(resumed.snapshots())[-1]["time"] == t_end
    report = carom.analyze(path, structure=False)
    assert report["log_complete"]


def test_sigint_leaves_an_unlogged_run_consistent():
    p = start(UNLOGGED)
    assert p.stdout.readline().strip() == "running"
    time.sleep(1.0)
    out, _ = interrupt(p)
    r = json.loads(out.strip().splitlines()[-1])
    assert r["time"] > 0
    assert r["k"] == pytest.approx(r["k0"], rel=1e-9)  # elastic: K conserved
    assert np.allclose(r["p"], 0.0, atol=1e-9 * 3000)
    assert r["overlaps"] == 0
    assert r["more"] > 0 and r["t_after"] == r["time"] + 0.5

