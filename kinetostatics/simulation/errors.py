"""The simulation's exceptions (no pymunk import: the command line builds its messages
with them before any simulation runs)."""

from __future__ import annotations

from ..model.errors import WorkbenchError

__all__ = ["SimulationDiverged", "SimulationError"]


class SimulationError(WorkbenchError):
    """A scene that the simulation cannot reproduce (or a bad simulation setting)."""


class SimulationDiverged(SimulationError):
    """A run that blew up: its state or readings became non-finite, its joints drifted
    apart beyond the bound of :func:`kinetostatics.simulation.drift_bound`, or its
    momentum balance could not be solved. Its numbers are not a result.

    Attributes
    ----------
    time : float
        Simulated time of the first sample found diverged (s).
    position : float
        Driver position there (deg or m; NaN when the state was no longer finite).
    drift : float
        Largest joint drift of the run (m; inf when the state was not finite).
    size : float
        The mechanism's size (m), against which the drift is stated.
    iterations : int
    dt : float
    steps_per_revolution : float
        Steps per driver revolution (a sliding driver: per sweep).
    reason : str
        What was found: ``"drift"``, ``"not finite"`` or ``"singular momentum balance"``.
    where : str
        What drifted: ``"joint <name>"`` (the joint that drifted most at that sample),
        ``"body <name>"`` (the first whose state was not finite), or ``""``.
    """

    def __init__(self, *, time: float, position: float, kind: str, drift: float, size: float,
                 iterations: int, dt: float, steps_per_revolution: float, reason: str,
                 where: str = ""):
        self.time, self.position, self.kind = float(time), float(position), kind
        self.drift, self.size, self.reason = float(drift), float(size), reason
        self.where = where
        self.iterations, self.dt = int(iterations), float(dt)
        self.steps_per_revolution = float(steps_per_revolution)
        super().__init__(self._message())

    def __reduce__(self):
        """Picklable (a batch's worker may raise it): rebuilt from its fields."""
        fields = {k: getattr(self, k) for k in ("time", "position", "kind", "drift", "size",
                                                 "iterations", "dt", "steps_per_revolution",
                                                 "reason", "where")}
        return _rebuild, (fields,)

    @property
    def advice(self) -> tuple[int, int]:
        """The settings the message suggests: four times the iterations, or half the steps
        (with ``error_bias = 0`` a finer step needs more iterations to stay stable)."""
        return 4 * self.iterations, max(10, int(round(self.steps_per_revolution / 2)))

    def _message(self) -> str:
        if self.position == self.position:          # finite position
            where = (f"{self.position:.4g} deg" if self.kind == "R"
                     else f"{self.position:.4g} m")
            at = f"t = {self.time:.4g} s, driver at {where}"
        else:
            at = f"t = {self.time:.4g} s"
        drift = (f"drift {self.drift:.2g} m = {self.drift / self.size:.2g} x the mechanism's "
                 f"size" if self.drift < float("inf") else "state not finite")
        if self.where:
            drift += (f", first in {self.where}" if self.reason == "not finite"
                      else f", first over the bound at {self.where}")
        if self.reason == "singular momentum balance":
            drift += ", singular momentum balance"
        it, steps = self.advice
        return (f"the simulation diverged at {at} ({drift}, iterations {self.iterations}, "
                f"dt {self.dt:.4g} s); try --iterations {it} or --steps {steps}")


def _rebuild(fields: dict) -> SimulationDiverged:
    return SimulationDiverged(**fields)
