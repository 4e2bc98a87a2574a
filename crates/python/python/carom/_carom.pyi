"""Type stubs of carom._carom, the compiled half of the package (crates/python/src)."""

from os import PathLike
from typing import Any, Callable, Iterator

import numpy as np

__version__: str

State = dict[str, Any]

class Simulation:
    """A hard-disc system in memory, built from the JSON configuration's fields."""

    def __init__(self, config: dict[str, Any] | str | None = None) -> None: ...
    @staticmethod
    def from_arrays(
        x: Any,
        y: Any,
        vx: Any,
        vy: Any,
        *,
        box: tuple[float, float],
        radius: float | Any | None = None,
        mass: float | Any | None = None,
        species: Any | None = None,
        species_radius: Any | None = None,
        species_mass: Any | None = None,
        boundaries: str | dict[str, str] | None = None,
        wall_restitution: float | None = None,
        collision: dict[str, Any] | None = None,
        **config: Any,
    ) -> Simulation: ...
    def run(
        self,
        until: float | None = None,
        collisions: int | None = None,
        every: float | None = None,
        callback: Callable[[State], object] | None = None,
        log: str | PathLike[str] | None = None,
    ) -> int: ...
    @property
    def state(self) -> State: ...
    @property
    def time(self) -> float: ...
    @property
    def collisions(self) -> int: ...
    @property
    def pair_collisions(self) -> int: ...
    @property
    def wall_collisions(self) -> int: ...
    @property
    def kinetic_energy(self) -> float: ...
    @property
    def potential_energy(self) -> float: ...
    @property
    def energy_lost(self) -> float: ...
    @property
    def config_json(self) -> str: ...
    def __len__(self) -> int: ...

class Snapshots:
    def __iter__(self) -> Iterator[State]: ...
    def __next__(self) -> State: ...

class Log:
    def __init__(self, path: str | PathLike[str]) -> None: ...
    def run_metadata(self) -> dict[str, str]: ...
    def summary_metadata(self) -> dict[str, str] | None: ...
    def snapshots(self, t0: float = ..., t1: float = ...) -> Snapshots: ...
    def thermo_json(self) -> list[str]: ...
    def collision_columns(self, t0: float = ..., t1: float = ...) -> dict[str, np.ndarray]: ...

def analyze_json(
    path: str | PathLike[str],
    equilibrate: float | None = None,
    every: float | None = None,
    bins: int = 40,
    structure: bool = True,
) -> tuple[str, list[str]]: ...
