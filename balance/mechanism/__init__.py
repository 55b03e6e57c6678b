"""Static balancing of planar mechanisms (seed 002, section 3.4).

A mechanism is statically balanced when its centre of mass stays fixed over the
cycle: then the resultant of the inertia forces, F = -m a_G, is zero (the seed's
definition, s. 3.4). This package reads a mechanism scene with a ``[balancing]``
section (scene-format.md, section 2), finds the counterweights the chosen method
asks for (the scene gives each one's body, the body point it is measured from
and its radius; the method gives its mass and direction), and computes, from the
kinematics of the same scene, the shaking force and moment over the cycle before
and after.

Modules, in the order of the data flow:

- :mod:`~balance.mechanism.linkage`: recognise the four-bar or slider-crank, read
  the ``[balancing]`` table, first moments of the bodies;
- :mod:`~balance.mechanism.counterweights`: counterweights, the counter-rotating
  pair, and the placement of a counterweight for a required first moment;
- :mod:`~balance.mechanism.methods`: the seed's methods (eqs 3.38-3.53);
- :mod:`~balance.mechanism.shaking`: shaking force and moment, centre of mass,
  h vectors, harmonics;
- :mod:`~balance.mechanism.solve`: :func:`solve_mechanism_balancing`, its result
  and the numerical checks;
- :mod:`~balance.mechanism.plot`: the pictures (imported on demand: matplotlib).
"""

from __future__ import annotations

from .counterweights import CounterRotatingPair, Counterweight
from .linkage import BALANCING_KEYS, COUNTERWEIGHT_KEYS, METHODS, ON_LINE
from .methods import HARMONIC_GRID
from .shaking import centre_of_mass, h_vectors, harmonic_amplitude, shaking_force
from .solve import (
    CHECK,
    MechanismBalancing,
    balanced_scene,
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
