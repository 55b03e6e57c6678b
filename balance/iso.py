"""Balance quality of rigid rotors after ISO 21940-11 (formerly ISO 1940-1).

Beyond the seed: the tolerance a balanced rotor must meet. A balance quality grade
G (mm/s) is the product e_per * Omega of the permissible specific unbalance and the
maximum service angular velocity. Hence the permissible residual unbalance

    U_per [g mm] = 1000 G [mm/s] m [kg] / Omega [rad/s] = 9549 G m / n   (n in rpm),

(the constant is 1000 * 60 / (2 pi) = 9549.3) e.g. 10 kg at 3000 rpm, G 6.3:
200.5 g mm.

Allocation to two correction planes A and B (the standard's simple rule for a
rotor whose centre of mass lies between the planes): in inverse proportion to the
distances, U_per,A = U_per L_B / L and U_per,B = U_per L_A / L (L_A, L_B the
distances of the centre of mass from planes A and B, L = L_A + L_B), each share
limited to [0.3, 0.7] U_per so that neither plane gets an unreasonably tight
tolerance (the shares still add up to U_per). Overhung or narrow rotors, with the
centre of mass outside the planes, need the standard's full procedure and are
refused here.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ._util import check_number
from .errors import BalanceError

__all__ = [
    "GRADES",
    "IsoAllocation",
    "IsoCheck",
    "iso_allocate",
    "iso_check",
    "iso_permissible_unbalance",
    "kgm_to_gmm",
]

GRADES = (0.4, 1.0, 2.5, 6.3, 16.0, 40.0, 100.0, 250.0, 630.0, 1600.0, 4000.0)
"""The standard's balance quality grades G (mm/s)."""

SHARE_LIMITS = (0.3, 0.7)
"""Limits of each plane's share of U_per in :func:`iso_allocate`."""


def kgm_to_gmm(u: float) -> float:
    """Convert an unbalance from kg m (the workbench's unit) to g mm (the standard's)."""
    return u * 1e6


def iso_permissible_unbalance(grade: float, rotor_mass: float, speed_rpm: float) -> float:
    """Permissible residual unbalance U_per (g mm) of a rigid rotor, ISO 21940-11.

    U_per = 1000 G m / Omega = (60000 / 2 pi) G m / n ~= 9549 G m / n.

    Parameters
    ----------
    grade : float
        Balance quality grade G (mm/s), e.g. 6.3 for G 6.3 (any positive value is
        accepted; the standard's grades are :data:`GRADES`).
    rotor_mass : float
        m, the rotor's mass (kg).
    speed_rpm : float
        n, the maximum service speed (rpm).

    Returns
    -------
    float
        U_per in g mm (1 g mm = 1e-6 kg m).

    Examples
    --------
    >>> round(iso_permissible_unbalance(6.3, 10.0, 3000.0), 1)
    200.5
    """
    G = check_number(grade, "grade G", positive=True)
    m = check_number(rotor_mass, "rotor_mass", positive=True)
    n = check_number(speed_rpm, "speed_rpm", positive=True)
    omega = n * 2.0 * math.pi / 60.0
    return 1000.0 * G * m / omega


@dataclass(frozen=True)
class IsoAllocation:
    """U_per shared between correction planes A and B (g mm).

    Attributes
    ----------
    U_per : float
        The rotor's permissible residual unbalance.
    plane_a, plane_b : float
        The shares of planes A and B.
    limited : bool
        True when the 0.3 / 0.7 limits changed the lever-rule shares.
    """

    U_per: float
    plane_a: float
    plane_b: float
    limited: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"U_per": self.U_per, "plane_a": self.plane_a, "plane_b": self.plane_b,
                "limited": self.limited}


def iso_allocate(U_per: float, z_a: float, z_b: float, z_cog: float) -> IsoAllocation:
    """Allocate U_per to two correction planes by the centre of mass's position.

    U_per,A = U_per L_B / L, U_per,B = U_per L_A / L with L_A = |z_cog - z_a|,
    L_B = |z_b - z_cog|, L = |z_b - z_a|; each share limited to [0.3, 0.7] U_per.

    Parameters
    ----------
    U_per : float
        Permissible residual unbalance of the whole rotor (g mm).
    z_a, z_b : float
        Axial positions of planes A and B (m, any common unit).
    z_cog : float
        Axial position of the rotor's centre of mass, between the planes.

    Returns
    -------
    IsoAllocation

    Raises
    ------
    BalanceError
        Coincident planes, or a centre of mass outside the planes (overhung rotor).
    """
    U = check_number(U_per, "U_per", positive=True)
    za, zb, zc = (check_number(v, n) for v, n in ((z_a, "z_a"), (z_b, "z_b"), (z_cog, "z_cog")))
    L = abs(zb - za)
    if L == 0.0:
        raise BalanceError("iso_allocate: planes A and B coincide; give two distinct planes")
    t = (zc - za) / (zb - za)                     # L_A / L, 0 at plane A, 1 at plane B
    if not -1e-12 <= t <= 1.0 + 1e-12:
        raise BalanceError(f"iso_allocate: the centre of mass (z = {zc:g}) lies outside the "
                           f"planes (z = {za:g}, {zb:g}); the simple allocation applies to "
                           "rotors with the centre of mass between the planes")
    share_a = min(max(1.0 - t, SHARE_LIMITS[0]), SHARE_LIMITS[1])   # L_B / L, limited
    limited = share_a != 1.0 - t
    return IsoAllocation(U_per=U, plane_a=U * share_a, plane_b=U * (1.0 - share_a),
                         limited=limited)


@dataclass(frozen=True)
class IsoCheck:
    """Residual unbalances compared with their permissible values (g mm).

    Attributes
    ----------
    residual, permissible : tuple of float
        Per plane (or one value for the whole rotor).
    ratio : tuple of float
        residual / permissible per plane.
    ok : bool
        True when every residual is within its permissible value.
    """

    residual: tuple[float, ...]
    permissible: tuple[float, ...]
    ratio: tuple[float, ...]
    ok: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {"residual": list(self.residual), "permissible": list(self.permissible),
                "ratio": list(self.ratio), "ok": self.ok}


def iso_check(residual: float | Sequence[float], permissible: float | Sequence[float]
              | IsoAllocation) -> IsoCheck:
    """Whether residual unbalances meet their ISO 21940-11 tolerances.

    Parameters
    ----------
    residual : float or sequence of float
        Residual unbalance(s), g mm (convert kg m with :func:`kgm_to_gmm`): one for the
        whole rotor, or one per plane.
    permissible : float, sequence of float or IsoAllocation
        U_per, or the per-plane shares (an :class:`IsoAllocation` gives planes A, B).

    Returns
    -------
    IsoCheck

    Examples
    --------
    >>> iso_check(150.0, iso_permissible_unbalance(6.3, 10.0, 3000.0)).ok
    True
    """
    if isinstance(permissible, IsoAllocation):
        permissible = (permissible.plane_a, permissible.plane_b)
    res = np.atleast_1d(np.asarray(residual, dtype=float))
    per = np.atleast_1d(np.asarray(permissible, dtype=float))
    if res.shape != per.shape or res.ndim != 1:
        raise BalanceError(f"iso_check: {res.size} residual(s) for {per.size} permissible "
                           "value(s); give one per plane")
    for i, (r, p) in enumerate(zip(res, per, strict=True)):
        check_number(float(r), f"iso_check: residual {i + 1}", nonnegative=True)
        check_number(float(p), f"iso_check: permissible {i + 1}", positive=True)
    ratio = res / per
    return IsoCheck(residual=tuple(map(float, res)), permissible=tuple(map(float, per)),
                    ratio=tuple(map(float, ratio)), ok=bool(np.all(res <= per)))
