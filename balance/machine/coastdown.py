"""The speed history of a coast-down through resonance (:class:`CoastDown`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import BalanceError


@dataclass(frozen=True)
class CoastDown:
    """A speed history for the machine: spun up above resonance, coasting down through it
    (seed 002 s. 3.3.2: each run is spun above the resonance speed and let go; the
    amplitude A1 (A2, A3) is read as the speed passes resonance, eqs 3.23, 3.24, 3.26).

    The rotor's speed falls linearly from ``start`` to ``stop`` times the mount's
    natural frequency omega_n in ``duration`` seconds. The machine's motor imposes it
    (a ``SimpleMotor`` whose rate is set before every step), so every run, whatever
    its masses, passes resonance along the same history: the method's premise (the
    amplitudes of the runs compare only if they are read the same way). A free coast
    would not do that: its run-down rate depends on the rotor's inertia (the trial
    mass changes it) and on the torque the swinging frame exerts on the eccentric
    masses near resonance.

    Parameters
    ----------
    start, stop : float
        Speeds at the start and at the end, in multiples of omega_n (start > stop > 0).
    duration : float
        Time of the run-down (s).
    """

    start: float = 1.5
    stop: float = 0.5
    duration: float = 10.0

    def __post_init__(self) -> None:
        for name in ("start", "stop", "duration"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise BalanceError(f"CoastDown.{name} = {v!r}: give a positive number")
        if not self.start > self.stop:
            raise BalanceError(f"CoastDown: start = {self.start!r} must exceed stop = "
                               f"{self.stop!r} (a coast-down slows down)")

    def speed(self, t: Any, omega_n: float) -> np.ndarray:
        """The rotor's speed (rad/s) at time(s) ``t`` (held at ``stop`` after the end)."""
        s = np.clip(np.asarray(t, dtype=float) / self.duration, 0.0, 1.0)
        return omega_n * (self.start + (self.stop - self.start) * s)

    def rate(self, omega_n: float) -> float:
        """Deceleration (rad/s^2)."""
        return (self.start - self.stop) * omega_n / self.duration

    def passage(self, omega_n: float, damping_ratio: float) -> float:
        """Time taken to cross the half-power band 2 zeta omega_n, in time constants
        1 / (zeta omega_n) of the mount: 2 zeta^2 omega_n^2 / rate. Large (10 and more):
        the run passes resonance quasi-steadily; near 1 and below: the peak shrinks and
        comes late (at a lower speed)."""
        return 2.0 * (damping_ratio * omega_n) ** 2 / self.rate(omega_n)
