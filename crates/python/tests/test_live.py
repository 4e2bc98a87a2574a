"""sim.run(..., live=...): a simulation served live as `carom run --live` serves
a run. A client of Foxglove's own WebSocket library (tests/node/live.mjs:
@foxglove/ws-protocol, protobufjs for foxglove.SceneUpdate) watches runs of a
simulation, and what it gets is exact: each /scene frame holds the positions a
second simulation of the same configuration has when run to that frame's time,
bit for bit, and each /thermo record is one a log of the run holds, field for
field. The server outlives each run (the client stays connected across runs) and
closes with stop_live() or with the simulation. Skips without node and
tests/node's modules; fails instead when CI is set."""

from __future__ import annotations

import gc
import json
import os
import shutil
import socket
import subprocess
import threading
import time
import _thread

import numpy as np
import pytest

import carom

from conftest import ROOT

NODE_DIR = ROOT / "tests" / "node"

#: A periodic fluid of 400 discs at η = 0.5, /thermo every 50 time units.
FLUID = {
    "species": [{"count": 400, "radius": 0.5, "mass": 1.0}],
    "box": {"packing_fraction": 0.5, "aspect": 1.0, "boundary": "periodic"},
    "temperature": 1.0,
    "seed": 54,
    "stop": {"duration": 1_000_000},
    "log": {"collisions": False, "snapshot_interval": 1000, "thermo_interval": 50,
            "checkpoint_interval": 1000},
}

#: Frames the client takes before it disconnects and comes back.
FRAMES = 25


@pytest.fixture
def node() -> str:
    """The node executable, with tests/node's modules installed."""
    how = "install node and npm, then `npm ci --prefix tests/node`"
    exe = shutil.which("node")
    problem = None
    if exe is None:
        problem = "node is not installed"
    elif not (NODE_DIR / "node_modules" / "@foxglove" / "ws-protocol").exists():
        problem = "tests/node/node_modules has no @foxglove/ws-protocol"
    if problem:
        if os.environ.get("CI"):
            pytest.fail(f"{problem}: {how}")
        pytest.skip(f"{problem}: {how}")
    return exe


def watch(node: str, url: str) -> subprocess.Popen:
    """`node live.mjs URL watch FRAMES`: its JSON comes out when the server closes."""
    return subprocess.Popen(
        [node, str(NODE_DIR / "live.mjs"), url, "watch", str(FRAMES)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def run_a_while(sim: carom.Simulation, seconds: float, **run) -> None:
    """Run `sim` in runs of 200 time units for `seconds` of wall time: the client
    stays connected from one run to the next."""
    t0 = time.monotonic()
    while time.monotonic() - t0 < seconds:
        sim.run(until=sim.time + 200.0, **run)


def what_it_saw(client: subprocess.Popen) -> dict:
    """The client's output, once the server has closed its connection."""
    out, err = client.communicate(timeout=60)
    assert client.returncode == 0, f"live.mjs: {client.returncode}\n{err}"
    return json.loads(out)


def assert_exact_frames(got: dict) -> None:
    """Each frame's positions are, bit for bit, those of a simulation of the same
    configuration run to the frame's time."""
    frames = got["frames"] + got["again"]["frames"]
    assert len(got["frames"]) == FRAMES
    assert got["stamps_ok"], "a frame's log time is not its time"
    times = [f["time"] for f in frames]
    assert times == sorted(times), "frames out of order"
    ref = carom.Simulation(FLUID)
    for f in frames:
        if f["time"] > ref.time:
            ref.run(until=f["time"])
        s = ref.state
        np.testing.assert_array_equal(np.array(f["x"]), s["x"], err_msg=f"x at {f['time']}")
        np.testing.assert_array_equal(np.array(f["y"]), s["y"], err_msg=f"y at {f['time']}")
    # The frames are not all of one state.
    assert len(set(times)) > FRAMES // 2


def assert_records_in_log(records: list[dict], log_path) -> int:
    """Each record equals the log's record at its (time, collisions), field for
    field; returns how many records there were."""
    th = carom.open_log(str(log_path)).thermo()
    for r in records:
        at = np.flatnonzero((th["time"] == r["time"]) & (th["collisions"] == r["collisions"]))
        assert len(at) >= 1, f"no record of the log at time {r['time']}"
        i = at[0]
        for k, v in r.items():
            assert th[k][i] == v, f"/thermo {k} at time {r['time']}: {v} live, {th[k][i]} logged"
    return len(records)


def test_a_client_sees_exact_states_and_the_logs_records_across_runs(node, tmp_path):
    sim = carom.Simulation(FLUID)
    url = sim.start_live(0, rate=40)
    assert sim.live_url == url and url.startswith("ws://127.0.0.1:")
    client = watch(node, url)
    run_a_while(sim, 5.0)
    # Every run has ended; the client is still connected, and the server still up.
    assert client.poll() is None, "the client was dropped between runs"
    assert sim.live_url == url
    end = sim.time
    sim.stop_live()
    assert sim.live_url is None
    got = what_it_saw(client)

    assert got["channels"]["/scene"]["schemaName"] == "foxglove.SceneUpdate"
    assert got["channels"]["/thermo"]["schemaName"] == "carom.Thermo"
    assert got["channels"]["/progress"]["schemaName"] == "carom.Progress"
    assert got["progress"], "no /progress record"
    assert_exact_frames(got)

    # The /thermo records are carom-run's: the log of the same configuration run
    # to the same end holds each record sent, at t0 + k·Δ and at the end of each
    # run (every 200 time units, on the series).
    log = tmp_path / "ref.mcap"
    carom.Simulation(FLUID).run(until=end, log=str(log))
    assert assert_records_in_log(got["thermo"], log) >= 3


def test_a_logged_run_serves_the_logs_own_records(node, tmp_path):
    sim = carom.Simulation(FLUID)
    url = sim.start_live(0, rate=40)
    client = watch(node, url)
    log = tmp_path / "run.mcap"
    run_a_while(sim, 5.0, log=str(log))
    assert client.poll() is None, "the client was dropped between runs"
    sim.stop_live()
    got = what_it_saw(client)
    assert_exact_frames(got)
    # Every record sent, the run-end records of each run included, is the log's.
    assert assert_records_in_log(got["thermo"], log) >= 3


def refused(url: str) -> bool:
    """Whether nothing listens at `url` any more."""
    host, port = url.removeprefix("ws://").rsplit(":", 1)
    with socket.socket() as s:
        return s.connect_ex((host, int(port))) != 0


def closes(url: str, within: float = 5.0) -> bool:
    """Whether `url` stops listening within `within` seconds: the server's tasks
    have ended when `stop_live` returns, but on a loaded machine its runtime drops
    the listening socket a moment later (seen once in a full test run)."""
    end = time.monotonic() + within
    while not refused(url):
        if time.monotonic() > end:
            return False
        time.sleep(0.01)
    return True


def test_the_server_stays_up_across_runs_and_closes_with_the_simulation():
    sim = carom.Simulation(FLUID)
    assert sim.live_url is None
    sim.run(until=1.0, live=0)
    url = sim.live_url
    assert url is not None and not refused(url)
    # Later runs keep it: without live, with live=False, and asking for it again.
    sim.run(until=2.0)
    sim.run(until=3.0, live=False)
    sim.run(until=4.0, live=int(url.rsplit(":", 1)[1]))
    assert sim.live_url == url
    sim.stop_live()
    assert sim.live_url is None and closes(url)
    sim.stop_live()  # nothing to stop

    other = carom.Simulation(FLUID)
    url = other.start_live(0)
    del other
    gc.collect()
    assert closes(url)


def test_ctrl_c_during_a_served_run_keeps_the_server_and_the_state():
    sim = carom.Simulation(FLUID)
    url = sim.start_live(0)
    threading.Timer(0.5, _thread.interrupt_main).start()
    with pytest.raises(KeyboardInterrupt):
        sim.run(until=1e9)
    t, energy = sim.time, sim.kinetic_energy
    assert 0 < t < 1e9
    assert sim.live_url == url and not refused(url)
    sim.run(until=t + 1.0)
    assert sim.time == t + 1.0
    assert sim.kinetic_energy == pytest.approx(energy, rel=1e-12)
    sim.stop_live()
    assert closes(url)


def test_a_served_run_and_live_false_leave_the_trajectory_alone():
    plain = carom.Simulation(FLUID)
    plain.run(until=300.0)
    served = carom.Simulation(FLUID)
    served.run(until=100.0, live=0, live_rate=1000)
    served.run(until=200.0, live=False)
    served.run(until=300.0)
    served.stop_live()
    for k in ("x", "y", "vx", "vy", "image"):
        np.testing.assert_array_equal(served.state[k], plain.state[k], err_msg=k)
    assert served.collisions == plain.collisions


def test_bad_live_arguments_name_live_and_say_what_is_allowed():
    sim = carom.Simulation(FLUID)
    with pytest.raises(ValueError, match=r"live address \"nowhere:x\".*HOST:PORT"):
        sim.run(until=1.0, live="nowhere:x")
    with pytest.raises(ValueError, match="live = 70000: a port is 0 to 65535"):
        sim.run(until=1.0, live=70000)
    with pytest.raises(TypeError, match="live: give True"):
        sim.run(until=1.0, live=1.5)
    with pytest.raises(ValueError, match="live_rate: goes with live"):
        sim.run(until=1.0, live_rate=5)
    with pytest.raises(ValueError, match="live frame rate -1"):
        sim.run(until=1.0, live=0, live_rate=-1)
    assert sim.live_url is None
    # An address in use is an OSError naming live.
    url = sim.start_live(0)
    port = int(url.rsplit(":", 1)[1])
    other = carom.Simulation(FLUID)
    with pytest.raises(OSError, match=f"live address 127.0.0.1:{port}: cannot serve there"):
        other.run(until=1.0, live=port)
    # One server per simulation: another address needs stop_live() first.
    with pytest.raises(ValueError, match="serves ws://.* already.*stop_live"):
        sim.run(until=1.0, live=port + 1 if port < 65535 else port - 1)
    sim.stop_live()
    assert sim.time == 0.0 and other.time == 0.0
