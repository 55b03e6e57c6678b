"""Small numeric helpers shared by the balancing modules (angles, speeds, checks)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from kinetostatics.common.angles import degree_value, radian_value
from kinetostatics.model.tomlio import MIN_MAGNITUDE, as_float

from .errors import BalanceError

RPM_TO_RAD_S = 2.0 * math.pi / 60.0
"""omega [rad/s] = n [rpm] * 2 pi / 60."""


def deg360(angle: float) -> float:
    """Map an angle in degrees into [0, 360), never returning 360.0 or -0.0."""
    a = float(angle) % 360.0
    if a >= 360.0 or a == 0.0:  # -1e-17 % 360 rounds to 360.0; also turns -0.0 into 0.0
        return 0.0
    return a


def deg360_array(angles: ArrayLike) -> np.ndarray:
    """Vectorised :func:`deg360`."""
    a = np.mod(np.asarray(angles, dtype=float), 360.0)
    return np.where((a >= 360.0) | (a == 0.0), 0.0, a)


def angle_of(z: complex) -> float:
    """Angle of a complex number (a plane vector) in degrees, in [0, 360)."""
    return deg360(degree_value(math.atan2(z.imag, z.real)))


def polar(magnitude: float, angle_deg: float) -> complex:
    """The plane vector of given magnitude and angle (deg from +x, ccw) as a complex number."""
    return complex(magnitude * math.cos(radian_value(angle_deg)),
                   magnitude * math.sin(radian_value(angle_deg)))


def check_number(value: object, name: str, *, positive: bool = False,
                 nonnegative: bool = False, smallest: float | None = None) -> float:
    """A finite float, else :class:`BalanceError` naming ``name`` (the scene reader's
    :func:`~kinetostatics.model.tomlio.as_float`, with no magnitude limit; ``smallest``:
    the least magnitude other than zero, for a measured amplitude a method squares)."""
    return as_float(value, name, positive=positive, nonnegative=nonnegative, limit=math.inf,
                    smallest=smallest, error=BalanceError)


def radius_ratio(top: object, top_name: str, bottom: object, bottom_name: str,
                 neither: str) -> float:
    """``top / bottom`` of two radii given together (both checked positive, ``top``
    first), 1.0 when neither is given; one alone raises :class:`BalanceError` with the
    message ``neither``."""
    if (top is None) != (bottom is None):
        raise BalanceError(neither)
    if top is None:
        return 1.0
    return (check_number(top, top_name, positive=True)
            / check_number(bottom, bottom_name, positive=True))


def within(where: str, func: Any, *args: Any, **kwargs: Any) -> Any:
    """Call ``func``; a :class:`BalanceError` gets the scene section's name in front."""
    try:
        return func(*args, **kwargs)
    except BalanceError as exc:
        raise BalanceError(f"{where}: {exc}") from None


def coincide(a: float, b: float) -> bool:
    """Two positions (the z of two planes) equal to rounding: a method that divides by
    their distance cannot use them (below 1e-9 of their size, or ``MIN_MAGNITUDE``)."""
    return abs(b - a) <= max(1e-9 * max(abs(a), abs(b)), MIN_MAGNITUDE)
