"""The static balancing device of seed 002, fig. 3.9 (eqs 3.18-3.21).

A disk of mass m rests on knife edges with its unknown unbalance m r hanging
straight down. A comparison mass m_c is fixed at radius r_c on the horizontal
diameter x-x; the disk turns to a new equilibrium at the angle alpha read on the
dial. Moments about the axis then give m r sin(alpha) = m_c r_c cos(alpha).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from kinetostatics.common.angles import radian_value

from ..common import check_number
from ..errors import BalanceError

__all__ = ["StaticDeviceResult", "static_device"]


@dataclass(frozen=True)
class StaticDeviceResult:
    """Result of :func:`static_device`: the disk's eccentricity and the correction mass
    that balances it (seed 002, eqs 3.18-3.21).

    Attributes
    ----------
    eccentricity : float
        r, the distance of the disk's centre of mass from the axis (m), eq. 3.20.
    correction_mass : float
        m_e placed at the correction radius on y-y above the axis (kg), eq. 3.21.
    unbalance : float
        m r (kg m), eq. 3.19.
    """

    eccentricity: float
    correction_mass: float
    unbalance: float

    def to_dict(self) -> dict[str, Any]:
        """The contract's keys ``{eccentricity, correction_mass}``."""
        return {"eccentricity": self.eccentricity, "correction_mass": self.correction_mass}


def static_device(disk_mass: float, comparison_mass: float, comparison_radius: float,
                  alpha: float, correction_radius: float) -> StaticDeviceResult:
    """Eccentricity and correction mass from the static balancing device (fig. 3.9).

    Equilibrium with the comparison mass (eq. 3.18): m r sin(alpha) = m_c r_c cos(alpha),
    hence m r = m_c r_c cot(alpha) (eq. 3.19), the eccentricity
    r = (m_c / m) r_c cot(alpha) (eq. 3.20) and the correction mass placed at r_e
    above the axis m_e = m r / r_e (eq. 3.21).

    Parameters
    ----------
    disk_mass : float
        m, the disk's mass (kg, > 0).
    comparison_mass : float
        m_c (kg, > 0).
    comparison_radius : float
        r_c (m, > 0).
    alpha : float
        Equilibrium angle read on the dial (deg), in (0, 90]. 90 deg means the disk
        is already balanced (cot 90 = 0).
    correction_radius : float
        r_e where the correction mass is fixed (m, > 0).

    Returns
    -------
    StaticDeviceResult

    Raises
    ------
    BalanceError
        A non-positive mass or radius, or alpha outside (0, 90].

    Examples
    --------
    >>> r = static_device(5.0, 0.05, 0.10, 25.0, 0.08)
    >>> round(r.eccentricity, 9), round(r.correction_mass, 6)
    (0.002144507, 0.134032)
    """
    m = check_number(disk_mass, "static_test: disk_mass", positive=True)
    mc = check_number(comparison_mass, "static_test: comparison_mass", positive=True)
    rc = check_number(comparison_radius, "static_test: comparison_radius", positive=True)
    a = check_number(alpha, "static_test: alpha")
    re = check_number(correction_radius, "static_test: correction_radius", positive=True)
    if not 0.0 < a <= 90.0:
        raise BalanceError(f"static_test: alpha must lie in (0, 90] deg, got {a:g}; it is the "
                           "dial angle at which the disk settles with the comparison mass")
    t = radian_value(a)
    cot = 0.0 if a == 90.0 else math.cos(t) / math.sin(t)
    mr = mc * rc * cot                   # eq. 3.19: m r = m_c r_c cot(alpha)
    r = mr / m                           # eq. 3.20: r = (m_c / m) r_c cot(alpha)
    me = m * r / re                      # eq. 3.21: m_e = m r / r_e
    return StaticDeviceResult(eccentricity=r, correction_mass=me, unbalance=mr)
