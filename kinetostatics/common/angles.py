"""Angles for people: the solver works in radians, people read and type degrees.

The one home of the degree conversions outside the scene readers (model/) and the
writers (results/, balance/report/): an angle turned into degrees for a message, a
picture, a table column or a summary value, and a degree given as a number by a person
(a public function's ``*_deg`` argument, a constant written in degrees) turned into
radians. Each function is the plain numpy or math conversion, so that a value moved here
stays the same to the last bit.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike


def degrees_text(angle: float, spec: str = ".6g") -> str:
    """``angle`` (rad) as a number of degrees, formatted by ``spec`` (no unit: the
    message says ``deg``)."""
    return format(math.degrees(angle), spec)


def degree_value(angle: float) -> float:
    """``angle`` (rad) in degrees, one number for a summary, a table row or a label
    (``math.degrees``)."""
    return math.degrees(angle)


def degree_column(angles: ArrayLike) -> np.ndarray:
    """Angles (rad) in degrees, for a table column or a picture's axis
    (``np.degrees``)."""
    return np.degrees(angles)


def radian_value(angle_deg: float) -> float:
    """An angle a person gave in degrees, in radians (``math.radians``)."""
    return math.radians(angle_deg)


def radian_column(angles_deg: ArrayLike) -> np.ndarray:
    """Angles a person or a table gave in degrees, in radians (``np.radians``, the same
    function as ``np.deg2rad``)."""
    return np.radians(angles_deg)
