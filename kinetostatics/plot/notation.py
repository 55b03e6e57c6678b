"""One notation on every picture: magnitudes positive with the sense in words, angles
from 0 to 360 deg, no "-0", subscripts as mathtext, and the course's Romanian term as a
gloss after the English name of each construction.
"""

from __future__ import annotations

import numpy as np

__all__ = ["GLOSS", "POLE", "direction_text", "gloss", "number", "signed_text", "titled"]

#: The pole of the velocity and of the acceleration plan (fixed points sit on it).
POLE = "o"

#: The Romanian name of each course construction (seeds 001, 002: planul vitezelor,
#: poligonul forțelor, unghiul de transmitere, momentul de echilibrare, reacțiunea,
#: forțele de inerție, centrul instantaneu), written after the English one.
GLOSS = {
    "velocity plan": "planul vitezelor",
    "acceleration plan": "planul accelerațiilor",
    "force polygon": "poligonul forțelor",
    "polar diagram": "diagrama polară a reacțiunii",
    "free-body diagram": "diagrama corpului liber",
    "Wittenbauer diagram": "diagrama Wittenbauer",
    "instantaneous centres": "centrele instantanee de rotație",
    "transmission angle": "unghiul de transmitere",
    "balancing moment": "momentul de echilibrare",
    "balancing force": "forța de echilibrare",
    "unbalance": "dezechilibrul",
    "mechanism": "mecanismul",
}


def gloss(term: str) -> str:
    """The Romanian term of a course construction (``KeyError`` for an unknown one)."""
    return GLOSS[term]


def titled(term: str) -> str:
    """``"velocity plan (planul vitezelor)"``: the English name with its gloss."""
    return f"{term} ({GLOSS[term]})"


def number(x: float, fmt: str = ".4g") -> str:
    """A number formatted with ``fmt``, a negative zero written ``0``."""
    s = format(float(x), fmt)
    if s.startswith("-") and float(s) == 0.0:
        s = s[1:]
    return s


def signed_text(name: str, value: float, unit: str, fmt: str = ".4g", *,
                rotation: bool = True) -> str:
    """A signed quantity as its magnitude and its sense in words.

    ``signed_text("ω(coupler)", -0.7873, "rad/s")`` gives ``"ω(coupler) = 0.7873 rad/s,
    clockwise"``. For a rotation (angular speed, acceleration, a couple) the sign is
    counterclockwise positive; otherwise ``rotation=False`` writes "negative".
    """
    mag = number(abs(value), fmt)
    if float(mag) == 0.0:
        return f"{name} = 0 {unit}"
    if rotation:
        sense = "counterclockwise" if value > 0 else "clockwise"
    else:
        sense = "positive" if value > 0 else "negative"
    return f"{name} = {mag} {unit}, {sense}"


def direction_text(v) -> str:
    """The direction of a vector as an angle from +x, 0 to 360 deg: ``"299.1°"``."""
    a = float(np.degrees(np.arctan2(v[1], v[0]))) % 360.0
    s = number(a, ".1f")
    return ("0.0" if s == "360.0" else s) + "°"
