"""Angles for people: the solver works in radians, people read and type degrees.

The one place outside the scene readers (model/) and the writers (results/,
balance/report/) where an angle changes unit: an angle turned into degrees for a message,
a picture, a table column or a summary value, and a degree given as a number by a person
(a public function's ``*_deg`` argument, a constant written in degrees) turned into
radians. The arithmetic itself has one home, :mod:`kinetostatics.model.units`
(:func:`~kinetostatics.model.units.degrees`, :func:`~kinetostatics.model.units.radians`,
bit for bit ``math``'s and numpy's conversions); these names say what the angle is for
and keep the type the callers had (a float, or a numpy value).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..model.units import degrees, radians


def degrees_text(angle: float, spec: str = ".6g") -> str:
    """``angle`` (rad) as a number of degrees, formatted by ``spec`` (no unit: the
    message says ``deg``)."""
    return format(degree_value(angle), spec)


def degree_value(angle: float) -> float:
    """``angle`` (rad) in degrees, one number for a summary, a table row or a label (a
    float, as ``math.degrees`` gives)."""
    return degrees(float(angle))


def degree_column(angles: ArrayLike) -> np.ndarray:
    """Angles (rad) in degrees, for a table column or a picture's axis (a numpy value,
    as ``np.degrees`` gives)."""
    return degrees(np.asarray(angles))


def radian_value(angle_deg: float) -> float:
    """An angle a person gave in degrees, in radians (a float, as ``math.radians``
    gives)."""
    return radians(float(angle_deg))


def radian_column(angles_deg: ArrayLike) -> np.ndarray:
    """Angles a person or a table gave in degrees, in radians (a numpy value, as
    ``np.radians`` gives)."""
    return radians(np.asarray(angles_deg))
