"""The observables of plain arrays (carom.pair_correlation, psi6, structure_factor,
msd): against freud on a carom fluid's frames, against carom.analyze on the same
log, against a trajectory whose MSD is known, and their errors for bad input."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

import carom
from carom.observables import _arrays

freud = pytest.importorskip("freud")

#: A periodic fluid of 1600 discs at η = 0.65, snapshots every time unit.
DENSE = {
    "species": [{"count": 1600}],
    "box": {"packing_fraction": 0.65},
    "seed": 5,
    "stop": {"duration": 20},
    "log": {"snapshot_interval": 1, "collision_detail": "compact"},
}


@pytest.fixture(scope="module")
def dense_log(carom_bin, tmp_path_factory):
    """The log of DENSE and its snapshots (the last 10, equilibrated a little)."""
    d = tmp_path_factory.mktemp("dense")
    (d / "dense.json").write_text(json.dumps(DENSE))
    path = d / "dense.mcap"
    subprocess.run([carom_bin, "run", str(d / "dense.json"), "--out", str(path),
                    "--quiet", "--force"], check=True, capture_output=True)
    return path, list(carom.open_log(path).snapshots(10.0))


def _freud_frame(s):
    """A state's box and points as freud takes them (centred box, z = 0)."""
    lx, ly = s["box"]
    box = freud.box.Box.from_box([lx, ly])
    pts = np.column_stack([s["x"] - lx / 2, s["y"] - ly / 2, np.zeros_like(s["x"])])
    return box, box.wrap(pts)


def _float32_exact(s):
    """The frame of state `s` dilated into a 64 × 64 box and put on a grid of
    2⁻¹⁶ (moves of < 10⁻⁵ σ): freud works in float32, and on these points every
    difference and wrap it makes is exact, so only its float32 sums and weights
    differ from carom's float64. ψ6 does not change under a dilation."""
    q, side = 2.0**16, 64.0
    x, y = (np.round(s[a] * (side / s["box"][k]) * q) / q % side
            for k, a in enumerate("xy"))
    box = freud.box.Box.from_box([side, side])
    return x, y, (side, side), (box, box.wrap(np.column_stack([x, y, np.zeros_like(x)])))


def test_voronoi_psi6_agrees_with_freud(dense_log):
    """Eq. 11.1 is freud's Hexatic(k=6, weighted=True) on Voronoi neighbours (the
    Minkowski structure metric): weights the Voronoi edge lengths, normalised by
    their sum, e^{+6iθ} in both: to 1e-6 on float32-exact points, to float32
    rounding (the points' last bits, ~√N amplified) on the frames as they are."""
    for s in dense_log[1][::3]:
        x, y, side, system = _float32_exact(s)
        voronoi = freud.locality.Voronoi().compute(system)
        hexatic = freud.order.Hexatic(k=6, weighted=True)
        hexatic.compute(system, neighbors=voronoi.nlist)
        ours = carom.psi6(x, y, box=side)
        assert ours.dtype == np.complex128 and ours.shape == (len(x),)
        assert 0.3 < np.mean(np.abs(ours)) < 0.95  # a dense liquid, not a trivial case
        np.testing.assert_allclose(np.abs(ours), np.abs(hexatic.particle_order),
                                   rtol=0, atol=1e-6)
        np.testing.assert_allclose(ours, hexatic.particle_order, rtol=0, atol=1e-6)
        raw = _freud_frame(s)
        hexatic.compute(raw, neighbors=freud.locality.Voronoi().compute(raw).nlist)
        np.testing.assert_allclose(carom.psi6(s), hexatic.particle_order, rtol=0,
                                   atol=1e-4)


def test_equal_weight_and_nearest_psi6_agree_with_freud(dense_log):
    """Eq. 11.7 is the unweighted Hexatic on Voronoi neighbours, eq. 11.8 the
    unweighted one on the six nearest (freud's k-nearest query)."""
    x, y, side, system = _float32_exact(dense_log[1][-1])
    voronoi = freud.locality.Voronoi().compute(system)
    equal = freud.order.Hexatic(k=6).compute(system, neighbors=voronoi.nlist)
    np.testing.assert_allclose(carom.psi6(x, y, box=side, estimator="delaunay"),
                               equal.particle_order, rtol=0, atol=1e-6)
    nearest = freud.order.Hexatic(k=6).compute(
        system, neighbors={"num_neighbors": 6, "exclude_ii": True})
    np.testing.assert_allclose(carom.psi6(x, y, box=side, estimator="nearest", k=6),
                               nearest.particle_order, rtol=0, atol=1e-6)


def test_pair_correlation_agrees_with_freud(dense_log):
    """g(r) on carom's bins against freud's RDF with the same edges; carom
    normalises by the N(N−1)/2 distinct pairs (10.1), freud's 'finite_size'
    mode the same way. freud's float32 distances put a few pairs near a bin
    edge into the next bin, so the two agree within the bin error, not to
    rounding."""
    states = dense_log[1]
    g = carom.pair_correlation(states)
    pair = g["pairs"][0]
    nbins = len(g["r"])
    assert g["snapshots"] == len(states) and nbins > 100
    rdf = freud.density.RDF(bins=nbins, r_max=g["r_max"], normalization_mode="finite_size")
    for s in states:
        rdf.compute(_freud_frame(s), reset=False)
    np.testing.assert_allclose(rdf.bin_centers, g["r"], rtol=1e-6)  # freud: float32
    err = pair["std_error"]
    assert np.all(np.isfinite(err)) and np.all(err[pair["g"] > 0] > 0)
    assert np.all(np.abs(pair["g"] - rdf.rdf) <= err + 1e-12)
    # Contact at σ = 1: g jumps from 0 to its peak.
    assert np.all(pair["g"][g["r"] < 1.0] == 0) and pair["g"][g["r"] > 1.0][0] > 3
    assert pair["contact"]["value"] > 3 and pair["contact"]["std_error"] > 0


def _same(a, b, path=""):
    """Equal, bit for bit (NaN equal to NaN), through dicts, lists and arrays."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and a.keys() == b.keys(), path
        for k in a:
            _same(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), path
        for k, (u, v) in enumerate(zip(a, b)):
            _same(u, v, f"{path}[{k}]")
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and np.array_equal(a, b, equal_nan=a.dtype.kind == "f"), path
    elif isinstance(a, float) and np.isnan(a):
        assert isinstance(b, float) and np.isnan(b), path
    else:
        assert a == b, path


def test_arrays_give_the_sections_of_analyze(dense_log):
    """The log's snapshots as arrays, over the report's window, give its
    structure sections bit for bit (the contact theorem aside: it needs the
    log's pressure), and its dynamics section to rounding (analyze unwraps by
    accumulating steps, the arrays as r + n L)."""
    path, _ = dense_log
    report = carom.analyze(path)
    window = (report["window"]["equilibrate"], report["window"]["t_end"])
    states = list(carom.open_log(path).snapshots())
    got = carom.structure(states, window=window)
    expected = _arrays(report)
    expected["pair_correlation"]["contact_theorem"] = None
    for section in ("pair_correlation", "bond_order", "orientational_correlation",
                    "structure_factor"):
        assert got[section] is not None, section
        _same(got[section], expected[section], section)
    pc = got["pair_correlation"]["pairs"][0]["contact"]["value"]
    assert pc == report["pair_correlation"]["pairs"][0]["contact"]["value"]
    assert got["bond_order"]["global"] == report["bond_order"]["global"]
    assert got["structure_factor"]["peak_s"] == report["structure_factor"]["peak_s"]
    # The same through the arrays, not the state dicts.
    xs = np.stack([s["x"] for s in states])
    ys = np.stack([s["y"] for s in states])
    times = [s["time"] for s in states]
    g = carom.pair_correlation(xs, ys, box=states[0]["box"], times=times, window=window)
    _same(g, got["pair_correlation"])
    dyn = carom.msd(states, window=window, snapshot_interval=1.0,
                    collision_rate=report["collision_rate"]["per_disc"])
    ours, theirs = dyn["species"][0], expected["dynamics"]["species"][0]
    np.testing.assert_array_equal(ours["lag"], theirs["lag"])
    np.testing.assert_allclose(ours["msd"], theirs["msd"], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(ours["vacf"], theirs["vacf"], rtol=1e-12)
    assert ours["diffusion"]["d"] == pytest.approx(theirs["diffusion"]["d"], rel=1e-9)


def test_msd_of_free_flight_is_v_squared_t_squared():
    """Straight flights u = u0 + v t (arrays built by hand, no collisions):
    MSD(τ) = ⟨v²⟩ τ² at every lag of both species, α₂ that of the speeds, and
    C(τ) = ⟨v²⟩ constant (physics.md 13.1, 13.3)."""
    rng = np.random.default_rng(3)
    n, lx = 300, 60.0
    species = np.repeat([0, 1], [200, 100])
    u0 = rng.uniform(0, lx, (2, n))
    v = rng.normal(0, 1, (2, n)) / np.where(species == 1, 2.0, 1.0)
    t = np.arange(41) * 0.25
    x, y = (u0[k] + v[k] * t[:, np.newaxis] for k in range(2))
    vx, vy = (np.broadcast_to(v[k], x.shape) for k in range(2))
    d = carom.msd(x, y, vx, vy, times=t, box=(lx, lx), species=species,
                  radius=[0.5, 0.7], mass=[1.0, 4.0])
    assert [s["count"] for s in d["species"]] == [200, 100]
    for s in d["species"]:
        sel = species == s["species"]
        v2 = np.mean(v[0, sel] ** 2 + v[1, sel] ** 2)
        assert len(s["lag"]) > 10 and s["lag"][0] == 0
        np.testing.assert_allclose(s["msd"], v2 * s["lag"] ** 2, rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(s["vacf"], v2, rtol=1e-12)
        v4 = np.mean((v[0, sel] ** 2 + v[1, sel] ** 2) ** 2)
        np.testing.assert_allclose(s["alpha2"][1:], v4 / (2 * v2**2) - 1, rtol=1e-9)


def test_psi6_of_a_triangular_lattice_is_one():
    """Every disc of a perfect triangular lattice with a bond along x has
    ψ6 = 1 by every estimator (11.1, 11.7, 11.8)."""
    a, nx, ny = 1.1, 12, 14
    i, j = np.meshgrid(np.arange(nx), np.arange(ny))
    x = ((i + 0.5 * (j % 2)) * a).ravel()
    y = (j * a * np.sqrt(3) / 2).ravel()
    box = (nx * a, ny * a * np.sqrt(3) / 2)
    for estimator in carom.observables.ESTIMATORS:
        np.testing.assert_allclose(carom.psi6(x, y, box=box, estimator=estimator), 1,
                                   atol=1e-12)
    # Turned by α: every ψ6 turns by 6α (freud's e^{+6iθ} convention).
    # Discs away from the hull of a patch in a walled box (the hull's bonds need
    # not lie along the lattice).
    c, s = np.cos(0.1), np.sin(0.1)
    xr, yr = 10 + c * x - s * y, 2 + s * x + c * y
    psi = carom.psi6(xr, yr, box=(30.0, 30.0), boundaries="walls")
    inner = (x > 2) & (x < nx * a - 2) & (y > 2) & (y < box[1] - 2)
    assert inner.sum() > 50
    np.testing.assert_allclose(psi[inner], np.exp(0.6j), atol=1e-12)


X = np.linspace(0.5, 9.5, 20)
Y = np.tile([1.0, 3.0, 5.0, 7.0], 5)


@pytest.mark.parametrize("call, name", [
    (lambda: carom.pair_correlation(X, Y[:-1], box=(10, 10)), "y"),
    (lambda: carom.pair_correlation(X, Y, box=(10, 10), species=[0] * 19 + [2],
                                    radius=[0.5, 0.4]), "species"),
    (lambda: carom.pair_correlation(X, Y, box=(10, 10), species=[0] * 19), "species"),
    (lambda: carom.pair_correlation(X, Y, box=(0.8, 10)), "box"),
    (lambda: carom.pair_correlation(X, Y, box=(10, -1)), "box"),
    (lambda: carom.pair_correlation(X, Y), "box"),
    (lambda: carom.pair_correlation(X + 5, Y, box=(10, 10), boundaries="walls"), "x"),
    (lambda: carom.pair_correlation(X, Y, box=(10, 10), boundaries="sticky"), "boundaries"),
    (lambda: carom.pair_correlation(X, Y, box=(10, 10), radius=-1), "radius"),
    (lambda: carom.pair_correlation([X, X], [Y, Y], box=(10, 10), times=[0.0]), "times"),
    (lambda: carom.pair_correlation([X, X], [Y, Y], box=(10, 10), times=[1.0, 0.0]),
     "times"),
    (lambda: carom.pair_correlation(X, Y, box=(10, 10), window=(1, 1)), "window"),
    (lambda: carom.psi6(X, Y, box=(10, 10), estimator="voronoy"), "estimator"),
    (lambda: carom.psi6(X, Y, box=(10, 10), k=0), "k"),
    (lambda: carom.psi6([X, X], [Y, Y], box=(10, 10)), "x"),
    (lambda: carom.msd([X, X], [Y, Y], box=(10, 10), times=[0, 1]), "vx"),
    (lambda: carom.msd([X, X], [Y, Y], [X, X], [Y, Y], box=(10, 10)), "times"),
    (lambda: carom.msd([X, X], [Y, Y], [X, X], [Y, Y], box=(10, 10), times=[0, 1],
                       collision_rate=-1.0), "collision_rate"),
    (lambda: carom.pair_correlation(np.full(20, np.nan), Y, box=(10, 10)), "x"),
])
def test_bad_input_raises_a_value_error_naming_the_argument(call, name):
    with pytest.raises(ValueError, match=rf"^{name}\b"):
        call()
