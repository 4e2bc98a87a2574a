"""carom.to_gsd_frame and carom.to_freud: a state as a HOOMD frame equal to the
one `carom export --format gsd` writes, and as freud's box and points."""

from __future__ import annotations

import subprocess

import numpy as np
import pytest

import carom
from conftest import FLUID, WALLED

gsd_hoomd = pytest.importorskip("gsd.hoomd")

#: The frame's arrays compared with the export's.
PARTICLES = ("N", "types", "typeid", "mass", "diameter", "position", "image", "velocity")


def _same_frame(a, b):
    assert a.configuration.step == b.configuration.step
    assert a.configuration.dimensions == b.configuration.dimensions == 2
    assert np.array_equal(a.configuration.box, b.configuration.box)
    for name in PARTICLES:
        x, y = getattr(a.particles, name), getattr(b.particles, name)
        if isinstance(x, np.ndarray):
            assert x.dtype == np.asarray(y).dtype, name
        assert np.array_equal(np.asarray(x), np.asarray(y)), name
    assert np.array_equal(a.log["carom/time"], b.log["carom/time"])


@pytest.mark.parametrize("cfg", [FLUID, WALLED], ids=["fluid", "walled"])
def test_frames_equal_the_exports(cfg, carom_run, carom_bin, tmp_path):
    path = carom_run(cfg)
    out = tmp_path / "export.gsd"
    subprocess.run([carom_bin, "export", str(path), "--format", "gsd", "--out", str(out),
                    "--quiet", "--force"], check=True, capture_output=True)
    log = carom.open_log(path)
    periodic = tuple(b == "periodic" for b in log.facts["box"]["boundary"])
    with gsd_hoomd.open(out, "r") as exported:
        snaps = list(log.snapshots())
        assert len(exported) == len(snaps) > 1
        for k, (s, e) in enumerate(zip(snaps, exported)):
            _same_frame(carom.to_gsd_frame(s, periodic=periodic, step=k), e)


def test_a_frame_written_with_gsd_reads_back_as_the_state(tmp_path):
    sim = carom.Simulation(FLUID)
    sim.run(until=0.5)
    s = sim.state
    path = tmp_path / "sim.gsd"
    with gsd_hoomd.open(path, "w") as f:
        f.append(carom.to_gsd_frame(s))
    with gsd_hoomd.open(path, "r") as f:
        back = f[0]
    lx, ly = s["box"]
    assert tuple(back.configuration.box[:2]) == (np.float32(lx), np.float32(ly))
    pos = back.particles.position.astype(np.float64)
    # float32 of x - L/2: the state to float32 rounding (within 1 ulp of L/2).
    tol = np.spacing(np.float32(max(lx, ly)))
    assert np.all(np.abs(pos[:, 0] + lx / 2 - s["x"]) <= tol)
    assert np.all(np.abs(pos[:, 1] + ly / 2 - s["y"]) <= tol)
    assert np.all(pos[:, 2] == 0)
    assert np.array_equal(back.particles.velocity[:, 0], s["vx"].astype(np.float32))
    assert np.array_equal(back.particles.image[:, :2], s["image"])
    assert np.array_equal(back.particles.diameter, (2 * s["radius"]).astype(np.float32))
    assert np.array_equal(back.particles.typeid, s["species"])
    assert back.log["carom/time"][0] == s["time"]


def test_freud_takes_the_box_and_points():
    freud = pytest.importorskip("freud")
    sim = carom.Simulation(FLUID)
    sim.run(until=1.0)
    s = sim.state
    box, points = carom.to_freud(s)
    assert isinstance(box, freud.box.Box) and box.is2D
    assert (box.Lx, box.Ly) == pytest.approx(tuple(s["box"]), rel=1e-7)
    assert points.shape == (len(s["x"]), 3) and points.dtype == np.float64
    assert np.all(points[:, 2] == 0)
    # Inside freud's box, and back to carom's positions.
    assert np.all(np.abs(points[:, :2]) <= np.array(s["box"]) / 2)
    assert np.allclose(points[:, 0] + s["box"][0] / 2, s["x"], rtol=0, atol=1e-12)
    assert np.allclose(points[:, 1] + s["box"][1] / 2, s["y"], rtol=0, atol=1e-12)
    # freud wraps nothing: its own wrap leaves the points where they are.
    assert np.allclose(box.wrap(points), points, rtol=0, atol=1e-5)
    rdf = freud.density.RDF(bins=20, r_max=4.0).compute((box, points))
    assert rdf.bin_counts.sum() > 0
    # No disc overlaps: no pair closer than the contact distance 2a = 1.
    assert rdf.bin_counts[rdf.bin_edges[1:] <= 0.999].sum() == 0


def test_without_freud_the_box_is_a_tuple(monkeypatch):
    import sys
    monkeypatch.setitem(sys.modules, "freud", None)
    state = {"box": (10.0, 8.0), "x": np.array([0.0, 9.5]), "y": np.array([4.0, 0.0])}
    box, points = carom.to_freud(state)
    assert box == (10.0, 8.0, 0.0, 0.0, 0.0, 0.0)
    assert np.array_equal(points, [[-5.0, 0.0, 0.0], [4.5, -4.0, 0.0]])
