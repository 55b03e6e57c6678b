"""Angles for people: the solver works in radians, messages and tables speak degrees.
The one place where a message turns an angle in radians into degrees."""

from __future__ import annotations

import math


def degrees_text(angle: float, spec: str = ".6g") -> str:
    """``angle`` (rad) as a number of degrees, formatted by ``spec`` (no unit: the
    message says ``deg``)."""
    return format(math.degrees(angle), spec)
