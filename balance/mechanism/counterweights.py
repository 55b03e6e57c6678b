"""Counterweights (point masses fixed to a body), the counter-rotating pair of eqs
3.52-3.53, and the placement of a counterweight that gives a required first moment.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from kinetostatics.common.angles import degree_value
from kinetostatics.model.scene import Scene

from ..common import deg360
from ..errors import BalanceError
from .linkage import CounterweightSpec, vec

__all__ = ["CounterRotatingPair", "Counterweight", "place"]


# -- results -------------------------------------------------------------------------------

@dataclass(frozen=True)
class Counterweight:
    """A counterweight: a point mass fixed to a body.

    Attributes
    ----------
    body, about : str
        The body and the body's point the radius is measured from.
    radius : float
        Distance from ``about`` (m).
    mass : float
        kg.
    position : tuple of float
        Local coordinates in the body's frame (m), at ``radius`` from ``about``.
    angle : float
        Direction from ``about`` to the mass in the body's frame, deg in [0, 360).
    """

    body: str
    about: str
    radius: float
    mass: float
    position: tuple[float, float]
    angle: float

    def to_dict(self) -> dict[str, Any]:
        """``{body, about, mass, position, radius, angle}`` (the contract's keys first)."""
        return {"body": self.body, "about": self.about, "mass": float(self.mass),
                "position": [float(self.position[0]), float(self.position[1])],
                "radius": float(self.radius), "angle": float(self.angle)}


@dataclass(frozen=True)
class CounterRotatingPair:
    """The pair of eqs 3.52-3.53: two equal masses on gears outside the scene.

    At driver position theta (deg) the co-rotating mass stands at the global angle
    ``co_angle + theta`` and the counter-rotating one at ``counter_angle - theta``,
    both at ``radius`` from ``axis`` (the crank axis, by assumption).
    """

    mass: float
    radius: float
    axis: tuple[float, float]
    co_angle: float
    counter_angle: float

    def to_dict(self) -> dict[str, Any]:
        """``{mass, radius}`` of each mass of the pair, plus the axis and the angles at
        driver position 0 (deg, [0, 360))."""
        return {"mass": float(self.mass), "radius": float(self.radius),
                "axis": [float(self.axis[0]), float(self.axis[1])],
                "co_angle": float(self.co_angle), "counter_angle": float(self.counter_angle)}


def place(sc: Scene, spec: CounterweightSpec, ref: str, W: np.ndarray,
          scale: float) -> Counterweight:
    """The counterweight on ``spec.body`` whose first moment about the body point ``ref``
    is W (local): m (v + d) = W with v = about - ref and |d| = radius; the lightest."""
    body = sc.bodies[spec.body]
    p = vec(body.points[spec.about])
    v = p - vec(body.points[ref])
    r = spec.radius
    c = float(W @ W)
    if math.sqrt(c) <= 1e-14 * scale:
        return Counterweight(spec.body, spec.about, r, 0.0, (float(p[0] + r), float(p[1])), 0.0)
    a = float(v @ v) - r * r           # m^2 (|v|^2 - r^2) - 2 m W.v + |W|^2 = 0
    b = -2.0 * float(W @ v)
    if abs(a) <= 1e-12 * max(float(v @ v), r * r):
        roots = [-c / b] if b < 0.0 else []
    else:
        disc = b * b - 4.0 * a * c
        roots = [] if disc < 0.0 else [(-b - math.sqrt(disc)) / (2.0 * a),
                                      (-b + math.sqrt(disc)) / (2.0 * a)]
    roots = [m for m in roots if m > 0.0]
    if not roots:
        raise BalanceError(
            f"no counterweight on {spec.body!r} at radius {r:g} m from {spec.about!r} can give "
            f"the first moment {math.sqrt(c):.6g} kg m about {ref!r} (the circle does not meet "
            f"the needed direction): take a larger radius or measure it from {ref!r}")
    m = min(roots)
    d = W / m - v
    pos = p + d
    return Counterweight(spec.body, spec.about, r, m, (float(pos[0]), float(pos[1])),
                         deg360(degree_value(math.atan2(d[1], d[0]))))


