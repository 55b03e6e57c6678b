"""Solving a scene: structure (driver + dyads), kinematics, loads, friction,
reactions, reduction, and the pipeline :func:`solve`.
"""

from __future__ import annotations

from .pipeline import (
    solve,
)

__all__ = [
    "solve",
]
