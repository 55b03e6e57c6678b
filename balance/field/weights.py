"""The field balancer's weight arithmetic: splitting a correction onto fixed positions
and combining several weights into one.

Beyond the seed, which places a correction mass at any angle (seed 002 eq. 3.8 for
its magnitude and angle). On a fan or an impeller the mass can only go into one of N
equally spaced holes or onto a blade; several weights already on a rotor are better
replaced by one. Both are plane-vector statics: a mass m at radius r and angle
theta is the vector U = m r e^(i theta) (seed 002 eq. 3.3), and weights act through
the sum of their vectors.

- **Split**: the correction W = m e^(i theta) lies between two neighbouring positions
  at phi_k and phi_k+1 = phi_k + delta (delta = 360/N). The two masses
  m_k e^(i phi_k) + m_k+1 e^(i phi_k+1) = W are, by the law of sines in the triangle
  they form, m_k = m sin(phi_k+1 - theta) / sin(delta) and
  m_k+1 = m sin(theta - phi_k) / sin(delta); both are >= 0 because theta lies in
  [phi_k, phi_k+1) and delta < 180 deg (N >= 3). When the positions sit at another
  radius than the correction, each mass is scaled by r_correction / r_positions.
- **Combine**: the weights' resultant unbalance is U = sum m_i r_i e^(i theta_i)
  (seed 002 eq. 3.3); the single weight equivalent to them at radius r is U / r.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from kinetostatics.common.angles import radian_value

from ..common import angle_of, check_number, deg360, radius_ratio
from ..errors import BalanceError

__all__ = ["Combined", "Placement", "Split", "combine_weights", "split_correction"]

_ON_POSITION = 1e-9
"""A correction closer than this fraction of the pitch to a position goes there alone."""


@dataclass(frozen=True)
class Placement:
    """A mass at one of the fixed positions (1-based index, angle deg, mass)."""

    position: int
    angle: float
    mass: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"position": self.position, "angle": self.angle, "mass": self.mass}


@dataclass(frozen=True)
class Split:
    """A correction split onto the two neighbouring fixed positions.

    Attributes
    ----------
    mass, angle : float
        The correction being split (mass at the correction radius, deg).
    positions : int
        N, the number of equally spaced positions.
    first : float
        Angle of position 1 (deg); position k sits at first + (k - 1) 360 / N.
    placements : tuple of Placement
        One or two masses (one when the correction lies on a position).
    """

    mass: float
    angle: float
    positions: int
    first: float
    placements: tuple[Placement, ...]

    @property
    def total_mass(self) -> float:
        """The sum of the placed masses (>= the correction's mass)."""
        return float(sum(p.mass for p in self.placements))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"mass": self.mass, "angle": self.angle, "positions": self.positions,
                "first": self.first, "placements": [p.to_dict() for p in self.placements],
                "total_mass": self.total_mass}


def split_correction(mass: float, angle: float, positions: int, first: float = 0.0, *,
                     radius: float | None = None,
                     correction_radius: float | None = None) -> Split:
    """Split a correction onto the two neighbouring of N equally spaced positions.

    Parameters
    ----------
    mass : float
        The correction mass (>= 0), at ``correction_radius`` when given.
    angle : float
        Its angle (deg).
    positions : int
        N >= 3 equally spaced holes or blades.
    first : float
        Angle of position 1 (deg).
    radius, correction_radius : float, optional
        The positions' radius and the correction's radius: give both to rescale the
        masses by correction_radius / radius.

    Returns
    -------
    Split

    Examples
    --------
    >>> s = split_correction(10.0, 100.0, 8)       # holes every 45 deg: 90 and 135
    >>> [(p.position, p.angle, round(p.mass, 4)) for p in s.placements]
    [(3, 90.0, 8.1116), (4, 135.0, 2.4558)]
    """
    m = check_number(mass, "split: mass", nonnegative=True)
    theta = deg360(check_number(angle, "split: angle"))
    if isinstance(positions, bool) or not isinstance(positions, int | np.integer):
        raise BalanceError(f"split: positions must be a whole number of holes or blades, "
                           f"not {positions!r}")
    n = int(positions)
    if n < 3:
        raise BalanceError(f"split: {n} position(s) cannot hold every correction angle; "
                           "give at least 3 equally spaced positions")
    phi0 = deg360(check_number(first, "split: first"))
    scale = radius_ratio(correction_radius, "split: correction_radius", radius, "split: radius",
                         "split: give both radius and correction_radius, or neither")
    delta = 360.0 / n
    rel = (theta - phi0) % 360.0                  # angle past position 1, [0, 360)
    k = int(rel // delta) % n                     # the position just below theta
    frac = rel / delta - rel // delta
    placements: list[Placement] = []
    if m == 0.0:
        pass
    elif frac <= _ON_POSITION or frac >= 1.0 - _ON_POSITION:
        k = k if frac <= _ON_POSITION else (k + 1) % n
        placements.append(Placement(k + 1, deg360(phi0 + k * delta), m * scale))
    else:
        # degrees kept (7-9/10): the law of sines on the positions' angles, which the
        # split takes and gives in degrees (a field balancer's marks)
        d = math.radians(delta)
        below, above = math.radians(rel - k * delta), math.radians((k + 1) * delta - rel)
        m_k = m * math.sin(above) / math.sin(d)          # law of sines, see module doc
        m_k1 = m * math.sin(below) / math.sin(d)
        placements.append(Placement(k + 1, deg360(phi0 + k * delta), m_k * scale))
        placements.append(Placement((k + 1) % n + 1, deg360(phi0 + (k + 1) * delta),
                                    m_k1 * scale))
    return Split(mass=m, angle=theta, positions=n, first=phi0, placements=tuple(placements))


@dataclass(frozen=True)
class Combined:
    """The single weight equivalent to several weights.

    Attributes
    ----------
    mass : float
        Its mass at ``radius`` (or the resultant of mass times radius when no
        radius was given: then every weight is taken at the same radius).
    angle : float or None
        Its angle (deg); None when the weights cancel.
    radius : float or None
        The radius it is placed at.
    count : int
        How many weights were combined.
    """

    mass: float
    angle: float | None
    radius: float | None
    count: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"mass": self.mass, "angle": self.angle, "radius": self.radius,
                "count": self.count}


def combine_weights(weights: Iterable[Any], radius: float | None = None) -> Combined:
    """Replace several weights by one: sum m_i r_i e^(i theta_i) / r.

    Parameters
    ----------
    weights : iterable
        Each weight as (mass, angle_deg) or (mass, angle_deg, radius); either every
        weight has a radius or none has.
    radius : float, optional
        The radius of the single weight; required when the weights carry radii, not
        allowed otherwise (all at one radius: the masses add as vectors).

    Returns
    -------
    Combined

    Examples
    --------
    >>> c = combine_weights([(3.0, 0.0), (4.0, 90.0)])
    >>> round(c.mass, 12), round(c.angle, 4)
    (5.0, 53.1301)
    """
    items = list(weights)
    if not items:
        raise BalanceError("combine: no weights given")
    vecs, with_radius = [], []
    for i, w in enumerate(items):
        where = f"combine: weight {i + 1}"
        if not (isinstance(w, Sequence) and not isinstance(w, str) and len(w) in (2, 3)):
            raise BalanceError(f"{where} must be (mass, angle_deg) or (mass, angle_deg, "
                               f"radius), not {w!r}")
        m = check_number(w[0], f"{where}: mass", nonnegative=True)
        a = check_number(w[1], f"{where}: angle")
        r = check_number(w[2], f"{where}: radius", positive=True) if len(w) == 3 else 1.0
        with_radius.append(len(w) == 3)
        vecs.append(m * r * complex(math.cos(radian_value(a)), math.sin(radian_value(a))))
    if any(with_radius) and not all(with_radius):
        raise BalanceError("combine: give a radius for every weight, or for none")
    if all(with_radius) and radius is None:
        raise BalanceError("combine: the weights have radii; give the radius of the single "
                           "weight too")
    if not any(with_radius) and radius is not None:
        raise BalanceError("combine: a radius for the single weight needs the radius of every "
                           "weight too")
    r = 1.0 if radius is None else check_number(radius, "combine: radius", positive=True)
    total = complex(sum(vecs)) / r
    scale = max(abs(v) for v in vecs) / r
    if abs(total) <= 1e-12 * scale:
        return Combined(mass=0.0, angle=None, radius=radius, count=len(items))
    return Combined(mass=abs(total), angle=angle_of(total), radius=radius, count=len(items))
