"""Eccentric masses as the machine takes them, and the rotor body they make.

The rotor is one body: its own mass and moment of inertia plus every eccentric mass,
with the centre of mass and the moment of inertia about it that these give (seed 002
eq. 3.3 for the resultant unbalance, parallel axes for the inertia).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np

from ..errors import BalanceError
from ..rotor.design import Unbalance


def as_unbalances(items: Iterable[Any], where: str) -> list[Unbalance]:
    """Unbalance objects, dicts {mass, radius, angle} or (mass, radius, angle) tuples."""
    out = []
    for i, u in enumerate(items):
        if isinstance(u, Unbalance):
            m, r, a = u.mass, u.radius, u.angle
        elif isinstance(u, dict):
            try:
                m, r, a = u["mass"], u["radius"], u.get("angle", 0.0)
            except KeyError as exc:
                raise BalanceError(f"{where}[{i}]: missing {exc.args[0]!r}; give mass (kg), "
                                   "radius (m) and angle (deg)") from None
        else:
            try:
                m, r, a = u
            except (TypeError, ValueError):
                raise BalanceError(f"{where}[{i}]: give (mass, radius, angle) or an "
                                   "Unbalance") from None
        try:
            m, r, a = float(m), float(r), float(a)
        except (TypeError, ValueError):
            raise BalanceError(f"{where}[{i}]: mass, radius and angle must be numbers") \
                from None
        if not (math.isfinite(m) and m >= 0.0 and math.isfinite(r) and r >= 0.0
                and math.isfinite(a)):
            raise BalanceError(f"{where}[{i}]: mass {m!r} kg and radius {r!r} m must be "
                               ">= 0 and the angle finite")
        out.append(Unbalance(m, r, a))
    return out


def unbalance_vector(unbalances: Iterable[Any]) -> complex:
    """The resultant unbalance sum m_i r_i (kg m) as a complex number (angle from the
    rotor's 0 deg mark, counter-clockwise), eq. 3.3."""
    return sum((u.U for u in as_unbalances(unbalances, "unbalances")), 0j)


def random_unbalance(seed: int) -> list[Unbalance]:
    """The study's (and the tests') random unbalance: one mass of 5 to 30 g at 40 to
    100 mm, at any angle, from ``numpy.random.default_rng(seed)``."""
    rng = np.random.default_rng(seed)
    return [Unbalance(rng.uniform(0.005, 0.03), rng.uniform(0.04, 0.1), rng.uniform(0, 360))]



def spinning_rotor(us: list[Unbalance], rotor_mass: float, rotor_inertia: float,
                   speed: float):
    """The pymunk body of a rotor with eccentric masses, its local origin on the axis at
    the world origin, turning at ``speed`` (rad/s) about it.

    Returns
    -------
    (pymunk.Body, complex, complex)
        The body, the resultant unbalance U = sum m_i r_i (kg m, eq. 3.3) and the
        velocity of its centre of mass (m/s, as a complex number).
    """
    import pymunk
    m = rotor_mass + sum(u.mass for u in us)
    U = sum((u.U for u in us), 0j)                     # eq. 3.3
    g = U / m                                          # rotor's centre of mass
    inertia = rotor_inertia - m * abs(g) ** 2 \
        + sum(u.mass * u.radius ** 2 for u in us)      # about the cog (parallel axes)
    rotor = pymunk.Body(m, inertia)
    rotor.center_of_gravity = (g.real, g.imag)
    rotor.position = (0.0, 0.0)     # after the cog: else the origin jumps by -g
    rotor.angular_velocity = speed
    v = 1j * speed * g
    rotor.velocity = (v.real, v.imag)
    return rotor, U, v


def add_rigid(space, constraints) -> None:
    """Add constraints to a space as exact joints: ``error_bias = 0`` (the whole drift
    corrected in the next step), no collisions between the bodies they join."""
    for c in constraints:
        c.error_bias = 0.0
        c.collide_bodies = False
        space.add(c)
