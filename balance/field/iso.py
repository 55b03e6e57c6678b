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
tolerance (the shares still add up to U_per); :func:`iso_allocate` applies it to
a centre of mass between the planes and refuses others.

The standard states its tolerances in the bearing planes (the tolerance planes)
while the corrections go where material can be added. :func:`iso_tolerances`
allocates U_per to the bearing planes (the lever rule above; for an overhung rotor,
centre of mass outside the bearings, the bearing-plane unbalances that U_per at the
centre of mass produces) and carries the tolerances to two correction planes,
inboard or outboard, by statics (the force and moment balances of the seed's
two-plane balancing, seed 002 eqs 3.9 and 3.11): correction-plane residuals U_1, U_2
load the bearing planes like U_A = (U_1 (z_B - z_1) + U_2 (z_B - z_2)) / L, U_B = (U_1 (z_1 -
z_A) + U_2 (z_2 - z_A)) / L, and with unknown angles the worst case adds their
magnitudes. For narrow rotors (correction planes close together) it gives a static
and a couple tolerance instead. :func:`to_bearing_planes` carries measured residuals
to the bearing planes (exactly when their angles are known).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..common import check_number, coincide
from ..errors import BalanceError

__all__ = [
    "GRADES",
    "IsoAllocation",
    "IsoCheck",
    "IsoTolerances",
    "iso_allocate",
    "iso_check",
    "iso_permissible_unbalance",
    "iso_tolerances",
    "kgm_to_gmm",
    "to_bearing_planes",
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
    if coincide(za, zb):
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


# ------------------------------------------------ tolerance planes and correction planes
@dataclass(frozen=True)
class IsoTolerances:
    """U_per allocated to the bearing planes and translated to the correction planes.

    All unbalances in kg m (SI), positions in m.

    Attributes
    ----------
    U_per : float
        The rotor's permissible residual unbalance.
    kind : str
        ``"inboard"`` (centre of mass between the bearings), ``"overhung"`` (outside
        them) or ``"narrow"`` (static and couple tolerances); see
        :func:`iso_tolerances`.
    bearings : tuple of float
        z of bearing planes A and B.
    bearing_tolerances : tuple of float
        U_per,A and U_per,B.
    limited : bool
        True when the 0.3 / 0.7 limits changed the lever-rule shares.
    planes : tuple of float or None
        z of the correction planes, when given.
    plane_tolerances : tuple of float or None
        The largest residual in each correction plane that keeps both bearing planes
        within tolerance whatever the angles (inboard, overhung).
    static, couple : float or None
        ``narrow``: tolerance of the resultant (static) unbalance and of the couple
        unbalance (each plane's share of the couple).
    """

    U_per: float
    kind: str
    bearings: tuple[float, float]
    bearing_tolerances: tuple[float, float]
    limited: bool
    planes: tuple[float, float] | None = None
    plane_tolerances: tuple[float, float] | None = None
    static: float | None = None
    couple: float | None = None


def _levers(z: float, z_a: float, z_b: float) -> tuple[float, float]:
    """Signed shares of a unit unbalance at z carried by bearing planes A and B
    (statics: U_A + U_B = U, U_A z_a + U_B z_b = U z)."""
    t = (z - z_a) / (z_b - z_a)
    return 1.0 - t, t


def _translation(planes: tuple[float, float], z_a: float, z_b: float) -> np.ndarray:
    """Matrix M with (U_A, U_B) = M (U_1, U_2): correction-plane unbalances (vectors)
    carried to the bearing planes by statics (the force and moment balances of seed
    002 eqs 3.9 and 3.11, with the bearing planes as the two planes)."""
    return np.array([_levers(z, z_a, z_b) for z in planes]).T


def iso_tolerances(U_per: float, bearings: Sequence[float], z_cog: float,
                   planes: Sequence[float] | None = None, *, narrow: bool = False,
                   static_share: float = 0.5) -> IsoTolerances:
    """Allocate U_per to the bearing planes and translate it to the correction planes.

    - Bearing planes (the standard's tolerance planes), centre of mass between them:
      the lever rule U_per,A = U_per L_B / L, U_per,B = U_per L_A / L with each share
      limited to [0.3, 0.7] U_per (:func:`iso_allocate`). Centre of mass outside them
      (an overhung rotor): the bearing-plane unbalances that U_per at the centre of
      mass produces, U_per |L_B| / L and U_per |L_A| / L (signed distances; they
      add up to more than U_per).
    - Correction planes 1 and 2 (inboard or outboard of the bearings): statics carries
      residuals U_1, U_2 to the bearing planes, U_A = (U_1 (z_B - z_1) + U_2 (z_B -
      z_2)) / L and U_B = (U_1 (z_1 - z_A) + U_2 (z_2 - z_A)) / L. With unknown angles
      the worst case adds magnitudes, so tolerances t_1 = s w_1, t_2 = s w_2 (w the
      lever-rule shares of the centre of mass between the correction planes) are
      safe for the largest s with |z_B - z_1| t_1 + |z_B - z_2| t_2 <= L U_per,A and
      |z_1 - z_A| t_1 + |z_2 - z_A| t_2 <= L U_per,B. When the correction planes are
      the bearing planes this returns the bearing tolerances unchanged.
    - Narrow rotors (``narrow=True``, correction planes close together): the residual
      is split into a static part S (S/2 in each plane, at their middle z_m) and a
      couple +-C (distance b = |z_2 - z_1|). The static tolerance takes
      ``static_share`` of each bearing's tolerance, S_per = min_k f U_per,k /
      |lever_k(z_m)|; the couple takes the rest, C_per = min_k (U_per,k -
      |lever_k(z_m)| S_per) L / b. A couple barely loads the bearings of a narrow
      rotor, so C_per is far larger than the worst-case plane tolerances allow.

    Parameters
    ----------
    U_per : float
        Permissible residual unbalance of the rotor (any unbalance unit; the
        results are in the same unit).
    bearings : (float, float)
        z of bearing planes A and B.
    z_cog : float
        z of the centre of mass.
    planes : (float, float), optional
        z of correction planes 1 and 2.
    narrow : bool
        Give static and couple tolerances (needs ``planes``).
    static_share : float
        f in (0, 1): the part of each bearing tolerance given to the static unbalance.

    Returns
    -------
    IsoTolerances

    Examples
    --------
    >>> t = iso_tolerances(200.0, (0.0, 1.0), 0.5, planes=(0.2, 0.8))
    >>> [round(x, 3) for x in t.plane_tolerances]
    [100.0, 100.0]
    """
    U = check_number(U_per, "U_per", positive=True)
    if len(bearings) != 2:
        raise BalanceError("give the z of the two bearing planes A and B")
    za, zb = (check_number(v, f"bearing {n} z") for v, n in zip(bearings, "AB", strict=True))
    zc = check_number(z_cog, "z_cog")
    if coincide(za, zb):
        raise BalanceError(f"bearing planes A and B coincide (z = {za:g} for both); give two "
                           "distinct bearing planes")
    lever_a, lever_b = _levers(zc, za, zb)
    if lever_a >= -1e-12 and lever_b >= -1e-12:
        alloc = iso_allocate(U, za, zb, zc)
        kind, tol, limited = "inboard", (alloc.plane_a, alloc.plane_b), alloc.limited
    else:
        kind, tol, limited = "overhung", (U * abs(lever_a), U * abs(lever_b)), False
    if planes is None:
        if narrow:
            raise BalanceError("narrow rotor: give the z of the two correction planes")
        return IsoTolerances(U_per=U, kind=kind, bearings=(za, zb), bearing_tolerances=tol,
                             limited=limited)
    if len(planes) != 2:
        raise BalanceError("give the z of the two correction planes")
    z1, z2 = (check_number(v, f"correction plane {i + 1} z") for i, v in enumerate(planes))
    if coincide(z1, z2):
        raise BalanceError(f"correction planes 1 and 2 coincide (z = {z1:g} for both); give "
                           "two distinct planes")
    L = abs(zb - za)
    M = np.abs(_translation((z1, z2), za, zb))           # worst case: magnitudes add
    if narrow:
        f = check_number(static_share, "static_share")
        if not 0.0 < f < 1.0:
            raise BalanceError(f"static_share must lie in (0, 1), got {f:g}")
        lev = np.abs(_levers(0.5 * (z1 + z2), za, zb))
        S = min(f * t / lv for t, lv in zip(tol, lev, strict=True) if lv > 0.0)
        C = min((t - lv * S) * L / abs(z2 - z1) for t, lv in zip(tol, lev, strict=True))
        return IsoTolerances(U_per=U, kind="narrow", bearings=(za, zb), bearing_tolerances=tol,
                             limited=limited, planes=(z1, z2), static=float(S),
                             couple=float(C))
    w = np.array([abs(z2 - zc), abs(zc - z1)])
    w = w / w.sum() if w.sum() > 0.0 else np.array([0.5, 0.5])
    s = min(t / float(M[k] @ w) for k, t in enumerate(tol))
    return IsoTolerances(U_per=U, kind=kind, bearings=(za, zb), bearing_tolerances=tol,
                         limited=limited, planes=(z1, z2),
                         plane_tolerances=(float(s * w[0]), float(s * w[1])))


def to_bearing_planes(residuals: Sequence[complex] | Sequence[float],
                      planes: Sequence[float], bearings: Sequence[float]) -> np.ndarray:
    """Carry correction-plane residuals to the bearing planes (statics).

    Complex residuals (magnitude and angle known) give the exact bearing-plane
    vectors; real ones (magnitudes only) give the worst case over their angles.

    Parameters
    ----------
    residuals : two complex or two float
        U_1, U_2 in correction planes 1 and 2.
    planes, bearings : (float, float)
        z of the correction planes and of bearing planes A and B.

    Returns
    -------
    numpy.ndarray
        |U_A|, |U_B|.

    Examples
    --------
    >>> [round(float(x), 6) for x in to_bearing_planes([1.0, 1.0], (0.0, 1.0), (0.25, 0.75))]
    [2.0, 2.0]
    """
    z1, z2 = (check_number(v, "correction plane z") for v in planes)
    za, zb = (check_number(v, "bearing z") for v in bearings)
    if coincide(za, zb):
        raise BalanceError("bearing planes A and B coincide; give two distinct planes")
    res = np.asarray(residuals)
    if res.shape != (2,):
        raise BalanceError("give one residual per correction plane (two)")
    M = _translation((z1, z2), za, zb)
    if np.iscomplexobj(res):
        return np.abs(M @ res)
    return np.abs(M) @ np.abs(res.astype(float))
