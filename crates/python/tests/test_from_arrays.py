"""carom.Simulation.from_arrays: the state read back is the arrays given, in the
user's order; a run equals the run of the equivalent configuration bit for bit;
a command's final snapshot fed back goes on conserving energy and momentum; bad
input raises ValueError naming the argument."""

from __future__ import annotations

import numpy as np
import pytest

import carom
from conftest import WALLED


def lattice(n_side: int, spacing: float, seed: int):
    """Discs on a square lattice with random velocities (an independent start)."""
    g = np.arange(n_side) * spacing + spacing / 2
    x, y = (a.ravel() for a in np.meshgrid(g, g))
    rng = np.random.default_rng(seed)
    vx, vy = rng.normal(size=(2, x.size))
    return x, y, vx, vy, n_side * spacing


def test_the_state_is_the_arrays_given_in_the_users_order():
    x, y, vx, vy, l = lattice(10, 1.5, 1)
    # Unsorted kinds: the engine groups them, the state must not.
    radius = np.where(np.arange(100) % 3 == 0, 0.6, 0.4)
    mass = np.where(np.arange(100) % 2 == 0, 1.0, 2.5)
    sim = carom.Simulation.from_arrays(x, y, vx, vy, box=(l, l), radius=radius, mass=mass)
    s = sim.state
    for k, v in (("x", x), ("y", y), ("vx", vx), ("vy", vy), ("radius", radius), ("mass", mass)):
        assert np.array_equal(s[k], v), k
    assert s["box"] == (l, l) and s["time"] == 0.0
    # Discs of one (radius, mass) share a species, numbered by first appearance.
    kinds = list(zip(radius, mass))
    first = {k: kinds.index(k) for k in kinds}
    order = sorted(first, key=first.get)
    assert s["species"].tolist() == [order.index(k) for k in kinds]
    # The run keeps the user's order: the momentum of each disc is its own.
    k0 = 0.5 * np.sum(mass * (vx ** 2 + vy ** 2))
    assert sim.kinetic_energy == pytest.approx(k0, rel=1e-14)
    sim.run(until=2.0)
    s = sim.state
    assert np.array_equal(s["radius"], radius) and np.array_equal(s["mass"], mass)
    k1 = 0.5 * np.sum(s["mass"] * (s["vx"] ** 2 + s["vy"] ** 2))
    assert k1 == pytest.approx(k0, rel=1e-12)


def test_species_indices_and_tables():
    x, y, vx, vy, l = lattice(6, 2.0, 2)
    species = np.arange(36) % 2
    sim = carom.Simulation.from_arrays(x, y, vx, vy, box=(l, l), species=species,
                                       species_radius=[0.5, 0.7], species_mass=[1.0, 2.0],
                                       boundaries="walls", seed=3)
    s = sim.state
    assert s["species"].tolist() == species.tolist()
    assert np.array_equal(s["radius"], np.where(species == 1, 0.7, 0.5))
    assert np.array_equal(s["x"], x)


def test_a_run_from_arrays_is_the_run_of_the_equivalent_configuration():
    x, y, vx, vy, l = lattice(8, 1.6, 3)
    collision = {"model": "normal", "coefficient": 0.9}
    sim = carom.Simulation.from_arrays(x, y, vx, vy, box=(l, 0.9 * l + 1), radius=0.5,
                                       boundaries={"x": "periodic", "y": "walls"},
                                       collision=collision)
    cfg = {
        "species": [{"count": 64, "radius": 0.5, "mass": 1.0}],
        "box": {"size": [l, 0.9 * l + 1], "boundary": {"x": "periodic", "y": "walls"}},
        "placement": {"explicit": np.stack([x, y], 1).tolist()},
        "velocities": {"explicit": np.stack([vx, vy], 1).tolist()},
        "collision": collision,
    }
    other = carom.Simulation(cfg)
    sim.run(until=3.0)
    other.run(until=3.0)
    assert sim.collisions == other.collisions > 0
    for k in ("x", "y", "vx", "vy", "image"):
        assert np.array_equal(sim.state[k], other.state[k]), k


def test_a_commands_final_snapshot_fed_back_goes_on_conserving(carom_run):
    log = carom.open_log(carom_run(WALLED))
    last = list(log.snapshots())[-1]
    sim = carom.Simulation.from_arrays(
        last["x"], last["y"], last["vx"], last["vy"], box=last["box"],
        radius=last["radius"], mass=last["mass"], boundaries="walls")
    for k in ("x", "y", "vx", "vy", "species", "radius", "mass"):
        assert np.array_equal(sim.state[k], last[k]), k
    # Elastic now (the configuration's rule is not passed): energy is conserved.
    k0 = sim.kinetic_energy
    sim.run(until=2.0)
    assert sim.collisions > 0
    assert sim.kinetic_energy == pytest.approx(k0, rel=1e-12)


def _inputs():
    x, y, vx, vy, l = lattice(4, 2.0, 4)
    return dict(x=x, y=y, vx=vx, vy=vy, box=(l, l))


@pytest.mark.parametrize("change,start", [
    (lambda a: a["x"].__setitem__(5, a["x"][4] + 0.3), "x, y: discs 4 and 5 overlap"),
    (lambda a: a.update(vx=a["vx"][:-1]), "vx: 15 values for 16 discs"),
    (lambda a: a.update(radius=np.r_[0.5, 0.5, -0.2, [0.5] * 13]), "radius[2]:"),
    (lambda a: a["y"].__setitem__(7, 100.0), "y[7]:"),
    (lambda a: a["x"].__setitem__(3, np.nan), "x[3] = NaN: not a finite number"),
    (lambda a: a.update(x=np.zeros((16, 2))), "x: an array of one number per disc"),
    (lambda a: a.update(species=[0] * 15 + [2], species_radius=[0.5, 0.4]), "species[15] = 2"),
    (lambda a: a.update(placement="lattice"), "placement: set by the arrays"),
    (lambda a: a.update(collision={"model": "normal", "coefficient": 2}), "collision.coefficient:"),
])
def test_bad_input_raises_value_error_naming_the_argument(change, start):
    a = _inputs()
    change(a)
    with pytest.raises(ValueError) as e:
        carom.Simulation.from_arrays(a.pop("x"), a.pop("y"), a.pop("vx"), a.pop("vy"), **a)
    assert str(e.value).startswith(start), str(e.value)


def test_an_overlap_names_the_users_discs_when_the_engine_regroups_them():
    a = _inputs()
    radius = np.array([0.5, 0.6] * 8)
    a["x"][5] = a["x"][4] + 0.3
    with pytest.raises(ValueError, match=r"^x, y: discs 4 and 5 overlap"):
        carom.Simulation.from_arrays(a.pop("x"), a.pop("y"), a.pop("vx"), a.pop("vy"),
                                     radius=radius, **a)
