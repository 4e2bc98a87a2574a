"""Type stubs of carom (python/carom/__init__.py)."""

from os import PathLike
from typing import Any, Iterator, Literal, overload

import numpy as np

from ._carom import Simulation as Simulation
from .ecosystem import to_freud as to_freud
from .ecosystem import to_gsd_frame as to_gsd_frame
# The observables of plain arrays (observables.py: typed in the module itself).
from .observables import bond_order as bond_order
from .observables import msd as msd
from .observables import pair_correlation as pair_correlation
from .observables import psi6 as psi6
from .observables import structure as structure
from .observables import structure_factor as structure_factor

__version__: str
COLLISION_DTYPE: np.dtype

class Log:
    path: str
    def __init__(self, path: str | PathLike[str]) -> None: ...
    @property
    def run(self) -> dict[str, Any]: ...
    @property
    def facts(self) -> dict[str, Any] | None: ...
    @property
    def summary(self) -> dict[str, Any] | None: ...
    def snapshots(self, t0: float = ..., t1: float = ...) -> Iterator[dict[str, Any]]: ...
    def snapshot_stack(
        self, t0: float = ..., t1: float = ..., *, max_bytes: int | None = None
    ) -> dict[str, np.ndarray]: ...
    @overload
    def thermo(self, frame: Literal[False] = False) -> dict[str, np.ndarray]: ...
    @overload
    def thermo(self, frame: Literal[True]) -> Any: ...
    def collisions(self, t0: float = ..., t1: float = ...) -> np.ndarray: ...

def open_log(path: str | PathLike[str]) -> Log: ...
def analyze(
    path: str | PathLike[str],
    *,
    equilibrate: float | None = None,
    every: float | None = None,
    bins: int = 40,
    structure: bool = True,
) -> dict[str, Any]: ...
