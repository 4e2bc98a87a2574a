"""sim.run(..., log=path): the command's log, continued by later logged runs,
read and analysed like the command's; Ctrl-C leaves a finished, resumable log."""

from __future__ import annotations

import os
import subprocess
import threading
import _thread

import numpy as np
import pytest

import carom
from conftest import FLUID, WALLED, config


@pytest.mark.parametrize("cfg", [FLUID, WALLED], ids=["fluid", "walled"])
def test_a_logged_run_writes_the_commands_log(cfg, carom_run, tmp_path):
    ours = tmp_path / "ours.mcap"
    sim = carom.Simulation(cfg)
    sim.run(log=ours)
    theirs = carom.open_log(carom_run(cfg))
    mine = carom.open_log(ours)
    assert np.array_equal(mine.collisions(), theirs.collisions())
    for a, b in zip(mine.snapshots(), theirs.snapshots(), strict=True):
        assert a["time"] == b["time"] and np.array_equal(a["x"], b["x"])
    assert mine.run["config"] == theirs.run["config"]
    # The report differs in the file's name only.
    ra, rb = carom.analyze(ours), carom.analyze(theirs.path)
    ra.pop("file"), rb.pop("file")
    assert ra == rb
    # The simulation holds the log's final state.
    last = list(mine.snapshots())[-1]
    assert sim.time == last["time"] and np.array_equal(sim.state["vx"], last["vx"])


def test_logged_runs_continue_their_log_and_the_trajectory(tmp_path):
    path = tmp_path / "run.mcap"
    sim = carom.Simulation(FLUID)
    sim.run(until=1.0, log=path)
    sim.run(until=2.0, log=path)  # carom resume, in place
    sim.run(until=3.0)  # in memory, from the log's final checkpoint
    straight = carom.Simulation(FLUID)
    straight.run(until=3.0)
    for k in ("x", "y", "vx", "vy", "image"):
        assert np.array_equal(sim.state[k], straight.state[k]), k
    log = carom.open_log(path)
    assert log.summary["sim_time"] == 2.0
    assert [s["time"] for s in log.snapshots()] == [0.0, 1.0, 2.0]
    # The log now ends behind the simulation: it cannot be continued.
    with pytest.raises(ValueError, match="log"):
        sim.run(until=4.0, log=tmp_path / "other.mcap")


def test_a_log_is_not_overwritten(tmp_path):
    path = tmp_path / "taken.mcap"
    path.write_bytes(b"not mine")
    with pytest.raises(FileExistsError):
        carom.Simulation(FLUID).run(log=path)
    assert path.read_bytes() == b"not mine"


def test_ctrl_c_leaves_a_finished_log_that_the_command_resumes(tmp_path, carom_bin):
    path = tmp_path / "cut.mcap"
    big = config(FLUID, species=[{"count": 3000}], stop={"duration": 1e5})
    sim = carom.Simulation(big)

    def interrupt_once_written():
        # The first checkpoint is written at the start: the run is under way.
        while not (path.exists() and path.stat().st_size > 0):
            threading.Event().wait(0.01)
        _thread.interrupt_main()

    t = threading.Thread(target=interrupt_once_written)
    t.start()
    with pytest.raises(KeyboardInterrupt):
        sim.run(log=path)
    t.join()
    log = carom.open_log(path)
    assert log.summary["stop_reason"] == "interrupted"
    assert 0 < sim.time < 1e5 and sim.time == log.summary["sim_time"]
    # `carom resume` continues it, as it would the command's own.
    target = sim.time + 0.5
    subprocess.run([carom_bin, "resume", str(path), "--until", str(target), "--quiet"],
                   check=True, capture_output=True)
    sim.run(until=target)
    # The command's continuation and the simulation's agree to the last bit.
    final = carom.open_log(path)
    assert final.summary["stop_reason"] == "time"
    assert final.summary["sim_time"] == target == sim.time
    th = final.thermo()
    assert th["time"][-1] == target
    assert th["collisions"][-1] == sim.collisions
    assert th["kinetic_energy"][-1] == sim.kinetic_energy
