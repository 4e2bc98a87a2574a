"""carom states in the shapes other packages expect: a HOOMD ``gsd.hoomd.Frame``
and freud's box and points.

A state is ``Simulation.state`` or a snapshot of ``Log.snapshots()``: discs in
the box [0, L_x) x [0, L_y). HOOMD and freud centre the box on the origin,
[-L/2, L/2), so positions are shifted, x' = x - L/2, with z = 0 (both are 3-D
codes; a 2-D box has L_z = 1 in HOOMD, 0 in freud). ``to_gsd_frame`` follows
``carom export --format gsd`` (src/export/gsd.rs) value for value: float32
positions and velocities, a shifted coordinate that rounds to L/2 in float32
wrapped to -L/2 on a periodic axis (its image one higher) or moved one float32
step inside by a wall, ``typeid`` the species, ``diameter`` 2a, ``mass`` m,
``configuration/box`` = [L_x, L_y, 1, 0, 0, 0] and the time as ``log/carom/time``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["to_gsd_frame", "to_freud"]


def _type_name(k: int) -> str:
    """The name of species k, as ``carom export`` writes it: A, B, ..., Z, T26, ..."""
    return chr(ord("A") + k) if k < 26 else f"T{k}"


def _centred(x: np.ndarray, length: float, periodic: bool) -> tuple[np.ndarray, np.ndarray]:
    """x in [0, L) as float32 in [-L/2, L/2) and where it was wrapped to -L/2
    (``centred`` of src/export/gsd.rs)."""
    half = np.float32(length / 2.0)
    c = (np.asarray(x, dtype=np.float64) - length / 2.0).astype(np.float32)
    out_of_box = c >= half
    if periodic:
        c[out_of_box] = -half
        return c, out_of_box
    c[out_of_box] = np.nextafter(half, np.float32(-np.inf))
    return c, np.zeros_like(out_of_box)


def to_gsd_frame(state: dict[str, Any], *, periodic: tuple[bool, bool] = (True, True),
                 step: int = 0) -> Any:
    """The state as a ``gsd.hoomd.Frame`` (HOOMD's schema, 2-D), the frame
    ``carom export --format gsd`` writes for the same snapshot (module docstring).

    ``periodic`` tells, per axis, whether the box is periodic (True) or walled:
    it decides what happens to a coordinate that rounds to L/2 in float32
    (``log.facts["boundaries"]`` or the configuration's ``box.boundary`` say
    which). ``step`` is ``configuration.step`` (the export numbers its frames
    0, 1, ...). Write it with ``gsd.hoomd.open(path, "w").append(frame)``.
    Needs the ``gsd`` package."""
    import gsd.hoomd

    lx, ly = (float(v) for v in state["box"])
    species = np.asarray(state["species"])
    n = len(species)
    f = gsd.hoomd.Frame()
    f.configuration.step = int(step)
    f.configuration.dimensions = 2
    f.configuration.box = np.array([lx, ly, 1.0, 0.0, 0.0, 0.0], dtype=np.float32)
    f.particles.N = n
    f.particles.types = [_type_name(k) for k in range(int(species.max()) + 1 if n else 0)]
    f.particles.typeid = species.astype(np.uint32)
    f.particles.mass = np.asarray(state["mass"]).astype(np.float32)
    f.particles.diameter = (2.0 * np.asarray(state["radius"])).astype(np.float32)
    x, wrapped_x = _centred(state["x"], lx, periodic[0])
    y, wrapped_y = _centred(state["y"], ly, periodic[1])
    f.particles.position = np.column_stack([x, y, np.zeros(n, np.float32)])
    image = np.asarray(state["image"], dtype=np.int32)
    f.particles.image = np.column_stack(
        [image[:, 0] + wrapped_x, image[:, 1] + wrapped_y, np.zeros(n, np.int32)]
    ).astype(np.int32)
    f.particles.velocity = np.column_stack(
        [np.asarray(state["vx"]).astype(np.float32), np.asarray(state["vy"]).astype(np.float32),
         np.zeros(n, np.float32)])
    f.log["carom/time"] = np.array([state["time"]], dtype=np.float64)
    return f


def to_freud(state: dict[str, Any]) -> tuple[Any, np.ndarray]:
    """The state as ``(box, points)`` for freud: ``box`` a 2-D ``freud.box.Box``
    (L_x, L_y) when freud is importable, else the tuple (L_x, L_y, 0, 0, 0, 0)
    that ``freud.box.Box.from_box`` takes; ``points`` an N x 3 float64 array of
    the centred positions (x - L_x/2, y - L_y/2, 0), inside freud's box
    [-L/2, L/2). For example ``freud.density.RDF(bins, r_max).compute((box,
    points))``. freud computes in float32."""
    lx, ly = (float(v) for v in state["box"])
    x = np.asarray(state["x"], dtype=np.float64)
    points = np.column_stack([x - lx / 2.0, np.asarray(state["y"], np.float64) - ly / 2.0,
                              np.zeros(len(x))])
    try:
        import freud
    except ImportError:
        return (lx, ly, 0.0, 0.0, 0.0, 0.0), points
    return freud.box.Box.from_box([lx, ly], dimensions=2), points
