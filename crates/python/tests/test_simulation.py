"""carom.Simulation: the configuration's checks, the state's arrays, runs to a
time or a number of collisions, callbacks at exact times, Ctrl-C, and the
command's trajectory bit for bit."""

from __future__ import annotations

import json
import subprocess
import threading
import _thread

import numpy as np
import pytest

import carom
from conftest import FLUID, WALLED, config

BAD = [
    ({"species": [{"count": 10, "radius": -1}]}, "species.0.radius"),
    ({"species": [{"count": 10}], "packing_fraction": 0.4}, "packing_fraction"),
    ({"box": {"packing_fraction": 0.95}}, "box.packing_fraction"),
    ({"stop": {"duration": "long"}}, "stop.duration"),
]


@pytest.mark.parametrize("cfg,field", BAD)
def test_a_bad_configuration_raises_the_commands_message(cfg, field, carom_bin, tmp_path):
    with pytest.raises(ValueError) as e:
        carom.Simulation(cfg)
    msg = str(e.value)
    assert msg.startswith(field + ":"), msg
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(cfg))
    r = subprocess.run([carom_bin, "run", str(path), "--out", str(tmp_path / "b.mcap")],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert f"error: configuration: {msg}" in r.stderr


def test_the_state_is_numpy_arrays_in_the_users_order():
    sim = carom.Simulation(WALLED)
    s = sim.state
    n = 180
    assert len(sim) == n and sim.time == 0.0 and sim.collisions == 0
    for k in ("x", "y", "vx", "vy", "radius", "mass"):
        assert s[k].dtype == np.float64 and s[k].shape == (n,)
    assert s["image"].dtype == np.int32 and s["image"].shape == (n, 2)
    assert s["species"].tolist() == [0] * 120 + [1] * 60
    assert set(s["radius"][120:]) == {0.7} and set(s["mass"][120:]) == {2.0}
    k = 0.5 * np.sum(s["mass"] * (s["vx"] ** 2 + s["vy"] ** 2))
    assert k == pytest.approx(sim.kinetic_energy, rel=1e-12)
    lx, ly = s["box"]
    assert np.all((s["x"] >= 0) & (s["x"] <= lx) & (s["y"] >= 0) & (s["y"] <= ly))


def test_run_until_a_time_and_for_a_number_of_collisions():
    sim = carom.Simulation(FLUID)
    n = sim.run(until=0.5)
    assert sim.time == 0.5 and n == sim.collisions > 0
    assert sim.run(collisions=1000) == 1000
    assert sim.collisions == n + 1000
    assert sim.pair_collisions == sim.collisions and sim.wall_collisions == 0
    # Elastic: energy is conserved to rounding.
    assert sim.kinetic_energy == pytest.approx(carom.Simulation(FLUID).kinetic_energy, rel=1e-9)
    with pytest.raises(ValueError):
        sim.run(until=0.1)  # in the past
    with pytest.raises(ValueError):
        sim.run(until=1.0, collisions=5)


def test_callbacks_come_at_exact_times_with_the_state_then():
    sim = carom.Simulation(FLUID)
    seen = []
    sim.run(until=1.0, every=0.25, callback=lambda s: seen.append((s["time"], s["x"].copy())))
    assert [t for t, _ in seen] == [0.25, 0.5, 0.75, 1.0]
    # The state at 0.5 is the state a run straight to 0.5 ends in.
    other = carom.Simulation(FLUID)
    other.run(until=0.5)
    assert np.array_equal(seen[1][1], other.state["x"])
    with pytest.raises(ValueError):
        sim.run(until=2.0, every=0.5)


def test_a_callbacks_exception_stops_the_run_and_reaches_the_caller():
    sim = carom.Simulation(FLUID)

    def fail(state):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        sim.run(until=1.0, every=0.1, callback=fail)
    assert sim.time == pytest.approx(0.1)


def test_ctrl_c_raises_keyboard_interrupt_and_the_run_goes_on_unchanged():
    big = config(FLUID, species=[{"count": 2000}])
    sim = carom.Simulation(big)
    sim.run(until=0.2)
    # A SIGINT as the main thread runs (never before: the flag is raised once the
    # run has taken a slice's worth of events past the callback at 0.3).
    started = threading.Event()
    timer = threading.Thread(target=lambda: (started.wait(), _thread.interrupt_main()))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sim.run(until=1e6, every=0.3, callback=lambda s: started.set())
    timer.join()
    t_stop = sim.time
    assert 0.3 <= t_stop < 1e6
    # The state is consistent: going on to t = 2 gives what a straight run gives.
    target = max(2.0, t_stop + 1.0)
    sim.run(until=target)
    straight = carom.Simulation(big)
    straight.run(until=target)
    for k in ("x", "y", "vx", "vy"):
        assert np.array_equal(sim.state[k], straight.state[k])
    assert sim.collisions == straight.collisions


#: A dense fluid, which the engine runs on neighbour lists (η ≥ 0.66).
DENSE = {**FLUID, "species": [{"count": 400}], "box": {"packing_fraction": 0.7}}


@pytest.mark.parametrize("cfg", [FLUID, WALLED, DENSE], ids=["fluid", "walled", "dense"])
def test_a_python_run_ends_in_the_commands_final_state_bit_for_bit(cfg, carom_run):
    log = carom.open_log(carom_run(cfg))
    last = list(log.snapshots())[-1]
    sim = carom.Simulation(cfg)
    sim.run()  # to the configuration's stop
    assert last["time"] == sim.time == cfg["stop"]["duration"]
    s = sim.state
    for k in ("x", "y", "vx", "vy", "image", "species"):
        assert np.array_equal(s[k], last[k]), k
    assert sim.collisions == log.summary["pair_collisions"] + log.summary["wall_collisions"]


def test_the_neighbour_search_is_the_configurations():
    """Auto: lists for the dense fluid, cells at η = 0.4; `neighbours` forces either."""
    assert carom.Simulation(DENSE).neighbour_lists
    assert not carom.Simulation(FLUID).neighbour_lists
    assert not carom.Simulation({**DENSE, "neighbours": "cells"}).neighbour_lists
    assert carom.Simulation({**FLUID, "neighbours": "lists"}).neighbour_lists
    with pytest.raises(ValueError, match="neighbours"):
        carom.Simulation({**FLUID, "neighbours": "grid"})
