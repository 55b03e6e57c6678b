"""Static balancing of mechanisms (seed 002 s. 3.4).
"""

from __future__ import annotations

from .core import (
    BALANCING_KEYS,
    CHECK,
    COUNTERWEIGHT_KEYS,
    HARMONIC_GRID,
    METHODS,
    ON_LINE,
    CounterRotatingPair,
    Counterweight,
    MechanismBalancing,
    balanced_scene,
    centre_of_mass,
    h_vectors,
    harmonic_amplitude,
    shaking_force,
    shaking_tables,
    solve_mechanism_balancing,
)

__all__ = [
    "BALANCING_KEYS",
    "CHECK",
    "COUNTERWEIGHT_KEYS",
    "CounterRotatingPair",
    "Counterweight",
    "HARMONIC_GRID",
    "METHODS",
    "MechanismBalancing",
    "ON_LINE",
    "balanced_scene",
    "centre_of_mass",
    "h_vectors",
    "harmonic_amplitude",
    "shaking_force",
    "shaking_tables",
    "solve_mechanism_balancing",
]
