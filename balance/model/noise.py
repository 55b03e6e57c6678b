"""The noise model of a field-balancing section's readings, read from the scene's
``noise``, ``phase_noise`` and ``confidence`` keys (:func:`parse_noise`)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from kinetostatics.model.units import radians

from ..common import check_number
from ..errors import BalanceError

__all__ = ["NoiseModel", "parse_noise"]


@dataclass(frozen=True)
class NoiseModel:
    """1-sigma noise of every reading: amplitude (relative, absolute) and phase (deg)."""

    relative: float = 0.01
    absolute: float = 0.0
    phase: float = 1.0
    confidence: float = 0.95

    def amplitude_sigma(self, amps: np.ndarray) -> np.ndarray:
        """sigma_A = sqrt((relative A)^2 + absolute^2), element-wise."""
        return np.hypot(self.relative * amps, self.absolute)

    def complex_sigma(self, amps: np.ndarray) -> np.ndarray:
        """Standard deviation of the complex reading, sqrt(sigma_A^2 + (A sigma_phase)^2)."""
        return np.hypot(self.amplitude_sigma(amps), amps * radians(self.phase))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the noise model and confidence used."""
        return {"relative": self.relative, "absolute": self.absolute,
                "phase_noise": self.phase, "confidence": self.confidence}


def parse_noise(noise: Mapping[str, Any] | None = None, phase_noise: float | None = None,
                confidence: float | None = None) -> NoiseModel:
    """A :class:`NoiseModel` from the scene's keys (defaults: 1 %, 0, 1 deg, 0.95)."""
    d = NoiseModel()
    rel, ab = d.relative, d.absolute
    if noise is not None:
        if not isinstance(noise, Mapping):
            raise BalanceError("noise must be a table, e.g. { relative = 0.01, absolute = 0.0 }")
        unknown = set(noise) - {"relative", "absolute"}
        if unknown:
            raise BalanceError(f"noise: unknown key {sorted(unknown)[0]!r}; known keys: "
                               "relative, absolute")
        rel = check_number(noise.get("relative", rel), "noise.relative", nonnegative=True)
        ab = check_number(noise.get("absolute", ab), "noise.absolute", nonnegative=True)
    ph = d.phase if phase_noise is None else check_number(phase_noise, "phase_noise",
                                                           nonnegative=True)
    c = d.confidence if confidence is None else check_number(confidence, "confidence")
    if not 0.5 <= c < 1.0:
        raise BalanceError(f"confidence must lie in [0.5, 1), got {c:g}")
    if rel == 0.0 and ab == 0.0 and ph == 0.0:
        raise BalanceError("noise: relative, absolute and phase_noise are all 0; a measurement "
                           "always has noise (give at least one of them)")
    return NoiseModel(relative=rel, absolute=ab, phase=ph, confidence=c)
