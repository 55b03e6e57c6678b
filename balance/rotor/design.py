"""Rotor balancing by design (seed 002, section 3.2).

A rigid rotor carries known eccentric masses m_j at radii r_j, angles theta_j, in
axial planes z_j. Each gives the unbalance vector U_j = m_j r_j (eq. 3.3), a plane
vector along its position vector; at speed omega its inertia force is U_j omega^2
(eq. 3.5). The rotor is corrected by one mass in one plane (static balancing,
eqs 3.3-3.8) or by two masses in two planes (dynamic balancing, eqs 3.9-3.14).

Plane vectors are complex numbers x + i y; angles are in degrees from the rotor's
+x mark, counter-clockwise, and reported in [0, 360).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from kinetostatics.common.angles import radian_column, radian_value
from kinetostatics.model.tomlio import suggest
from kinetostatics.model.units import Units

from ..common import RPM_TO_RAD_S, angle_of, check_number
from ..errors import BalanceError, BalanceWarning

__all__ = [
    "CorrectionPlane",
    "Correction",
    "RotorResult",
    "Unbalance",
    "balance_rotor",
]

_ZERO_TOL = 1e-12
"""A correction below this fraction of the rotor's unbalance scale is reported as zero."""

_COINCIDENT_TOL = 1e-9
"""Planes closer than this fraction of the rotor's axial extent coincide."""

CLOSE_PLANES = 0.05
"""Two correction planes closer than this fraction of the rotor's axial extent are
flagged: the couple is corrected by a lever that short, so the corrections grow as
extent / distance."""

LARGE_CORRECTION = 10.0
"""Corrections whose total |U_e| exceeds this many times the total |U_j| they balance
are flagged as absurd."""


@dataclass(frozen=True)
class Unbalance:
    """One eccentric mass: ``mass`` (kg) at ``radius`` (m) and ``angle`` (deg), in the
    plane ``z`` (m)."""

    mass: float
    radius: float
    angle: float
    z: float = 0.0

    @property
    def U(self) -> complex:
        """The unbalance vector m r (kg m), eq. 3.3."""
        return self.mass * self.radius * complex(math.cos(radian_value(self.angle)),
                                                 math.sin(radian_value(self.angle)))


@dataclass(frozen=True)
class CorrectionPlane:
    """A correction plane at axial position ``z`` (m); the mass is fixed at ``radius`` (m)."""

    z: float
    radius: float


@dataclass(frozen=True)
class Correction:
    """The correction mass of one plane.

    Attributes
    ----------
    plane : int
        1-based index of the plane in the input.
    z, radius : float
        The plane's axial position and the correction radius (m).
    mass : float
        Correction mass (kg), |U| / radius; 0 for a zero correction.
    angle : float
        Angle of the correction mass (deg, [0, 360)); 0 for a zero correction.
    U : float
        |U| = mass x radius (kg m).
    vector : complex
        The correction unbalance vector U_e (kg m).
    """

    plane: int
    z: float
    radius: float
    mass: float
    angle: float
    U: float
    vector: complex

    def to_dict(self) -> dict[str, Any]:
        """The contract's keys ``{plane, z, radius, mass, angle, U}``."""
        return {"plane": self.plane, "z": self.z, "radius": self.radius, "mass": self.mass,
                "angle": self.angle, "U": self.U}


@dataclass(frozen=True)
class RotorResult:
    """Result of :func:`balance_rotor`.

    Magnitudes are forces (N) and moments (N m) when ``speed_rpm`` is given, else
    unbalances (kg m) and unbalance moments (kg m^2); the moment is taken about z = 0.

    Attributes
    ----------
    corrections : tuple of Correction
        One per correction plane, in input order.
    initial_force, initial_moment : float
        |sum U_j| and |sum z_j U_j| (times omega^2 with a speed) before correction.
    residual_force, residual_moment : float
        The same after the corrections are added.
    speed_rpm : float or None
        Speed used for forces and moments.
    unbalances : numpy.ndarray of complex
        The vectors U_j = m_j r_j (kg m), input order (for plotting).
    z : numpy.ndarray
        Their axial positions (m).
    warnings : tuple of str
        Conditioning warnings (correction planes too close for the rotor's length,
        corrections far larger than the unbalance); empty when all is well.
    """

    corrections: tuple[Correction, ...]
    initial_force: float
    initial_moment: float
    residual_force: float
    residual_moment: float
    speed_rpm: float | None
    unbalances: np.ndarray = field(repr=False)
    z: np.ndarray = field(repr=False)
    warnings: tuple[str, ...] = ()

    @property
    def scale(self) -> float:
        """omega^2 (rad^2/s^2) with a speed, else 1: multiplies kg m into N."""
        return (self.speed_rpm * RPM_TO_RAD_S) ** 2 if self.speed_rpm is not None else 1.0

    @property
    def units(self) -> tuple[str, str]:
        """Units of the force and the moment magnitudes."""
        return ("N", "N m") if self.speed_rpm is not None else ("kg m", "kg m^2")

    def to_dict(self) -> dict[str, Any]:
        """Exactly the contract's keys (scene-format.md section 2, ``rotor``)."""
        return {
            "corrections": [c.to_dict() for c in self.corrections],
            "initial_force": self.initial_force,
            "initial_moment": self.initial_moment,
            "residual_force": self.residual_force,
            "residual_moment": self.residual_moment,
            "warnings": list(self.warnings),
        }


def _check_dict_keys(item: Mapping, known: tuple[str, ...], where: str) -> None:
    for key in item:
        if key not in known:
            raise BalanceError(f"{where}: unknown key {key!r}{suggest(key, known)}; "
                               f"known keys: {', '.join(known)}")


def _as_unbalance(item: Any, k: int) -> Unbalance:
    where = f"unbalance {k + 1}"
    if isinstance(item, Unbalance):
        u = item
    elif isinstance(item, Mapping):
        _check_dict_keys(item, ("mass", "radius", "angle", "z"), where)
        try:
            u = Unbalance(item["mass"], item["radius"], item["angle"], item.get("z", 0.0))
        except KeyError as exc:
            raise BalanceError(f"{where}: missing {exc.args[0]!r}") from None
    elif isinstance(item, Sequence) and len(item) in (3, 4):
        u = Unbalance(*item)
    else:
        raise BalanceError(f"{where} must be an Unbalance, a dict or (mass, radius, angle[, z])")
    return Unbalance(check_number(u.mass, f"{where}: mass", nonnegative=True),
                     check_number(u.radius, f"{where}: radius", nonnegative=True),
                     check_number(u.angle, f"{where}: angle"),
                     check_number(u.z, f"{where}: z"))


def _as_plane(item: Any, k: int) -> CorrectionPlane:
    where = f"correction plane {k + 1}"
    if isinstance(item, CorrectionPlane):
        p = item
    elif isinstance(item, Mapping):
        _check_dict_keys(item, ("z", "radius"), where)
        try:
            p = CorrectionPlane(item.get("z", 0.0), item["radius"])
        except KeyError as exc:
            raise BalanceError(f"{where}: missing {exc.args[0]!r}") from None
    elif isinstance(item, Sequence) and len(item) == 2:
        p = CorrectionPlane(*item)
    else:
        raise BalanceError(f"{where} must be a CorrectionPlane, a dict or (z, radius)")
    return CorrectionPlane(check_number(p.z, f"{where}: z"),
                           check_number(p.radius, f"{where}: radius", positive=True))


def _correction(k: int, plane: CorrectionPlane, Ue: complex, tol: float) -> Correction:
    if abs(Ue) <= tol:  # zero correction: mass 0, angle 0 (contract)
        return Correction(k + 1, plane.z, plane.radius, 0.0, 0.0, 0.0, 0j)
    return Correction(k + 1, plane.z, plane.radius, abs(Ue) / plane.radius, angle_of(Ue),
                      abs(Ue), Ue)


def balance_rotor(unbalances: Iterable[Any], planes: Iterable[Any],
                  speed_rpm: float | None = None, units: Units | None = None) -> RotorResult:
    """Correction masses that balance a rigid rotor by design (seed 002, s. 3.2).

    One correction plane gives static balancing: the correction vector closes the
    polygon of the unbalance vectors, U_e = -sum_j m_j r_j (eqs 3.3-3.8, with the
    misprint of eq. 3.8 corrected: its third term is m3 r3, not m2 r3). The couple of
    the unbalances is left as it is (``residual_moment``).

    Two planes I and II (at z_I, z_II) give dynamic balancing. The moments about the
    point O of plane I vanish (eqs 3.11-3.12, vectors k x (z U)):
    sum_j (z_j - z_I) U_j + (z_II - z_I) U_e2 = 0, which fixes U_e2 (eq. 3.13); the
    forces vanish (eqs 3.9-3.10), sum_j U_j + U_e1 + U_e2 = 0, which fixes U_e1
    (eq. 3.14). Each mass is |U_e| / r_e at the angle of U_e.

    Parameters
    ----------
    unbalances : iterable
        The eccentric masses: :class:`Unbalance` objects, dicts with keys ``mass``
        (kg, >= 0), ``radius`` (m, >= 0), ``angle`` (deg), ``z`` (m, default 0), or
        tuples ``(mass, radius, angle[, z])``. At least one.
    planes : iterable
        One or two correction planes: :class:`CorrectionPlane`, dicts ``{z, radius}``
        or tuples ``(z, radius)``; ``radius`` > 0 is where the mass is fixed.
    speed_rpm : float, optional
        Speed (rpm, > 0). With it, forces and moments are in N and N m (U omega^2);
        without, the magnitudes are unbalances in kg m and kg m^2.
    units : Units, optional
        The scene's units, in which the messages quote lengths and unbalances (the
        numbers given and returned stay SI).

    Returns
    -------
    RotorResult
        Corrections (mass 0 and angle 0 for a zero correction) and the force and
        moment (about z = 0) before and after correction.

    Raises
    ------
    BalanceError
        No unbalance, a number of planes other than one or two, coincident
        correction planes, a negative mass or radius.

    Warns
    -----
    BalanceWarning
        Each entry of the result's ``warnings``: two correction planes closer than
        :data:`CLOSE_PLANES` of the rotor's axial extent; corrections whose total
        exceeds :data:`LARGE_CORRECTION` times the total unbalance.

    Examples
    --------
    >>> r = balance_rotor([(0.02, 0.1, 30.0, 0.05), (0.015, 0.12, 150.0, 0.15)],
    ...                   [(0.0, 0.12), (0.3, 0.12)])
    >>> round(r.residual_force, 15)
    0.0
    """
    ub = [_as_unbalance(u, k) for k, u in enumerate(unbalances)]
    pl = [_as_plane(p, k) for k, p in enumerate(planes)]
    if not ub:
        raise BalanceError("rotor: no unbalance given; list at least one eccentric mass")
    if len(pl) not in (1, 2):
        raise BalanceError(f"rotor: {len(pl)} correction planes given; give one (static "
                           "balancing) or two (dynamic balancing)")
    if speed_rpm is not None:
        speed_rpm = check_number(speed_rpm, "rotor: speed_rpm", positive=True)

    m = np.array([u.mass for u in ub])
    r = np.array([u.radius for u in ub])
    th = radian_column([u.angle for u in ub])
    z = np.array([u.z for u in ub])
    U = m * r * np.exp(1j * th)                  # eq. 3.3: U_j = m_j r_j
    Ud = complex(U.sum())                        # eq. 3.3: total unbalance U_d
    Mz = complex((z * U).sum())                  # eqs 3.11-3.12 about z = 0 (k x omitted)
    size = float(np.abs(U).sum())

    if len(pl) == 1:
        Ue = [-Ud]                               # eqs 3.6, 3.8: U_e = -U_d
        tol = _ZERO_TOL * size
    else:
        z1, z2 = pl[0].z, pl[1].z
        dz = z2 - z1
        extent = max(abs(z1), abs(z2), float(np.abs(z - z1).max()), float(np.abs(z - z2).max()))
        if dz == 0.0 or abs(dz) <= _COINCIDENT_TOL * extent:
            u = units or Units()
            # the fewest digits that tell the two apart (the same when they are equal)
            digits = next((p for p in range(6, 17) if format(u.from_si(z1, "length"), f".{p}g")
                           != format(u.from_si(z2, "length"), f".{p}g")), 6)
            raise BalanceError(f"rotor: correction planes 1 and 2 coincide (z = "
                               f"{format(u.from_si(z1, 'length'), f'.{digits}g')} and "
                               f"{u.quote(z2, 'length', f'.{digits}g')}); two-plane balancing "
                               "needs planes at different z")
        Ue2 = -complex(((z - z1) * U).sum()) / dz  # eqs 3.12-3.13: moments about plane I
        Ue1 = -Ud - Ue2                            # eqs 3.10, 3.14: force balance
        Ue = [Ue1, Ue2]
        lever = float(((np.abs(z - z1) + np.abs(z - z2)) * np.abs(U)).sum()) / abs(dz)
        tol = _ZERO_TOL * (size + lever)

    corrections = tuple(_correction(k, p, ue, tol) for k, (p, ue) in enumerate(zip(pl, Ue,
                                                                                   strict=True)))
    notes = _conditioning(pl, z, corrections, size, units or Units())
    Ue_applied = np.array([c.vector for c in corrections])
    ze = np.array([p.z for p in pl])
    res_F = Ud + complex(Ue_applied.sum())                  # eq. 3.9 / 3.4 left-hand side
    res_M = Mz + complex((ze * Ue_applied).sum())           # eq. 3.11 about z = 0
    w2 = (speed_rpm * RPM_TO_RAD_S) ** 2 if speed_rpm is not None else 1.0  # eq. 3.5: U w^2
    return RotorResult(
        corrections=corrections,
        initial_force=abs(Ud) * w2,
        initial_moment=abs(Mz) * w2,
        residual_force=abs(res_F) * w2,
        residual_moment=abs(res_M) * w2,
        speed_rpm=speed_rpm,
        unbalances=U,
        z=z,
        warnings=notes,
    )


def _conditioning(pl: list[CorrectionPlane], z: np.ndarray, corrections: tuple[Correction, ...],
                  size: float, units: Units) -> tuple[str, ...]:
    """Warnings, with their numbers in the scene's ``units``, where the corrections are not
    to be trusted; each is also issued as a BalanceWarning."""
    notes = []
    if len(pl) == 2:
        z1, z2 = pl[0].z, pl[1].z
        extent = max(z.max(), z1, z2) - min(z.min(), z1, z2)
        if abs(z2 - z1) < CLOSE_PLANES * extent:
            notes.append(f"rotor: the correction planes are "
                         f"{units.quote(abs(z2 - z1), 'length', '.3g')} apart, "
                         f"{abs(z2 - z1) / extent:.2g} of the rotor's axial extent "
                         f"{units.quote(extent, 'length', '.3g')} (under {CLOSE_PLANES:g}): "
                         "the couple is corrected by a short lever and the corrections grow "
                         "as extent / distance; place the planes further apart")
    total = sum(c.U for c in corrections)
    if size > 0.0 and total > LARGE_CORRECTION * size:
        notes.append(f"rotor: the corrections total {_unbalance(total, units)}, "
                     f"{total / size:.3g} times the unbalance they balance "
                     f"({_unbalance(size, units, '.4g')}): check the planes' positions and "
                     "radii")
    for note in notes:
        warnings.warn(note, BalanceWarning, stacklevel=3)
    return tuple(notes)


def _unbalance(value: float, units: Units, spec: str = ".4g") -> str:
    """An unbalance (kg m) in the scene's unit: its ``unbalance`` unit when it names one,
    else its mass unit times its length unit (``"g mm"``)."""
    if getattr(units, "unbalance", "kg m") != "kg m":
        return units.quote(value, "unbalance", spec)
    f = units.factor("mass") * units.factor("length")
    return f"{format(value / f, spec)} {units.mass} {units.length}"
