"""Followers, the transmission angle, the base circle and the profile of a cam (seed 002
s. 1.3-1.4, eqs 1.27-1.38).
"""

from __future__ import annotations

import math
from dataclasses import InitVar, dataclass
from typing import Any

import numpy as np
import pandas as pd

from ..common.angles import degree_column
from ..model.units import Units
from ..motion import golden_max
from .laws import (
    SAMPLES,
    CamError,
    CamLaw,
    cycle_extreme,
)

# --------------------------------------------------------------------------- followers

SI = Units()
"""The contract's units: the messages' when no scene's are told."""


def _len(x: float, units: Units | None) -> str:
    """A length (m) for a message, in the scene's unit (SI without one)."""
    return (units or SI).quote(x, "length")


def _roller_check(rr: float, r0: float, units: Units | None) -> None:
    if not 0.0 <= rr < r0:
        raise CamError(f"the roller radius {_len(rr, units)} must lie in [0, base radius "
                       f"{_len(r0, units)})")


@dataclass(frozen=True)
class TranslatingFollower:
    """A translating follower (fig. 1.10): base radius r0, offset e, roller radius (m).

    ``units`` (not kept) only says the messages' unit: the scene's, SI without one."""

    base_radius: float
    offset: float = 0.0
    roller_radius: float = 0.0
    units: InitVar[Units | None] = None

    def __post_init__(self, units: Units | None) -> None:
        r0, e, rr = self.base_radius, self.offset, self.roller_radius
        if not (math.isfinite(r0) and math.isfinite(e) and math.isfinite(rr)):
            raise CamError("base radius, offset and roller radius must be finite numbers")
        if r0 <= abs(e):
            raise CamError(f"the base radius {_len(r0, units)} must exceed the offset |e| = "
                           f"{_len(abs(e), units)} (eq. 1.27: s0 = sqrt(r0^2 - e^2))")
        _roller_check(rr, r0, units)

    @property
    def s0(self) -> float:
        """Height of B above A on the base circle, s0 = sqrt(r0^2 - e^2) (eq. 1.27)."""
        return math.sqrt(self.base_radius**2 - self.offset**2)


@dataclass(frozen=True)
class OscillatingFollower:
    """An oscillating follower (fig. 1.12): base radius r0, arm L = CB, pivot distance d = AC.

    ``units`` (not kept) only says the messages' unit: the scene's, SI without one."""

    base_radius: float
    arm: float
    pivot_distance: float
    roller_radius: float = 0.0
    rise_sense: str = "same"
    units: InitVar[Units | None] = None

    def __post_init__(self, units: Units | None) -> None:
        r0, L, d, rr = self.base_radius, self.arm, self.pivot_distance, self.roller_radius
        if not all(math.isfinite(v) for v in (r0, L, d, rr)):
            raise CamError("base radius, arm, pivot distance and roller radius must be finite")
        if L <= 0.0 or d <= 0.0:
            raise CamError("the arm and the pivot distance must be positive")
        if not abs(d - L) < r0 < d + L:
            raise CamError(f"no triangle A-B0-C with r0 = {_len(r0, units)}, arm "
                           f"{_len(L, units)} and pivot distance {_len(d, units)}: r0 must lie "
                           f"in ({_len(abs(d - L), units)}, {_len(d + L, units)}) (eq. 1.35)")
        _roller_check(rr, r0, units)
        if self.rise_sense not in ("same", "opposite"):
            raise CamError(f"rise_sense must be 'same' or 'opposite', not {self.rise_sense!r}")

    @property
    def beta0(self) -> float:
        """Angle at C between CA and CB0 on the base circle, from eq. 1.35 (rad)."""
        L, d, r0 = self.arm, self.pivot_distance, self.base_radius
        return math.acos(np.clip((d * d + L * L - r0 * r0) / (2.0 * d * L), -1.0, 1.0))


Follower = TranslatingFollower | OscillatingFollower


def cross2(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[0] * b[1] - a[1] * b[0]


def perp(a: np.ndarray) -> np.ndarray:
    """J a: a turned +90 deg."""
    return np.stack((-a[1], a[0]))


def follower_points(follower: Follower, s: np.ndarray, ds: np.ndarray, dds: np.ndarray,
            beta0: float | None = None) -> tuple[np.ndarray, ...]:
    """B, dB/dphi, d2B/dphi2, the rise direction u of B and the speed of B along it per unit
    cam angle, in the fixed frame of a counter-clockwise cam (arrays of shape (2, n))."""
    s, ds, dds = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (s, ds, dds)))
    if isinstance(follower, TranslatingFollower):
        zero, one = np.zeros_like(s), np.ones_like(s)
        b = np.stack((np.full_like(s, follower.offset), follower.s0 + s))
        return b, np.stack((zero, ds)), np.stack((zero, dds)), np.stack((zero, one)), ds
    sig = 1.0 if follower.rise_sense == "same" else -1.0
    b0 = follower.beta0 if beta0 is None else beta0     # may be an array broadcasting with s
    L, d = follower.arm, follower.pivot_distance
    th = math.pi + sig * (b0 + s)
    c, sn = np.cos(th), np.sin(th)
    b = np.stack((d + L * c, L * sn))
    t = np.stack((-sn, c))
    d1 = L * sig * ds * t
    d2 = L * sig * dds * t - L * ds * ds * np.stack((c, sn))
    return b, d1, d2, sig * t, L * ds


def tau_of(b: np.ndarray, d1: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Transmission angle (rad, [0, pi/2]): between the relative sliding direction
    T = dB/dphi - J B and the follower's direction of motion (eqs 1.28, 1.34)."""
    t = d1 - perp(b)
    return np.arctan2(np.abs(cross2(t, u)), np.abs(np.sum(t * u, axis=0)))


def transmission_angle(law: CamLaw, follower: Follower, phi: Any) -> np.ndarray:
    """Transmission angle tau (rad, in (0, pi/2]) at cam angles ``phi`` (eqs 1.28, 1.34).

    Translating follower (eq. 1.28): tan tau = (s + s0) / |ds/dphi - e|; oscillating
    follower (eq. 1.34): tan tau = AC sin(beta0 + beta) /
    |L dbeta/dphi - (L - AC cos(beta0 + beta))| for ``rise_sense = "same"`` (with
    + (L - AC cos) for ``"opposite"``). Computed from the vectors of the mechanism: the
    angle between the relative sliding direction of the follower point on the cam and the
    follower's direction of motion. The pressure angle is pi/2 - tau.
    """
    b, d1, _, u, _ = follower_points(follower, *law(phi))
    return tau_of(b, d1, u)


def base_radius_translating(law: CamLaw, tau_adm: float, offset: float = 0.0) -> float:
    """Smallest base radius r0 that keeps tau >= tau_adm over the cycle (eq. 1.29).

    From tan tau_adm <= (s + s0) / |ds/dphi - e| at every angle: s0 = sup(|ds/dphi - e|
    tan tau_adm - s), r0 = sqrt(s0^2 + e^2) (eq. 1.27). The analytic form of the seed's
    graphical construction (fig. 1.11) for a given offset.

    Parameters
    ----------
    law : CamLaw
    tau_adm : float
        Admissible transmission angle, rad, in (0, pi/2) (the seed gives 45-75 deg).
    offset : float
        e, m (sign as in the module's conventions).
    """
    check_tau(tau_adm)
    s0 = _s0_required(law, tau_adm, offset)
    if s0 <= 0.0:
        raise CamError("every base radius keeps the transmission angle admissible for this "
                       "law and offset; give the base radius instead")
    return math.hypot(s0, offset)


def check_tau(tau_adm: float, units: Units | None = None) -> None:
    """Refuse an admissible transmission angle (rad) outside (0, 90) deg, quoted in the
    scene's ``units`` (degrees without)."""
    if not (0.0 < tau_adm < 0.5 * math.pi):
        raise CamError(f"the admissible transmission angle must lie in (0, "
                       f"{_angle(0.5 * math.pi, units)}), got {_angle(tau_adm, units)}")


def _angle(rad: float, units: Units | None) -> str:
    """An angle (rad) for a message, in the scene's unit (degrees without one)."""
    return (units or SI).quote(rad, "angle")


def _s0_required(law: CamLaw, tau_adm: float, offset: float) -> float:
    k = math.tan(tau_adm)
    return cycle_extreme(law, lambda p, s, ds, dds: np.abs(ds - offset) * k - s)[0]


def optimal_offset(law: CamLaw, tau_adm: float) -> tuple[float, float]:
    """Offset e and base radius r0 of the smallest cam that keeps tau >= tau_adm.

    The seed's construction (fig. 1.11) puts the cam centre at the intersection of the two
    lines du and dc; analytically r0(e) = sqrt(s0(e)^2 + e^2) with s0(e) of eq. 1.29 is
    convex in e and is minimised here by golden-section search over e between the least
    and the largest ds/dphi.

    Returns
    -------
    (offset, base_radius) : tuple of float, m
    """
    check_tau(tau_adm)
    lo = cycle_extreme(law, lambda p, s, ds, dds: -ds)[0]
    hi = cycle_extreme(law, lambda p, s, ds, dds: ds)[0]

    def neg_r0(e: float) -> float:
        return -math.hypot(max(_s0_required(law, tau_adm, e), 0.0), e)

    e, r = golden_max(neg_r0, -lo, hi, xtol=1e-10 * max(hi + lo, 1e-300))
    return e, -r


def base_radius_oscillating(law: CamLaw, tau_adm: float, arm: float, pivot_distance: float,
                            rise_sense: str = "same", units: Units | None = None) -> float:
    """Smallest base radius r0 of an oscillating-follower cam with tau >= tau_adm (eq. 1.36).

    r0 follows from beta0 by eq. 1.35 and grows with it; the smallest beta0 that satisfies
    eq. 1.36 at every cam angle is found by a scan over (0, pi - beta_max) and bisection.
    The seed advises tau_adm = 25 deg for oscillating followers.

    Parameters
    ----------
    law : CamLaw
        Its stroke is the swing angle beta (rad).
    tau_adm : float
        Admissible transmission angle, rad.
    arm, pivot_distance : float
        L = CB and d = AC, m.
    rise_sense : {"same", "opposite"}
    units : Units, optional
        The scene's units, in which the messages quote lengths and angles (SI without).
    """
    check_tau(tau_adm, units)
    if arm <= 0.0 or pivot_distance <= 0.0:
        raise CamError("the arm and the pivot distance must be positive")
    if law.stroke >= math.pi:
        raise CamError(f"the follower's swing must be below "
                       f"{(units or SI).quote(math.pi, 'angle')}")
    key = (law, float(tau_adm), float(arm), float(pivot_distance), rise_sense)
    if key not in _BASE_RADII:
        if len(_BASE_RADII) >= 256:
            _BASE_RADII.clear()
        _BASE_RADII[key] = _smallest_base_radius(law, tau_adm, arm, pivot_distance, rise_sense,
                                                 units)
    return _BASE_RADII[key]


# r0 of every (law, tau_adm, L, d, sense) sized so far: reading the same scene again (the
# tests, a notebook's slider, a class's scenes) asks for it again; a refusal is not kept
_BASE_RADII: dict[tuple, float] = {}


def _smallest_base_radius(law: CamLaw, tau_adm: float, arm: float, pivot_distance: float,
                          rise_sense: str, units: Units | None) -> float:
    """:func:`base_radius_oscillating` for checked arguments (eqs 1.35-1.36)."""
    probe = OscillatingFollower(0.5 * (abs(pivot_distance - arm) + pivot_distance + arm), arm,
                                pivot_distance, rise_sense=rise_sense)

    def margin(beta0: float) -> float:
        def f(p: np.ndarray, s: np.ndarray, ds: np.ndarray, dds: np.ndarray) -> np.ndarray:
            b, d1, _, u, _ = follower_points(probe, s, ds, dds, beta0=beta0)
            return -tau_of(b, d1, u)
        return -cycle_extreme(law, f)[0] - tau_adm

    # scan beta0 over (0, pi - beta_max) on sampled cam angles (vectorised), then bisect
    # with the refined minimum of tau
    x = [np.linspace(0.0, seg.angle, SAMPLES) for seg in law.segments]
    vals = [np.concatenate(v) for v in zip(*(law.segment_values(k, xk)
                                             for k, xk in enumerate(x)), strict=True)]
    grid = np.linspace(0.0, math.pi - law.stroke, 362)[1:-1]
    b, d1, _, u, _ = follower_points(probe, *vals, beta0=grid[:, None])
    ok = np.min(tau_of(b, d1, u), axis=1) >= tau_adm
    if not np.any(ok):
        raise CamError(f"no base radius keeps tau >= {_angle(tau_adm, units)} with arm "
                       f"{_len(arm, units)} and pivot distance {_len(pivot_distance, units)}; "
                       "change them")
    i = int(np.argmax(ok))
    lo, hi = (0.0 if i == 0 else grid[i - 1]), grid[i]
    while margin(hi) < 0.0:           # the sampled minimum may miss a sharp dip
        lo, hi = hi, hi + 0.25 * (hi - lo)
        if hi >= math.pi - law.stroke:
            raise CamError(f"no base radius keeps tau >= {_angle(tau_adm, units)} with "
                           f"arm {_len(arm, units)} and pivot distance "
                           f"{_len(pivot_distance, units)}")
    while hi - lo > 1e-12:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if margin(mid) >= 0.0 else (mid, hi)
    d, L = pivot_distance, arm
    return math.sqrt(d * d + L * L - 2.0 * d * L * math.cos(hi))


# --------------------------------------------------------------------------- profile

def _mirror(follower: Follower, x: np.ndarray, y: np.ndarray,
            rotation: str) -> tuple[np.ndarray, np.ndarray]:
    if rotation == "ccw":
        return x, y
    if rotation != "cw":
        raise CamError(f"rotation must be 'ccw' or 'cw', not {rotation!r}")
    return (-x, y) if isinstance(follower, TranslatingFollower) else (x, -y)


def profile(law: CamLaw, follower: Follower, phi: Any, rotation: str = "ccw") -> pd.DataFrame:
    """The cam's profiles at cam angles ``phi`` (rad), in the cam's own frame (eqs 1.37-1.38).

    The cam frame coincides with the fixed frame at phi = 0. The theoretical (pitch) profile
    is the path of B: P = R(-phi) B(phi) for a counter-clockwise cam (the seed's
    construction: turn AB_i back by phi_i, s. 1.3.7). The outward normal n of the pitch
    curve gives the working profile P - r n (inner envelope of the roller) and P + r n.

    Returns
    -------
    pandas.DataFrame
        ``angle`` (deg), ``x_pitch, y_pitch, x_profile, y_profile, x_outer, y_outer`` (m),
        ``radius`` (|AP|, m) and ``curvature`` of the pitch curve (1/m, positive where it is
        convex; the working profile is undercut where curvature > 1 / roller radius).
    """
    phi = np.asarray(phi, dtype=float)
    s, ds, dds = law(phi)
    b, d1, d2, _, _ = follower_points(follower, s, ds, dds)
    t = d1 - perp(b)
    w = d2 - 2.0 * perp(d1) - b
    tn = np.hypot(t[0], t[1])
    c, sn = np.cos(phi), np.sin(phi)

    def back(v: np.ndarray) -> np.ndarray:      # R(-phi) v
        return np.stack((c * v[0] + sn * v[1], -sn * v[0] + c * v[1]))

    p = back(b)
    n = back(perp(t) / tn)
    rr = follower.roller_radius
    cols: dict[str, np.ndarray] = {"angle": degree_column(phi)}
    for name, pt in (("pitch", p), ("profile", p - rr * n), ("outer", p + rr * n)):
        x, y = _mirror(follower, pt[0], pt[1], rotation)
        cols[f"x_{name}"], cols[f"y_{name}"] = x, y
    cols["radius"] = np.hypot(p[0], p[1])
    cols["curvature"] = -cross2(t, w) / tn**3
    return pd.DataFrame(cols)


def polar_profile_translating(phi: Any, s: Any, base_radius: float,
                              offset: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Polar coordinates of the pitch profile for a translating follower, eq. 1.37 as printed.

    r_i = sqrt((s0 + s_i)^2 + e^2), theta_i = phi_i - arctan(e s_i / (e^2 + (s0 + s_i) s0)),
    theta measured from A B0 against the sense of rotation (the upper sign of the seed's
    "-+" for a positive offset in this module's convention).
    """
    s = np.asarray(s, dtype=float)
    e = offset
    s0 = math.sqrt(base_radius**2 - e * e)
    return np.sqrt((s0 + s) ** 2 + e * e), np.asarray(phi) - np.arctan(
        e * s / (e * e + (s0 + s) * s0))


def polar_profile_oscillating(phi: Any, beta: Any, base_radius: float, arm: float,
                              pivot_distance: float) -> tuple[np.ndarray, np.ndarray]:
    """Polar coordinates of the pitch profile for an oscillating follower, eq. 1.38 as printed.

    r_i = sqrt(AC^2 + BC^2 - 2 AC BC cos(beta0 + beta_i)),
    theta_i = phi_i - [arcsin(BC sin(beta0)/r0) - arcsin(BC sin(beta0 + beta_i)/r_i)],
    theta measured from A B0 against the sense of rotation (``rise_sense = "same"``). The
    arcsines assume the angle at A of the triangle A B C stays acute.
    """
    beta = np.asarray(beta, dtype=float)
    d, L, r0 = pivot_distance, arm, base_radius
    b0 = math.acos((d * d + L * L - r0 * r0) / (2.0 * d * L))
    r = np.sqrt(d * d + L * L - 2.0 * d * L * np.cos(b0 + beta))
    th = np.asarray(phi) - (math.asin(L / r0 * math.sin(b0)) - np.arcsin(L / r * np.sin(b0 + beta)))
    return r, th
