"""Type stubs of carom.ecosystem (python/carom/ecosystem.py)."""

from typing import Any

import numpy as np

def to_gsd_frame(
    state: dict[str, Any], *, periodic: tuple[bool, bool] = (True, True), step: int = 0
) -> Any: ...
def to_freud(state: dict[str, Any]) -> tuple[Any, np.ndarray]: ...
