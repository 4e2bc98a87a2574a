"""Observables of plain arrays: carom's analysis on frames from anywhere.

``carom analyze`` measures g_ab(r), psi6, S(k) and the MSD on a log's
snapshots; these functions run the same Rust code (carom-analysis's ``frames``
module) on numpy arrays, so frames from another code, a GSD file or
``Simulation.state`` get the same numbers -- for a log's own snapshots and
window, bit for bit the sections of ``carom.analyze`` (docs/python.md,
"Observables on arrays"). Each takes one frame (x, y of length N), a stack
(frames x N), or state dicts (``Simulation.state``, ``open_log(...).snapshots()``);
equations are those of docs/physics.md. Bad input raises ``ValueError`` naming
the argument.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from . import _carom

__all__ = ["structure", "pair_correlation", "bond_order", "structure_factor", "psi6",
           "msd"]

#: The estimators of ``psi6``: Voronoi-weighted (11.1), Delaunay with equal
#: weights (11.7), the k nearest neighbours (11.8).
ESTIMATORS = ("voronoi", "delaunay", "nearest")


@dataclass
class _Frames:
    """Frames as the Rust side takes them: x, y (and vx, vy) frames x N float64,
    one species index per disc, per-species radius and mass, the box, which axes
    are periodic, the frames' times and the window [t0, t1]."""

    x: np.ndarray
    y: np.ndarray
    vx: np.ndarray | None
    vy: np.ndarray | None
    times: np.ndarray
    species: list[int]
    radius: list[float]
    mass: list[float]
    box: tuple[float, float]
    periodic: tuple[bool, bool]
    window: tuple[float, float]

    def system(self) -> tuple:
        return (self.box, self.periodic, self.radius, self.mass, self.species)


def _periodic(boundaries: Any) -> tuple[bool, bool]:
    """``"periodic"``, ``"walls"``, one per axis as (x, y) or {"x": ..., "y": ...}
    (the configuration's ``box.boundary``)."""
    if isinstance(boundaries, Mapping):
        axes = (boundaries.get("x"), boundaries.get("y"))
    elif isinstance(boundaries, str):
        axes = (boundaries, boundaries)
    else:
        axes = tuple(boundaries) if isinstance(boundaries, (tuple, list)) else ()
    if len(axes) != 2 or any(a not in ("periodic", "walls") for a in axes):
        raise ValueError(f"boundaries = {boundaries!r}: \"periodic\", \"walls\", or one "
                         "per axis as (x, y) or {\"x\": ..., \"y\": ...}")
    return (axes[0] == "periodic", axes[1] == "periodic")


def _per_species(name: str, value: Any) -> np.ndarray:
    """One number, or one per species index; finite and > 0."""
    v = np.atleast_1d(np.asarray(value, dtype=np.float64))
    if v.ndim != 1:
        raise ValueError(f"{name}: one number, or one per species index; got shape "
                         f"{np.shape(value)}")
    if not np.all(np.isfinite(v) & (v > 0)):
        raise ValueError(f"{name} = {value!r}: every value finite and > 0")
    return v


def _stack(name: str, a: Any, shape: tuple[int, ...] | None = None) -> np.ndarray:
    """One frame (N) or a stack (frames x N) as frames x N float64, finite."""
    a = np.asarray(a, dtype=np.float64)
    if a.ndim == 1:
        a = a[np.newaxis, :]
    if a.ndim != 2:
        raise ValueError(f"{name}: one frame (N) or a stack (frames x N); got shape "
                         f"{a.shape}")
    if shape is not None and a.shape != shape:
        raise ValueError(f"{name}: shape {a.shape}, but x has {shape}")
    bad = np.argwhere(~np.isfinite(a))
    if len(bad):
        f, i = bad[0]
        raise ValueError(f"{name}: not finite ({a[f, i]}) at frame {f}, disc {i}")
    return np.ascontiguousarray(a)


def _from_states(states: list[Mapping[str, Any]], unwrap: bool) -> dict[str, Any]:
    """The arrays of state dicts (``Simulation.state``, a log's snapshots): the
    species and per-species radius and mass from the first, positions unwrapped
    (r + n L, physics.md (12.1)) when ``unwrap``."""
    first = states[0]
    species = np.asarray(first["species"])
    for k, s in enumerate(states):
        if not np.array_equal(np.asarray(s["species"]), species):
            raise ValueError(f"x: state {k} has other species than state 0")
    ns = int(species.max()) + 1 if species.size else 1
    per = {}
    for key in ("radius", "mass"):
        col = np.asarray(first[key], dtype=np.float64)
        per[key] = [float(col[np.argmax(species == s)]) if np.any(species == s)
                    else float(col[0]) for s in range(ns)]
    lx, ly = (float(v) for v in first["box"])

    def pos(s: Mapping[str, Any], axis: int, key: str, length: float) -> np.ndarray:
        p = np.asarray(s[key], dtype=np.float64)
        return p + np.asarray(s["image"])[:, axis] * length if unwrap else p

    return {
        "x": np.stack([pos(s, 0, "x", lx) for s in states]),
        "y": np.stack([pos(s, 1, "y", ly) for s in states]),
        "vx": np.stack([np.asarray(s["vx"], dtype=np.float64) for s in states]),
        "vy": np.stack([np.asarray(s["vy"], dtype=np.float64) for s in states]),
        "times": np.array([float(s["time"]) for s in states]),
        "species": species, "radius": per["radius"], "mass": per["mass"],
        "box": (lx, ly),
    }


def _states(x: Any) -> tuple[list[Mapping[str, Any]] | None, Any]:
    """``x`` as a list of state dicts (None when it holds arrays), and ``x``
    itself with an iterator (a log's snapshots) read into a list."""
    if isinstance(x, Mapping):
        return [x], x
    if isinstance(x, np.ndarray) or not isinstance(x, Iterable):
        return None, x
    items = list(x)
    if items and all(isinstance(s, Mapping) for s in items):
        return items, items
    if any(isinstance(s, Mapping) for s in items):
        raise ValueError("x: state dicts and arrays mixed")
    return None, items


def _frames(x: Any, y: Any, *, box: Any, species: Any, radius: Any, mass: Any,
            boundaries: Any, times: Any, window: Any, vx: Any = None, vy: Any = None,
            dynamics: bool = False) -> _Frames:
    """Check and normalise the arguments shared by the observables. For the
    structure (``dynamics`` false) positions are put in the box along periodic
    axes and must lie in it along walled ones; for the dynamics they are
    unwrapped and velocities are required."""
    states, x = _states(x)
    if states is None and dynamics and times is None:
        raise ValueError("times: needed with arrays (one time per frame)")
    if states is not None and (y is not None or vx is not None or vy is not None):
        raise ValueError("y: not with state dicts (they hold x, y, vx, vy)")
    if states is not None:
        if not states:
            raise ValueError("x: no states")
        s = _from_states(states, unwrap=dynamics)
        x, y, vx, vy = s["x"], s["y"], s["vx"], s["vy"]
        species = s["species"] if species is None else species
        radius = s["radius"] if radius is None else radius
        mass = s["mass"] if mass is None else mass
        box = s["box"] if box is None else box
        times = s["times"] if times is None else times
    if y is None:
        raise ValueError("y: needed with x as arrays")
    x = _stack("x", x)
    y = _stack("y", y, x.shape)
    n_frames, n = x.shape
    if dynamics:
        if vx is None or vy is None:
            raise ValueError("vx, vy: needed (the velocity autocorrelation, "
                             "physics.md (13.3))")
        vx, vy = _stack("vx", vx, x.shape), _stack("vy", vy, x.shape)
    if box is None:
        raise ValueError("box: needed with arrays, as (L_x, L_y)")
    lengths = np.asarray(box, dtype=np.float64).ravel()
    if lengths.size != 2 or not np.all(np.isfinite(lengths) & (lengths > 0)):
        raise ValueError(f"box = {box!r}: (L_x, L_y), both finite and > 0")
    periodic = _periodic(boundaries)
    sp = np.zeros(n, dtype=np.int64) if species is None else np.asarray(species)
    if sp.shape != (n,) or (sp.size and not np.issubdtype(sp.dtype, np.integer)):
        raise ValueError(f"species: one integer index per disc ({n}); got shape "
                         f"{sp.shape}, dtype {sp.dtype}")
    if sp.size and (sp.min() < 0 or sp.max() > 65535):
        raise ValueError(f"species: indices from 0 to 65535; got {sp.min()} to "
                         f"{sp.max()}")
    r = _per_species("radius", 0.5 if radius is None else radius)
    m = _per_species("mass", 1.0 if mass is None else mass)
    given = {a.size for a in (r, m) if a.size > 1}
    if len(given) > 1:
        raise ValueError(f"radius and mass: {r.size} and {m.size} species; one number "
                         "or one per species each")
    n_species = given.pop() if given else int(sp.max()) + 1 if sp.size else 1
    if sp.size and sp.max() >= n_species:
        raise ValueError(f"species: index {sp.max()}, but radius and mass give "
                         f"{n_species} species (indices 0 to {n_species - 1})")
    radius = [float(a) for a in np.broadcast_to(r, n_species)] if r.size == 1 else r.tolist()
    mass = [float(a) for a in np.broadcast_to(m, n_species)] if m.size == 1 else m.tolist()
    diameter = 2 * max(radius[s] for s in set(sp.tolist()) or {0})
    if min(lengths) <= diameter:
        raise ValueError(f"box = ({lengths[0]}, {lengths[1]}): too small, each edge "
                         f"must exceed the largest diameter {diameter}")
    if not dynamics:
        x, y = (_into_box(name, a, length, p) for name, a, length, p in
                (("x", x, lengths[0], periodic[0]), ("y", y, lengths[1], periodic[1])))
    if times is None:
        times = np.arange(n_frames, dtype=np.float64)
    times = np.asarray(times, dtype=np.float64).ravel()
    if times.shape != (n_frames,) or not np.all(np.isfinite(times)):
        raise ValueError(f"times: one finite time per frame ({n_frames}); got "
                         f"{np.shape(times)}")
    if np.any(np.diff(times) < 0):
        raise ValueError("times: must not decrease (frames in time order)")
    if window is None:
        t0, t1 = times[0], times[-1]
        window = (t0, t1) if t1 > t0 else (t0, t0 + 1.0)
    w = np.asarray(window, dtype=np.float64).ravel()
    if w.size != 2 or not np.all(np.isfinite(w)) or not w[1] > w[0]:
        raise ValueError(f"window = {window!r}: (t0, t1), finite, t0 < t1")
    return _Frames(x, y, vx, vy, times, sp.astype(np.uint16).tolist(), radius, mass,
                   (float(lengths[0]), float(lengths[1])), periodic,
                   (float(w[0]), float(w[1])))


def _into_box(name: str, a: np.ndarray, length: float, periodic: bool) -> np.ndarray:
    """Positions in [0, L): wrapped along a periodic axis (values already in the
    box unchanged, bit for bit); along a walled axis they must lie in [0, L]."""
    if periodic:
        if np.all((a >= 0) & (a < length)):
            return a
        w = np.mod(a, length)
        return np.where(w >= length, 0.0, w)
    outside = np.argwhere((a < 0) | (a > length))
    if len(outside):
        f, i = outside[0]
        raise ValueError(f"{name}: disc {i} of frame {f} at {a[f, i]} is outside the "
                         f"walled box [0, {length}]")
    return a


def _arrays(v: Any) -> Any:
    """A report section from JSON with its lists of numbers as numpy arrays
    (int64 for counts, float64 else, JSON null -> NaN)."""
    if isinstance(v, dict):
        return {k: _arrays(u) for k, u in v.items()}
    if isinstance(v, list) and v:
        flat = np.ravel(np.array(v, dtype=object))
        if all(isinstance(u, int) and not isinstance(u, bool) for u in flat):
            return np.array(v, dtype=np.int64)
        if all(u is None or isinstance(u, (int, float)) and not isinstance(u, bool)
               for u in flat):
            return np.array(v, dtype=np.float64)
        return [_arrays(u) for u in v]
    return v


def structure(x: Any, y: Any = None, *, box: Any = None, species: Any = None,
              radius: Any = None, boundaries: Any = "periodic", times: Any = None,
              window: Any = None) -> dict[str, Any]:
    """The structure sections of ``carom analyze`` for frames of positions:
    ``pair_correlation`` (physics.md §10, eqs. 10.1-10.2 and 10.4; no contact
    theorem, which needs a pressure), ``bond_order`` (§11, eqs. 11.1-11.2, with
    the estimators 11.7-11.8), ``orientational_correlation`` (g6, eq. 11.3) and
    ``structure_factor`` (eqs. 11.4 and 11.6, periodic boxes only); a section is
    None when the frames cannot give it (ψ6 and g6 need two frames and seven discs).

    ``x``, ``y``: positions, one frame (N) or a stack (frames x N); or ``x``
    one state dict or a sequence of them (``Simulation.state``,
    ``open_log(...).snapshots()``), which also give species, radius, box and
    times. Positions outside a periodic box are wrapped into it.
    ``box``: (L_x, L_y). ``species``: an index per disc (default all 0).
    ``radius``: one radius or one per species index (default 0.5, carom's
    reference disc of diameter 1); g's bins are σ_min/50 wide.
    ``boundaries``: ``"periodic"``, ``"walls"`` or one per axis (x, y).
    ``times``: each frame's time (default 0, 1, 2, ...). ``window``: (t0, t1),
    the time span cut into the 16 blocks behind the error bars (default the
    frames' first to last time); frames before t0 are skipped. S(k) uses the
    first frame of each block. Lists come back as numpy arrays."""
    f = _frames(x, y, box=box, species=species, radius=radius, mass=None,
                boundaries=boundaries, times=times, window=window)
    text = _carom.structure_json(*f.system(), f.times.tolist(), f.x, f.y, f.window)
    return _arrays(json.loads(text))


def pair_correlation(x: Any, y: Any = None, **options: Any) -> dict[str, Any] | None:
    """g_ab(r) of every species pair a <= b (physics.md §10, eq. 10.1 with the
    ideal-gas count 10.2), with the standard error of 16 time blocks and the
    contact value g_ab(σ_ab+) (the parabola in ln g, eq. 10.4): a dict with
    ``r`` (bin centres), ``bin_width`` (σ_min/50), ``r_max``, ``snapshots``,
    ``blocks`` and ``pairs``, one dict per pair with ``a``, ``b``, ``sigma``,
    ``g``, ``std_error`` and ``contact`` (``value``, ``std_error``,
    ``fit_bins``). The arguments are those of ``structure`` (which gives this
    and the other sections at once)."""
    return structure(x, y, **options)["pair_correlation"]


def bond_order(x: Any, y: Any = None, **options: Any) -> dict[str, Any] | None:
    """The bond-order section (physics.md §11): ⟨|Ψ6|⟩ over the frames
    (``global``, Ψ6 = (1/N) Σ_j ψ6_j of eq. 11.1), the mean local |ψ6_j|
    (``local``), the susceptibility χ6 (eq. 11.2), the |Ψ6| series and the
    equal-weight and six-nearest estimators (11.7-11.8) in
    ``other_estimators``; None with fewer than two frames. The arguments are
    those of ``structure``; ``psi6`` gives ψ6 per disc of one frame."""
    return structure(x, y, **options)["bond_order"]


def structure_factor(x: Any, y: Any = None, **options: Any) -> dict[str, Any] | None:
    """S(k) = |ρ_k|²/N (physics.md §11, eq. 11.4) averaged over shells of the
    box's wave vectors: a dict with ``k``, ``s``, ``std_error`` (spread of the
    16 time blocks' first frames), ``vectors`` per shell, the first peak
    (``peak_k``, ``peak_s``, ``peak_std_error``) and the translational order
    ψ_T (eq. 11.6). Periodic boxes only (None with walls). The arguments are
    those of ``structure``."""
    return structure(x, y, **options)["structure_factor"]


def psi6(x: Any, y: Any = None, *, box: Any = None, boundaries: Any = "periodic",
         estimator: str = "voronoi", k: int = 6) -> np.ndarray:
    """ψ6_j of every disc of one frame as a complex128 array (physics.md §11):
    ``"voronoi"`` weighs each Delaunay bond by its Voronoi edge (eq. 11.1,
    Mickel et al. 2013), ``"delaunay"`` weighs them equally (eq. 11.7),
    ``"nearest"`` averages over the ``k`` nearest discs (eq. 11.8). Each bond
    counts e^{+6iθ}, θ the angle of r_k - r_j from the x axis (freud's
    convention: ψ6 = 1 for a hexagon with a bond along x). The global order is
    ``psi6(...).mean()``. ``x``, ``y``: positions of one frame (N), or ``x`` a
    state dict; ``box`` (L_x, L_y); ``boundaries`` as in ``structure``."""
    if estimator not in ESTIMATORS:
        raise ValueError(f"estimator = {estimator!r}: one of {', '.join(ESTIMATORS)}")
    if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or k < 1:
        raise ValueError(f"k = {k!r}: a positive integer (neighbours for \"nearest\")")
    f = _frames(x, y, box=box, species=None, radius=None, mass=None,
                boundaries=boundaries, times=None, window=None)
    if f.x.shape[0] != 1:
        raise ValueError(f"x: one frame (N); got {f.x.shape[0]} frames")
    pairs = _carom.local_psi6_pairs(f.box, f.periodic, f.x[0], f.y[0], estimator, int(k))
    return pairs.view(np.complex128)


def msd(x: Any, y: Any = None, vx: Any = None, vy: Any = None, *, times: Any = None,
        box: Any = None, species: Any = None, radius: Any = None, mass: Any = None,
        boundaries: Any = "periodic", window: Any = None,
        snapshot_interval: float | None = None,
        collision_rate: float | None = None) -> dict[str, Any] | None:
    """The dynamics section of ``carom analyze`` (physics.md §13) for frames in
    time order of *unwrapped* positions (§12, u = r + n L) and velocities: per
    species the MSD(τ) and α₂(τ) (eq. 13.1) with their errors (13.6), D from
    MSD → 4Dτ + c (13.2, the error 13.7), the velocity autocorrelation C(τ)
    (13.3) and F_s(k*, τ) with τ_α (13.4-13.5, periodic boxes). ``x``, ``y``,
    ``vx``, ``vy``: frames x N arrays; or ``x`` a sequence of state dicts, which
    are unwrapped with their image counts. ``times``: each frame's time
    (needed with arrays). Time origins are the frames in ``window`` (default
    first to last time). ``snapshot_interval``: the frames' spacing when
    regular; ``collision_rate``: collisions per disc per unit time, which sets
    the D window (t_a = 10/ω; a tenth of the longest lag when None). ``box``,
    ``species``, ``radius``, ``mass`` and ``boundaries`` as in ``structure``.
    None without two frames in the window."""
    for name, v in (("snapshot_interval", snapshot_interval),
                    ("collision_rate", collision_rate)):
        if v is not None and not (np.isfinite(v) and v > 0):
            raise ValueError(f"{name} = {v!r}: finite and > 0, or None")
    f = _frames(x, y, box=box, species=species, radius=radius, mass=mass,
                boundaries=boundaries, times=times, window=window, vx=vx, vy=vy,
                dynamics=True)
    text = _carom.dynamics_json(*f.system(), f.times.tolist(), f.x, f.y, f.vx, f.vy,
                                f.window, snapshot_interval, collision_rate)
    return None if text is None else _arrays(json.loads(text))
