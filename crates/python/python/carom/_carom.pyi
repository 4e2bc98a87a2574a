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
        live: bool | int | str | None = None,
        live_rate: float | None = None,
    ) -> int: ...
    def start_live(self, live: bool | int | str | None = None, rate: float | None = None) -> str: ...
    def stop_live(self) -> None: ...
    @property
    def live_url(self) -> str | None: ...
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
    def neighbour_lists(self) -> bool: ...
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
    def collision_records(self, t0: float = ..., t1: float = ...) -> np.ndarray: ...
    def snapshot_stack(
        self, t0: float = ..., t1: float = ..., max_bytes: int | None = None
    ) -> dict[str, np.ndarray]: ...

def analyze_json(
    path: str | PathLike[str],
    equilibrate: float | None = None,
    every: float | None = None,
    bins: int = 40,
    structure: bool = True,
) -> tuple[str, list[str]]: ...

# The observables of plain arrays (observables.rs).
def structure_json(
    box_size: tuple[float, float],
    periodic: tuple[bool, bool],
    radius: list[float],
    mass: list[float],
    species: list[int],
    times: list[float],
    x: np.ndarray,
    y: np.ndarray,
    window: tuple[float, float],
) -> str: ...
def dynamics_json(
    box_size: tuple[float, float],
    periodic: tuple[bool, bool],
    radius: list[float],
    mass: list[float],
    species: list[int],
    times: list[float],
    x: np.ndarray,
    y: np.ndarray,
    vx: np.ndarray,
    vy: np.ndarray,
    window: tuple[float, float],
    snapshot_interval: float | None,
    collision_rate: float | None,
) -> str | None: ...
def local_psi6_pairs(
    box_size: tuple[float, float],
    periodic: tuple[bool, bool],
    x: np.ndarray,
    y: np.ndarray,
    estimator: str,
    k: int,
) -> np.ndarray: ...
