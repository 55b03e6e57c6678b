"""The simulation's exception (no pymunk import: the command line builds its messages
with it before any simulation runs)."""

from __future__ import annotations

from ..model.errors import WorkbenchError


class SimulationError(WorkbenchError):
    """A scene that the simulation cannot reproduce (or a bad simulation setting)."""

