"""carom: exact event-driven molecular dynamics of hard discs, from Python.

Backed by the same Rust code as the ``carom`` command:

* ``Simulation(config)`` or ``Simulation.from_arrays(x, y, vx, vy, box=...)`` --
  a run in memory; ``run(until=...)``, ``run(collisions=...)``, callbacks at
  exact times, ``log=`` (the command's log), ``live=`` (served to Foxglove);
  ``state`` as numpy arrays. The same configuration and seed give the command's
  trajectory bit for bit.
* ``open_log(path)`` -- a carom log (MCAP) as numpy arrays: run facts,
  snapshots (one at a time or stacked), ``/thermo`` records and collisions
  (compact records replayed).
* ``analyze(path, **options)`` -- the report of ``carom analyze --json`` as a dict.
* ``structure``, ``pair_correlation``, ``bond_order``, ``structure_factor``,
  ``psi6``, ``msd`` -- the observables on plain arrays, any code's frames.
* ``to_gsd_frame``, ``to_freud`` -- a state for HOOMD's GSD and for freud.

See docs/python.md.
"""

from __future__ import annotations

import json
import math
import os
import warnings
from typing import Any, Iterator

import numpy as np

from . import _carom
from ._carom import Simulation
from .ecosystem import to_freud, to_gsd_frame
# The observables of plain arrays (observables.py, docs/python.md).
from .observables import (bond_order, msd, pair_correlation, psi6, structure,
                          structure_factor)

__all__ = ["Simulation", "Log", "open_log", "analyze", "COLLISION_DTYPE",
           "to_gsd_frame", "to_freud", "structure", "pair_correlation", "bond_order",
           "structure_factor", "psi6", "msd"]
__version__ = _carom.__version__

#: The fields of ``Log.collisions()``: one record per collision, in the names of
#: docs/log-format.md (``/collisions``). ``kind`` is 0 for a pair, 1 for a wall
#: (then ``j`` is 2**32 - 1 and the second disc's velocities are 0). Aligned
#: (144 bytes a record): the Rust reader writes the records in this layout and
#: numpy views them without a copy.
COLLISION_DTYPE = np.dtype(
    [("ordinal", np.uint64), ("kind", np.uint8), ("time", np.float64),
     ("i", np.uint32), ("j", np.uint32), ("nx", np.float64), ("ny", np.float64)]
    + [(f"v{d}{a}_{w}", np.float64)
       for w in ("before", "after") for d in "ij" for a in "xy"]
    + [("energy_lost", np.float64), ("virial", np.float64),
       ("impulse_x", np.float64), ("impulse_y", np.float64)],
    align=True,
)


def _json_or_text(text: str) -> Any:
    try:
        return json.loads(text)
    except ValueError:
        return text


def _number(v: Any) -> float:
    """A /thermo number: JSON numbers, null (absent) and the log's "NaN",
    "Infinity", "-Infinity" for non-finite values."""
    if v is None:
        return math.nan
    return float(v)


class Log:
    """A carom log opened for reading (``open_log(path)``)."""

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = os.fspath(path)
        self._log = _carom.Log(self.path)

    @property
    def run(self) -> dict[str, Any]:
        """The run's metadata (``carom.run``), JSON values decoded: ``config``,
        ``seed``, ``n_discs``, ``stop``, ``log_options``, ``run_facts``, ..."""
        return {k: _json_or_text(v) for k, v in self._log.run_metadata().items()}

    @property
    def facts(self) -> dict[str, Any] | None:
        """The run facts (species, box, boundaries, rule, fields, thermostat,
        growth, floor) as a dict; ``None`` in a log written before they existed."""
        return self.run.get("run_facts")

    @property
    def summary(self) -> dict[str, Any] | None:
        """The run's summary (``carom.summary``); ``None`` for a log cut short."""
        s = self._log.summary_metadata()
        return None if s is None else {k: _json_or_text(v) for k, v in s.items()}

    def snapshots(self, t0: float = -math.inf, t1: float = math.inf
                  ) -> Iterator[dict[str, Any]]:
        """The snapshots with t0 <= time <= t1, one at a time: dicts of numpy
        arrays ``x``, ``y``, ``vx``, ``vy``, ``image``, ``species``, ``radius``,
        ``mass`` with ``time`` and ``box`` (as ``Simulation.state``)."""
        return iter(self._log.snapshots(t0, t1))

    def snapshot_stack(self, t0: float = -math.inf, t1: float = math.inf, *,
                       max_bytes: int | None = None) -> dict[str, np.ndarray]:
        """The snapshots with t0 <= time <= t1 stacked: ``x``, ``y``, ``vx``,
        ``vy``, ``radius`` (float64, frames x N), ``image`` (int32, frames x N x
        2), ``time`` (frames), ``box`` (frames x 2), and ``species`` (int32) and
        ``mass`` (float64), which do not change, of length N.

        Before allocating, the frames are counted (a first pass over the log that
        decodes nothing) and the stack's size, 48 bytes per disc and frame, is
        checked against ``max_bytes`` -- by default half the memory available to
        the process (carom-run's rule: MemAvailable, a cgroup or ``ulimit -v``
        limit; skipped with ``CAROM_IGNORE_MEMORY_CHECK=1``). Too large raises
        ``MemoryError`` with the size, the frames and N, and how many frames fit:
        narrow t0 and t1, or iterate ``snapshots(t0, t1)``."""
        return self._log.snapshot_stack(t0, t1, max_bytes)

    def thermo(self, frame: bool = False) -> Any:
        """The ``/thermo`` records as a dict of numpy arrays, one per field
        (docs/log-format.md); counts are int64, the rest float64 (NaN where a
        record lacks the field, e.g. ``pressure`` before time has passed).
        Text fields (``growth_event``) are object arrays.

        ``frame=True`` gives a pandas DataFrame of the same columns instead (one
        row per record); it needs pandas, and says so with ``ImportError`` when
        pandas is not installed. The default, a dict, never needs pandas."""
        arrays = self._thermo_arrays()
        if not frame:
            return arrays
        try:
            import pandas
        except ImportError as e:
            raise ImportError(
                "Log.thermo(frame=True) needs pandas (pip install pandas); "
                "Log.thermo() gives the same columns as a dict of numpy arrays") from e
        return pandas.DataFrame(arrays)

    def _thermo_arrays(self) -> dict[str, np.ndarray]:
        """The ``/thermo`` records as a dict of numpy arrays (see ``thermo``)."""
        records = [json.loads(r) for r in self._log.thermo_json()]
        keys: list[str] = []
        for r in records:
            keys.extend(k for k in r if k not in keys)
        out: dict[str, np.ndarray] = {}
        for k in keys:
            col = [r.get(k) for r in records]
            if all(isinstance(v, int) and not isinstance(v, bool) for v in col):
                out[k] = np.array(col, dtype=np.int64)
            elif all(v is None or isinstance(v, (int, float)) or v in
                     ("NaN", "Infinity", "-Infinity") for v in col):
                out[k] = np.array([_number(v) for v in col], dtype=np.float64)
            else:
                out[k] = np.array(col, dtype=object)
        return out

    def collisions(self, t0: float = -math.inf, t1: float = math.inf) -> np.ndarray:
        """The collisions with t0 <= time <= t1 as a numpy structured array of
        ``COLLISION_DTYPE``; the velocities of a compact log are replayed exactly
        (the same numbers as a full log of the same run). Read in Rust with the
        GIL released, straight into the records' layout (no column copies)."""
        words = self._log.collision_records(t0, t1)
        return words.view(COLLISION_DTYPE)[:, 0]


def open_log(path: str | os.PathLike[str]) -> Log:
    """Open the carom log ``path`` (an MCAP file written by ``carom run``)."""
    return Log(path)


def analyze(path: str | os.PathLike[str], *, equilibrate: float | None = None,
            every: float | None = None, bins: int = 40,
            structure: bool = True) -> dict[str, Any]:
    """The report of ``carom analyze --json PATH`` as a dict (the same fields,
    with ``file`` and ``log_complete``; docs/analysis.md describes each).

    The options are the command's: ``equilibrate`` (``--equilibrate``, ignore
    what comes before this time), ``every`` (``--every``), ``bins``
    (``--bins``) and ``structure=False`` (``--no-structure``). Warnings about a
    damaged log are issued as Python warnings."""
    text, warned = _carom.analyze_json(os.fspath(path), equilibrate, every, bins,
                                       structure)
    for w in warned:
        warnings.warn(w, stacklevel=2)
    return json.loads(text)
