"""Cam mechanisms (seed 002 ch. 1): motion laws, base circle, profile, follower forces.

Conventions (the workbench's: SI units, angles in degrees in files and tables, radians in
the Python functions below unless a name ends in ``_deg``):

- The cam turns about A at the origin with a constant speed omega; ``phi`` is its angle of
  rotation from the start of the program (the start of the first segment). The geometry
  is worked out for a counter-clockwise cam; a clockwise cam is the mirror image (the
  profile's coordinates are mirrored, every angle and force is the same).
- Motion laws give the follower's lift ``s`` (m for a translating follower, rad for an
  oscillating one) and its derivatives with respect to the cam angle: ``ds = v / omega``
  and ``dds = a / omega^2`` (the seed's v/omega and a/omega^2, eqs 1.2-1.3).
- Translating follower (fig. 1.10): its axis is the line x = e, the follower point B (the
  knife edge or the roller centre) is at (e, s0 + s) with s0 = sqrt(r0^2 - e^2) (eq. 1.27).
  The offset e is positive on the side where the cam's surface moves in the follower's
  rise direction: a positive offset lowers the pressure angle during the rise.
- Oscillating follower (fig. 1.12): pivot C at (d, 0) (d = AC, ``pivot_distance``), arm
  L = CB (``arm``), psi = beta0 + beta the angle at C between CA and CB, r0 from eq. 1.35.
  ``rise_sense = "same"`` (the seed's figure: eqs 1.34 and 1.38 hold as printed) when the
  arm turns in the cam's sense of rotation while it rises, ``"opposite"`` otherwise.
- r0 is the base radius of the theoretical (pitch) profile, the path of B in the cam's
  frame (eq. 1.37: "the theoretical profile passes through the roller centre"). The
  working profile of a roller follower is the inner envelope of the roller (offset of the
  pitch curve by the roller radius along its normal); the outer envelope is also given
  (the outer wall of a groove cam).
- The transmission angle tau (between the contact normal and the follower's direction of
  motion's normal, eqs 1.28/1.34) is reported in (0, 90] deg; the pressure angle is
  90 deg - tau (alpha + tau = 90 deg, s. 1.3.5).

The ``[cam]`` scene (``docs/cam-scenes.md``) is loaded by :func:`load_cam_scene` and
solved by :func:`solve_cam`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from ..model.errors import WorkbenchError
from ..model.tomlio import as_float, as_int, as_list, as_str, check_keys, read_source, suggest
from ..motion import golden_max
from ..topics.efficiency import mean_efficiency

TWO_PI = 2.0 * math.pi
_SAMPLES = 801          # samples per segment when an extreme over the cycle is searched


class CamError(WorkbenchError):
    """A cam problem that cannot be solved as posed (bad law, no base radius, self-locking)."""


# --------------------------------------------------------------------------- motion laws

LawValues = tuple[np.ndarray, np.ndarray, np.ndarray]


def _phase(phi: Any, stroke: float, span: float, name: str) -> np.ndarray:
    if not (math.isfinite(span) and span > 0.0):
        raise CamError(f"{name}: the phase angle must be positive, got {span!r} rad")
    if not math.isfinite(stroke):
        raise CamError(f"{name}: the stroke must be a finite number, got {stroke!r}")
    x = np.asarray(phi, dtype=float)
    tol = 1e-9 * span
    if x.size and (np.nanmin(x) < -tol or np.nanmax(x) > span + tol or np.isnan(x).any()):
        raise CamError(f"{name}: cam angles must lie in the phase [0, {math.degrees(span):g}] "
                       "deg (measured from its start)")
    return np.clip(x, 0.0, span)


def zero_acceleration(phi: Any, stroke: float, span: float) -> LawValues:
    """Rise with zero acceleration (constant velocity), eqs 1.1-1.4.

    s = h phi / phi_u, ds/dphi = h / phi_u, d2s/dphi2 = 0 (the velocity jumps at both ends:
    theoretically infinite accelerations, hard shocks, s. 1.3.1).

    Parameters
    ----------
    phi : array_like
        Cam angle from the start of the rise, rad, in [0, span].
    stroke : float
        The stroke h (m, or rad for an oscillating follower).
    span : float
        The rise angle phi_u, rad.

    Returns
    -------
    s, ds, dds : numpy.ndarray
        Lift, ds/dphi (= v/omega) and d2s/dphi2 (= a/omega^2).
    """
    x = _phase(phi, stroke, span, "zero-acceleration law")
    return stroke * x / span, np.full_like(x, stroke / span), np.zeros_like(x)


def constant_acceleration(phi: Any, stroke: float, span: float) -> LawValues:
    """Rise with constant acceleration (parabolic), eqs 1.5-1.9.

    First half (eq. 1.8): s = 2h phi^2/phi_u^2, ds = 4h phi/phi_u^2, dds = 4h/phi_u^2;
    second half (eq. 1.9): s = h - 2h (phi_u - phi)^2/phi_u^2, ds = 4h (phi_u - phi)/phi_u^2,
    dds = -4h/phi_u^2. At the middle the acceleration of the first half is returned.

    Parameters and returns as :func:`zero_acceleration`.
    """
    x = _phase(phi, stroke, span, "constant-acceleration law")
    c = 4.0 * stroke / span**2
    first = x <= 0.5 * span
    y = span - x
    s = np.where(first, 0.5 * c * x * x, stroke - 0.5 * c * y * y)
    ds = np.where(first, c * x, c * y)
    dds = np.where(first, c, -c)
    return s, ds, dds


def cosine_acceleration(phi: Any, stroke: float, span: float) -> LawValues:
    """Rise with cosine acceleration (harmonic), eqs 1.10-1.13.

    s = h/2 (1 - cos(pi phi/phi_u)), ds = pi h/(2 phi_u) sin(pi phi/phi_u),
    dds = pi^2 h/(2 phi_u^2) cos(pi phi/phi_u); peaks in eq. 1.14.

    Parameters and returns as :func:`zero_acceleration`.
    """
    x = _phase(phi, stroke, span, "cosine-acceleration law")
    k = math.pi / span
    return (0.5 * stroke * (1.0 - np.cos(k * x)), 0.5 * stroke * k * np.sin(k * x),
            0.5 * stroke * k * k * np.cos(k * x))


def sine_acceleration(phi: Any, stroke: float, span: float) -> LawValues:
    """Rise with sine acceleration (cycloidal), eqs 1.17-1.20.

    s = h (phi/phi_u - sin(2 pi phi/phi_u)/(2 pi)), ds = h/phi_u (1 - cos(2 pi phi/phi_u)),
    dds = 2 pi h/phi_u^2 sin(2 pi phi/phi_u); peaks in eq. 1.21.

    Parameters and returns as :func:`zero_acceleration`.
    """
    x = _phase(phi, stroke, span, "sine-acceleration law")
    k = TWO_PI / span
    return (stroke * (x / span - np.sin(k * x) / TWO_PI), stroke / span * (1.0 - np.cos(k * x)),
            stroke * k / span * np.sin(k * x))


LAWS: dict[str, Callable[[Any, float, float], LawValues]] = {
    "zero-acceleration": zero_acceleration,
    "constant-acceleration": constant_acceleration,
    "cosine-acceleration": cosine_acceleration,
    "sine-acceleration": sine_acceleration,
}
ALIASES = {"constant-velocity": "zero-acceleration", "parabolic": "constant-acceleration",
           "harmonic": "cosine-acceleration", "cycloidal": "sine-acceleration"}

#: Peak coefficients (C_v, C_a): max ds/dphi = C_v h/phi_u, max |d2s/dphi2| = C_a h/phi_u^2.
#: zero-acceleration: eq. 1.4 (the end impulses are not counted); constant-acceleration:
#: eqs 1.8-1.9; cosine-acceleration: eq. 1.14; sine-acceleration: eq. 1.21.
LAW_COEFFICIENTS: dict[str, tuple[float, float]] = {
    "zero-acceleration": (1.0, 0.0),
    "constant-acceleration": (2.0, 4.0),
    "cosine-acceleration": (0.5 * math.pi, 0.5 * math.pi**2),
    "sine-acceleration": (2.0, TWO_PI),
}


def law_name(name: str) -> str:
    """The canonical name of a motion law (aliases: constant-velocity, parabolic, harmonic,
    cycloidal); a :class:`CamError` naming the nearest known name otherwise."""
    key = str(name).strip().lower().replace("_", "-").replace(" ", "-")
    if key in LAWS:
        return key
    if key in ALIASES:
        return ALIASES[key]
    known = list(LAWS) + list(ALIASES)
    raise CamError(f"unknown motion law {name!r}{suggest(key, known)}; known: {', '.join(known)}")


def rise(law: str, phi: Any, stroke: float, span: float) -> LawValues:
    """The rise phase of a law (eqs 1.4, 1.8-1.9, 1.13, 1.20); ``phi`` from the rise's start."""
    return LAWS[law_name(law)](phi, stroke, span)


def fall(law: str, phi: Any, stroke: float, span: float) -> LawValues:
    """The return phase (eqs 1.15, 1.22): s_c = h - s_u, the rise law run downwards.

    The seed obtains it from eqs 1.5-1.7, 1.10-1.12 and 1.17-1.19 with the boundary
    conditions of the return (s = h, v = 0 at its start; s = 0, v = 0 at its end), which
    gives h minus the rise law of the same angle; ``phi`` is measured from the return's start.
    """
    s, ds, dds = rise(law, phi, stroke, span)
    return stroke - s, -ds, -dds


def law_peaks(law: str, stroke: float, span: float) -> tuple[float, float]:
    """Peak |ds/dphi| and |d2s/dphi2| of a rise or return of angle ``span`` (eqs 1.14, 1.21).

    Multiply by omega and omega^2 for the peak velocity and acceleration (m/s, m/s^2).
    """
    cv, ca = LAW_COEFFICIENTS[law_name(law)]
    return cv * abs(stroke) / span, ca * abs(stroke) / span**2


# --------------------------------------------------------------------------- programs

@dataclass(frozen=True)
class Segment:
    """One phase of the follower's program: ``kind`` rise, dwell or return; ``angle`` (rad)."""

    kind: str
    angle: float
    law: str | None = None


@dataclass(frozen=True)
class CamLaw:
    """A full cycle of the follower: segments (rise, dwell, return, dwell, ...) over 360 deg.

    The lift starts at 0 (the base circle); a rise takes it to ``stroke``, a return back
    to 0, a dwell keeps it. The segments' angles add up to 2 pi. Evaluate with
    ``law(phi) -> (s, ds, dds)`` at any cam angles (rad, wrapped to the cycle).

    Parameters
    ----------
    stroke : float
        h, m (translating follower) or rad (oscillating follower: the swing beta).
    segments : sequence of Segment
    """

    stroke: float
    segments: tuple[Segment, ...]

    def __post_init__(self) -> None:
        if not (math.isfinite(self.stroke) and self.stroke > 0.0):
            raise CamError(f"the stroke must be positive, got {self.stroke!r}")
        segs = tuple(self.segments)
        if not segs:
            raise CamError("a cam program needs at least one segment")
        level, fixed = 0, []
        for i, seg in enumerate(segs, 1):
            if seg.kind not in ("rise", "dwell", "return"):
                raise CamError(f"segment {i}: kind must be rise, dwell or return, "
                               f"not {seg.kind!r}{suggest(seg.kind, ('rise', 'dwell', 'return'))}")
            if not (math.isfinite(seg.angle) and seg.angle > 0.0):
                raise CamError(f"segment {i}: the angle must be positive")
            if seg.kind == "dwell":
                fixed.append(Segment("dwell", float(seg.angle)))
                continue
            if seg.law is None:
                raise CamError(f"segment {i} ({seg.kind}) needs a motion law")
            want = 0 if seg.kind == "rise" else 1
            if level != want:
                where = "at the top" if level else "on the base circle"
                raise CamError(f"segment {i}: a {seg.kind} cannot start {where}; rises and "
                               "returns must alternate, starting with a rise")
            level = 1 - level
            fixed.append(Segment(seg.kind, float(seg.angle), law_name(seg.law)))
        if level != 0:
            raise CamError("the program ends at the top: add a return so the cycle closes")
        total = sum(seg.angle for seg in fixed)
        if abs(total - TWO_PI) > 1e-9 * TWO_PI:
            raise CamError(f"the segments' angles add up to {math.degrees(total):.6g} deg, "
                           "not 360")
        object.__setattr__(self, "segments", tuple(fixed))

    @classmethod
    def cycle(cls, stroke: float, rise_law: str, rise_deg: float, return_law: str,
              return_deg: float, top_dwell_deg: float = 0.0,
              bottom_dwell_deg: float | None = None) -> CamLaw:
        """The classic program rise - top dwell - return - bottom dwell (fig. 1.3), in degrees.

        ``bottom_dwell_deg`` defaults to what is left of 360 deg.
        """
        if bottom_dwell_deg is None:
            bottom_dwell_deg = 360.0 - rise_deg - top_dwell_deg - return_deg
        segs = [Segment("rise", math.radians(rise_deg), rise_law)]
        if top_dwell_deg:
            segs.append(Segment("dwell", math.radians(top_dwell_deg)))
        segs.append(Segment("return", math.radians(return_deg), return_law))
        if bottom_dwell_deg:
            segs.append(Segment("dwell", math.radians(bottom_dwell_deg)))
        return cls(stroke, tuple(segs))

    @property
    def starts(self) -> np.ndarray:
        """Cam angle (rad) where each segment starts."""
        return np.concatenate(([0.0], np.cumsum([s.angle for s in self.segments])[:-1]))

    def segment_values(self, k: int, x: Any) -> LawValues:
        """Lift and derivatives of segment ``k`` at angles ``x`` from its start (closed ends)."""
        seg = self.segments[k]
        x = np.asarray(x, dtype=float)
        if seg.kind == "dwell":
            level = self.stroke if sum(g.kind == "rise" for g in self.segments[:k]) > sum(
                g.kind == "return" for g in self.segments[:k]) else 0.0
            return np.full_like(x, level), np.zeros_like(x), np.zeros_like(x)
        if seg.kind == "rise":
            return rise(seg.law, x, self.stroke, seg.angle)
        return fall(seg.law, x, self.stroke, seg.angle)

    def __call__(self, phi: Any) -> LawValues:
        """Lift s, ds/dphi and d2s/dphi2 at cam angles ``phi`` (rad, any values: wrapped)."""
        phi = np.asarray(phi, dtype=float)
        x = np.mod(phi, TWO_PI)
        starts = self.starts
        k = np.clip(np.searchsorted(starts, x, side="right") - 1, 0, len(starts) - 1)
        s, ds, dds = (np.empty_like(x) for _ in range(3))
        for i in range(len(self.segments)):
            m = k == i
            if np.any(m):
                local = np.minimum(x[m] - starts[i], self.segments[i].angle)
                s[m], ds[m], dds[m] = self.segment_values(i, local)
        return s, ds, dds

    def peaks(self) -> pd.DataFrame:
        """One row per segment: ``segment, kind, law, start, angle`` (deg) and the peaks
        ``ds_max``, ``dds_max`` of eqs 1.14 / 1.21 (0 for a dwell)."""
        rows = []
        for i, (seg, c) in enumerate(zip(self.segments, self.starts, strict=True), 1):
            v, a = (0.0, 0.0) if seg.kind == "dwell" else law_peaks(seg.law, self.stroke,
                                                                     seg.angle)
            rows.append({"segment": i, "kind": seg.kind, "law": seg.law or "",
                         "start": math.degrees(c), "angle": math.degrees(seg.angle),
                         "ds_max": v, "dds_max": a})
        return pd.DataFrame(rows)


def cycle_extreme(law: CamLaw, func: Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
                                               np.ndarray],
                  samples: int = _SAMPLES) -> tuple[float, float]:
    """Supremum over the cycle of ``func(phi, s, ds, dds)`` and the cam angle (rad) where it is.

    Each segment is sampled on its closed interval (so one-sided limits at the joints
    count), then the bracket around the best sample is zoomed into (17 samples, eight-fold
    shrink per round, to 1e-13 of the segment): a vectorised search for a locally unimodal
    function, corners included.
    """
    best, best_phi = -math.inf, 0.0
    for k, (seg, c) in enumerate(zip(law.segments, law.starts, strict=True)):
        x = np.linspace(0.0, seg.angle, samples)
        while True:
            vals = func(c + x, *law.segment_values(k, x))
            j = int(np.argmax(vals))
            if vals[j] > best:
                best, best_phi = float(vals[j]), c + float(x[j])
            lo, hi = x[max(j - 1, 0)], x[min(j + 1, x.size - 1)]
            if hi - lo <= 1e-13 * seg.angle:
                break
            x = np.linspace(lo, hi, 17)
    return best, best_phi


# --------------------------------------------------------------------------- followers

@dataclass(frozen=True)
class TranslatingFollower:
    """A translating follower (fig. 1.10): base radius r0, offset e, roller radius (m)."""

    base_radius: float
    offset: float = 0.0
    roller_radius: float = 0.0

    def __post_init__(self) -> None:
        r0, e, rr = self.base_radius, self.offset, self.roller_radius
        if not (math.isfinite(r0) and math.isfinite(e) and math.isfinite(rr)):
            raise CamError("base radius, offset and roller radius must be finite numbers")
        if r0 <= abs(e):
            raise CamError(f"the base radius {r0:g} m must exceed the offset |e| = {abs(e):g} m "
                           "(eq. 1.27: s0 = sqrt(r0^2 - e^2))")
        if not 0.0 <= rr < r0:
            raise CamError(f"the roller radius {rr:g} m must lie in [0, base radius {r0:g} m)")

    @property
    def s0(self) -> float:
        """Height of B above A on the base circle, s0 = sqrt(r0^2 - e^2) (eq. 1.27)."""
        return math.sqrt(self.base_radius**2 - self.offset**2)


@dataclass(frozen=True)
class OscillatingFollower:
    """An oscillating follower (fig. 1.12): base radius r0, arm L = CB, pivot distance d = AC."""

    base_radius: float
    arm: float
    pivot_distance: float
    roller_radius: float = 0.0
    rise_sense: str = "same"

    def __post_init__(self) -> None:
        r0, L, d, rr = self.base_radius, self.arm, self.pivot_distance, self.roller_radius
        if not all(math.isfinite(v) for v in (r0, L, d, rr)):
            raise CamError("base radius, arm, pivot distance and roller radius must be finite")
        if L <= 0.0 or d <= 0.0:
            raise CamError("the arm and the pivot distance must be positive")
        if not abs(d - L) < r0 < d + L:
            raise CamError(f"no triangle A-B0-C with r0 = {r0:g}, arm {L:g} and pivot distance "
                           f"{d:g} m: r0 must lie in ({abs(d - L):g}, {d + L:g}) (eq. 1.35)")
        if not 0.0 <= rr < r0:
            raise CamError(f"the roller radius {rr:g} m must lie in [0, base radius {r0:g} m)")
        if self.rise_sense not in ("same", "opposite"):
            raise CamError(f"rise_sense must be 'same' or 'opposite', not {self.rise_sense!r}")

    @property
    def beta0(self) -> float:
        """Angle at C between CA and CB0 on the base circle, from eq. 1.35 (rad)."""
        L, d, r0 = self.arm, self.pivot_distance, self.base_radius
        return math.acos(np.clip((d * d + L * L - r0 * r0) / (2.0 * d * L), -1.0, 1.0))


Follower = TranslatingFollower | OscillatingFollower


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[0] * b[1] - a[1] * b[0]


def _perp(a: np.ndarray) -> np.ndarray:
    """J a: a turned +90 deg."""
    return np.stack((-a[1], a[0]))


def _points(follower: Follower, s: np.ndarray, ds: np.ndarray, dds: np.ndarray,
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


def _tau(b: np.ndarray, d1: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Transmission angle (rad, [0, pi/2]): between the relative sliding direction
    T = dB/dphi - J B and the follower's direction of motion (eqs 1.28, 1.34)."""
    t = d1 - _perp(b)
    return np.arctan2(np.abs(_cross(t, u)), np.abs(np.sum(t * u, axis=0)))


def transmission_angle(law: CamLaw, follower: Follower, phi: Any) -> np.ndarray:
    """Transmission angle tau (rad, in (0, pi/2]) at cam angles ``phi`` (eqs 1.28, 1.34).

    Translating follower (eq. 1.28): tan tau = (s + s0) / |ds/dphi - e|; oscillating
    follower (eq. 1.34): tan tau = AC sin(beta0 + beta) /
    |L dbeta/dphi - (L - AC cos(beta0 + beta))| for ``rise_sense = "same"`` (with
    + (L - AC cos) for ``"opposite"``). Computed from the vectors of the mechanism: the
    angle between the relative sliding direction of the follower point on the cam and the
    follower's direction of motion. The pressure angle is pi/2 - tau.
    """
    b, d1, _, u, _ = _points(follower, *law(phi))
    return _tau(b, d1, u)


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
    _check_tau(tau_adm)
    s0 = _s0_required(law, tau_adm, offset)
    if s0 <= 0.0:
        raise CamError("every base radius keeps the transmission angle admissible for this "
                       "law and offset; give the base radius instead")
    return math.hypot(s0, offset)


def _check_tau(tau_adm: float) -> None:
    if not (0.0 < tau_adm < 0.5 * math.pi):
        raise CamError(f"the admissible transmission angle must lie in (0, 90) deg, got "
                       f"{math.degrees(tau_adm):g} deg")


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
    _check_tau(tau_adm)
    lo = cycle_extreme(law, lambda p, s, ds, dds: -ds)[0]
    hi = cycle_extreme(law, lambda p, s, ds, dds: ds)[0]

    def neg_r0(e: float) -> float:
        return -math.hypot(max(_s0_required(law, tau_adm, e), 0.0), e)

    e, r = golden_max(neg_r0, -lo, hi, xtol=1e-10 * max(hi + lo, 1e-300))
    return e, -r


def base_radius_oscillating(law: CamLaw, tau_adm: float, arm: float, pivot_distance: float,
                            rise_sense: str = "same") -> float:
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
    """
    _check_tau(tau_adm)
    if arm <= 0.0 or pivot_distance <= 0.0:
        raise CamError("the arm and the pivot distance must be positive")
    if law.stroke >= math.pi:
        raise CamError("the follower's swing must be below 180 deg")
    probe = OscillatingFollower(0.5 * (abs(pivot_distance - arm) + pivot_distance + arm), arm,
                                pivot_distance, rise_sense=rise_sense)

    def margin(beta0: float) -> float:
        def f(p: np.ndarray, s: np.ndarray, ds: np.ndarray, dds: np.ndarray) -> np.ndarray:
            b, d1, _, u, _ = _points(probe, s, ds, dds, beta0=beta0)
            return -_tau(b, d1, u)
        return -cycle_extreme(law, f)[0] - tau_adm

    # scan beta0 over (0, pi - beta_max) on sampled cam angles (vectorised), then bisect
    # with the refined minimum of tau
    x = [np.linspace(0.0, seg.angle, _SAMPLES) for seg in law.segments]
    vals = [np.concatenate(v) for v in zip(*(law.segment_values(k, xk)
                                             for k, xk in enumerate(x)), strict=True)]
    grid = np.linspace(0.0, math.pi - law.stroke, 362)[1:-1]
    b, d1, _, u, _ = _points(probe, *vals, beta0=grid[:, None])
    ok = np.min(_tau(b, d1, u), axis=1) >= tau_adm
    if not np.any(ok):
        raise CamError(f"no base radius keeps tau >= {math.degrees(tau_adm):g} deg with arm "
                       f"{arm:g} m and pivot distance {pivot_distance:g} m; change them")
    i = int(np.argmax(ok))
    lo, hi = (0.0 if i == 0 else grid[i - 1]), grid[i]
    while margin(hi) < 0.0:           # the sampled minimum may miss a sharp dip
        lo, hi = hi, hi + 0.25 * (hi - lo)
        if hi >= math.pi - law.stroke:
            raise CamError(f"no base radius keeps tau >= {math.degrees(tau_adm):g} deg with "
                           f"arm {arm:g} m and pivot distance {pivot_distance:g} m")
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
    b, d1, d2, _, _ = _points(follower, s, ds, dds)
    t = d1 - _perp(b)
    w = d2 - 2.0 * _perp(d1) - b
    tn = np.hypot(t[0], t[1])
    c, sn = np.cos(phi), np.sin(phi)

    def back(v: np.ndarray) -> np.ndarray:      # R(-phi) v
        return np.stack((c * v[0] + sn * v[1], -sn * v[0] + c * v[1]))

    p = back(b)
    n = back(_perp(t) / tn)
    rr = follower.roller_radius
    cols: dict[str, np.ndarray] = {"angle": np.degrees(phi)}
    for name, pt in (("pitch", p), ("profile", p - rr * n), ("outer", p + rr * n)):
        x, y = _mirror(follower, pt[0], pt[1], rotation)
        cols[f"x_{name}"], cols[f"y_{name}"] = x, y
    cols["radius"] = np.hypot(p[0], p[1])
    cols["curvature"] = -_cross(t, w) / tn**3
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


# --------------------------------------------------------------------------- forces

def critical_transmission_angle(mu: float, a: Any, b: float) -> np.ndarray:
    """Critical transmission angle of a translating follower, tan tau_cr = mu (2a + b)/b (1.44).

    ``a``: distance from the contact point to the guide (m), ``b``: guide length (m).
    """
    return np.arctan(mu * (2.0 * np.asarray(a, dtype=float) + b) / b)


def translating_follower_forces(load: Any, tau: Any, mu: float = 0.0, a: Any = 0.0,
                                b: float = 1.0, direction: Any = 1.0,
                                angles: Any = None) -> tuple[np.ndarray, ...]:
    """Contact force F12 and guide reactions N1, N2 of a translating follower (eqs 1.39-1.43).

    Equilibrium along the axis, F12 sin tau - F - sgn(v) mu (N1 + N2) = 0 (eq. 1.39, the seed
    writes the rise, sgn(v) = +1; friction opposes the follower's velocity, and vanishes in
    a dwell), and moments about the guide ends (eq. 1.40, friction moments neglected as in
    the seed): N1 = (a + b)/b F12 cos tau (1.41), N2 = a/b F12 cos tau (1.42), hence
    F12 = F / (sin tau - sgn(v) mu (2a + b)/b cos tau) (1.43).

    Parameters
    ----------
    load : array_like
        F, N: the axial load on the follower, positive towards the cam (it resists the rise).
    tau : array_like
        Transmission angle, rad.
    mu : float
        Friction coefficient in the guide.
    a : array_like
        Distance from the contact point to the near end of the guide, m.
    b : float
        Guide length, m.
    direction : array_like
        Sign of the follower's velocity (+1 rise, -1 return, 0 dwell).
    angles : array_like, optional
        Cam angles (rad) of the rows, only to name the row in an error.

    Returns
    -------
    F12, N1, N2 : numpy.ndarray
        N. F12 < 0 means the cam would have to pull: contact is lost.

    Raises
    ------
    CamError
        Where the denominator of eq. 1.43 is not positive: self-locking (tau <= tau_cr, 1.44).
    """
    load, tau, a, sgn = np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                              for v in (load, tau, a, direction)))
    k = mu * (2.0 * a + b) / b
    den = np.sin(tau) - np.sign(sgn) * k * np.cos(tau)
    bad = den <= 1e-12
    if np.any(bad):
        i = int(np.argmax(bad.ravel()))
        raise CamError(f"the follower self-locks {_row(angles, i)}: transmission angle "
                       f"{math.degrees(tau.ravel()[i]):.4g} deg <= critical "
                       f"{math.degrees(math.atan(k.ravel()[i])):.4g} deg (eq. 1.44); enlarge "
                       "the base radius, shorten the overhang a or lower the friction")
    f12 = load / den
    ct = f12 * np.cos(tau)
    return f12, (a + b) / b * ct, a / b * ct


def _row(angles: Any, i: int) -> str:
    if angles is None:
        return f"at row {i}"
    return f"at cam angle {math.degrees(float(np.ravel(angles)[i])):.6g} deg"


def critical_transmission_angle_oscillating(mu: float, pin_radius: float, arm: float) -> float:
    """Critical transmission angle of an oscillating follower, sin tau_cr = mu r / L (1.48)."""
    return math.asin(min(mu * pin_radius / arm, 1.0))


def oscillating_follower_force(moment: Any, tau: Any, arm: float, mu: float = 0.0,
                               pin_radius: float = 0.0, direction: Any = 1.0,
                               angles: Any = None) -> np.ndarray:
    """Contact force F12 on an oscillating follower (eqs 1.46-1.47).

    Moments about the pivot C: F12 L sin tau - M - sgn(dbeta) Mf = 0 with the pin friction
    moment Mf = mu r F02 and F02 = F12 (eq. 1.46), so F12 = M / (L sin tau - sgn mu r)
    (eq. 1.47). ``moment``: M, N m, resisting the rise; ``direction``: sign of the swing
    velocity. Raises :class:`CamError` where the denominator is not positive (1.48).
    """
    moment, tau, sgn = np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                             for v in (moment, tau, direction)))
    den = arm * np.sin(tau) - np.sign(sgn) * mu * pin_radius
    bad = den <= 1e-12 * arm
    if np.any(bad):
        i = int(np.argmax(bad.ravel()))
        cr = math.degrees(critical_transmission_angle_oscillating(mu, pin_radius, arm))
        raise CamError(f"the follower self-locks {_row(angles, i)}: transmission angle "
                       f"{math.degrees(tau.ravel()[i]):.4g} deg <= critical {cr:.4g} deg "
                       "(eq. 1.48)")
    return moment / den


# --------------------------------------------------------------------------- tables

def cam_table(law: CamLaw, follower: Follower, count: int = 361, speed: float = 1.0,
              rotation: str = "ccw") -> pd.DataFrame:
    """Motion, transmission angle and profile of a cam over one turn.

    Parameters
    ----------
    law : CamLaw
    follower : TranslatingFollower or OscillatingFollower
    count : int
        Rows at cam angles numpy.linspace(0, 360, count) deg.
    speed : float
        Cam speed omega, rad/s, for the follower's velocity and acceleration.
    rotation : {"ccw", "cw"}

    Returns
    -------
    pandas.DataFrame
        ``angle`` (deg); translating: ``s, ds, dds, v, a`` (m, m/rad, m/rad^2, m/s, m/s^2);
        oscillating: ``beta`` (deg), ``dbeta, ddbeta`` (rad/rad, rad/rad^2), ``omega2,
        eps2`` (rad/s, rad/s^2); then ``tau, pressure_angle`` (deg) and the columns of
        :func:`profile`.
    """
    if count < 2:
        raise CamError("count must be at least 2")
    phi = np.radians(np.linspace(0.0, 360.0, count))
    s, ds, dds = law(phi)
    tau = transmission_angle(law, follower, phi)
    if isinstance(follower, TranslatingFollower):
        cols = {"s": s, "ds": ds, "dds": dds, "v": speed * ds, "a": speed**2 * dds}
    else:
        cols = {"beta": np.degrees(s), "dbeta": ds, "ddbeta": dds, "omega2": speed * ds,
                "eps2": speed**2 * dds}
    table = pd.DataFrame({"angle": np.degrees(phi), **cols, "tau": np.degrees(tau),
                          "pressure_angle": 90.0 - np.degrees(tau)})
    prof = profile(law, follower, phi, rotation).drop(columns="angle")
    return pd.concat([table, prof], axis=1)


# --------------------------------------------------------------------------- scenes

TOP_KEYS = ("title", "format", "cam")
CAM_KEYS = ("speed", "speed_rpm", "rotation", "count", "base_radius", "transmission_angle",
            "roller_radius", "follower", "segments", "loads")
FOLLOWER_KEYS = {"translating": ("kind", "stroke", "offset"),
                 "oscillating": ("kind", "stroke_angle", "arm", "pivot_distance",
                                 "rise_sense")}
SEGMENT_KEYS = ("kind", "law", "angle")
LOAD_KEYS = {"translating": ("force", "mass", "gravity", "spring_rate", "spring_preload",
                             "friction", "guide_length", "guide_gap"),
             "oscillating": ("moment", "inertia", "spring_rate", "spring_preload", "friction",
                             "pin_radius")}


@dataclass(frozen=True)
class CamLoads:
    """Loads on the follower (``[cam.loads]``); names as in ``docs/cam-scenes.md``."""

    force: float = 0.0            # N (translating) or N m (oscillating: the `moment` key)
    mass: float = 0.0             # kg, or kg m^2 about C (oscillating: `inertia`)
    gravity: float = 0.0          # m/s^2 along the axis towards the cam (translating)
    spring_rate: float = 0.0      # N/m or N m/rad
    spring_preload: float = 0.0   # N or N m at the lowest position
    friction: float = 0.0         # guide (translating) or pin (oscillating) coefficient
    guide_length: float = 0.0     # b, m
    guide_gap: float = 0.0        # a at the lowest position, m
    pin_radius: float = 0.0       # r, m


@dataclass(frozen=True)
class CamScene:
    """A checked ``[cam]`` scene: the program, the follower, the speed and the loads."""

    title: str
    law: CamLaw
    follower: Follower
    speed: float
    rotation: str
    count: int
    loads: CamLoads
    transmission_angle: float | None = None     # admissible, rad, if the radius came from it


def _opt_float(table: dict, key: str, where: str, default: float = 0.0, **kw: bool) -> float:
    return as_float(table[key], f"{where}.{key}", **kw) if key in table else default


def load_cam_scene(source: Any) -> CamScene:
    """Read and check a ``[cam]`` scene (a path, TOML text or a dict; ``docs/cam-scenes.md``).

    Unknown keys are refused with the nearest known key suggested; every error is one line
    (:class:`~kinetostatics.errors.SceneError` for the file's form, :class:`CamError` for a
    cam that cannot be built).
    """
    raw = read_source(source, "cam scene")
    if isinstance(raw, dict) and "cam" not in raw and "driver" in raw:
        raise CamError("this is a mechanism scene (it has [driver]); the cam command takes a "
                       "[cam] scene (docs/cam-scenes.md), e.g. the bundled translating_roller")
    raw = check_keys(raw, TOP_KEYS, "cam scene", required=("cam",))
    if "format" in raw and raw["format"] != 1:
        raise CamError(f"cam scene: format must be 1, got {raw['format']!r}")
    title = as_str(raw["title"], "title") if "title" in raw else ""
    cam = check_keys(raw["cam"], CAM_KEYS, "cam", required=("follower", "segments"))

    fol = cam["follower"]
    if not isinstance(fol, dict) or "kind" not in fol:
        check_keys(fol, (*fol, "kind") if isinstance(fol, dict) else (), "cam.follower",
                   required=("kind",))
    kind = as_str(fol["kind"], "cam.follower.kind")
    if kind not in FOLLOWER_KEYS:
        raise CamError(f"cam.follower.kind must be 'translating' or 'oscillating', not "
                       f"{kind!r}{suggest(kind, FOLLOWER_KEYS)}")
    other = "oscillating" if kind == "translating" else "translating"
    for key in fol:
        if key in FOLLOWER_KEYS[other] and key not in FOLLOWER_KEYS[kind]:
            raise CamError(f"cam.follower.{key} belongs to an {other} follower, not a {kind} one")
    fol = check_keys(fol, FOLLOWER_KEYS[kind], "cam.follower",
                     required=("stroke",) if kind == "translating"
                     else ("stroke_angle", "arm", "pivot_distance"))
    if kind == "translating":
        stroke = as_float(fol["stroke"], "cam.follower.stroke", positive=True)
    else:
        stroke = math.radians(as_float(fol["stroke_angle"], "cam.follower.stroke_angle",
                                       positive=True))

    segments = []
    for i, seg in enumerate(as_list(cam["segments"], "cam.segments"), 1):
        where = f"cam.segments[{i}]"
        seg = check_keys(seg, SEGMENT_KEYS, where, required=("kind", "angle"))
        skind = as_str(seg["kind"], f"{where}.kind")
        if skind == "dwell" and "law" in seg:
            raise CamError(f"{where}: a dwell has no law")
        law = as_str(seg["law"], f"{where}.law") if "law" in seg else None
        if skind in ("rise", "return") and law is None:
            raise CamError(f"{where}: a {skind} needs a law ({', '.join(LAWS)})")
        try:
            law = law_name(law) if law is not None else None
        except CamError as exc:
            raise CamError(f"{where}.law: {exc}") from None
        segments.append(Segment(skind, math.radians(as_float(seg["angle"], f"{where}.angle",
                                                             positive=True)), law))
    try:
        law = CamLaw(stroke, tuple(segments))
    except CamError as exc:
        raise CamError(f"cam.segments: {exc}") from None

    if ("speed" in cam) == ("speed_rpm" in cam):
        raise CamError("cam: give exactly one of speed (rad/s) and speed_rpm")
    speed = (as_float(cam["speed"], "cam.speed", positive=True) if "speed" in cam
             else as_float(cam["speed_rpm"], "cam.speed_rpm", positive=True) * TWO_PI / 60.0)
    rotation = as_str(cam.get("rotation", "ccw"), "cam.rotation")
    if rotation not in ("ccw", "cw"):
        raise CamError(f"cam.rotation must be 'ccw' or 'cw', not {rotation!r}")
    count = as_int(cam.get("count", 361), "cam.count", lo=2, hi=10_000_000)
    roller = _opt_float(cam, "roller_radius", "cam", nonnegative=True)
    if ("base_radius" in cam) == ("transmission_angle" in cam):
        raise CamError("cam: give exactly one of base_radius (m) and transmission_angle "
                       "(the admissible one, deg)")
    tau_adm = None
    if "transmission_angle" in cam:
        tau_adm = math.radians(as_float(cam["transmission_angle"], "cam.transmission_angle",
                                        positive=True))
        _check_tau(tau_adm)

    loads = _load_loads(cam.get("loads", {}), kind, stroke)

    if kind == "translating":
        offset_raw = fol.get("offset", 0.0)
        if offset_raw == "optimal":
            if tau_adm is None:
                raise CamError("cam.follower.offset = 'optimal' needs cam.transmission_angle")
            offset, r0 = optimal_offset(law, tau_adm)
        else:
            offset = as_float(offset_raw, "cam.follower.offset")
            r0 = (base_radius_translating(law, tau_adm, offset) if tau_adm is not None
                  else as_float(cam["base_radius"], "cam.base_radius", positive=True))
        follower: Follower = TranslatingFollower(r0, offset, roller)
        if tau_adm is not None and loads.friction > 0.0:
            cr = float(np.max(critical_transmission_angle(loads.friction,
                                                          loads.guide_gap - np.array([0, stroke]),
                                                          loads.guide_length)))
            if tau_adm <= cr:
                raise CamError(f"cam.transmission_angle {math.degrees(tau_adm):g} deg is not "
                               f"above the critical angle {math.degrees(cr):.4g} deg (eqs "
                               "1.44-1.45); raise it")
    else:
        arm = as_float(fol["arm"], "cam.follower.arm", positive=True)
        dist = as_float(fol["pivot_distance"], "cam.follower.pivot_distance", positive=True)
        sense = as_str(fol.get("rise_sense", "same"), "cam.follower.rise_sense")
        if sense not in ("same", "opposite"):
            raise CamError(f"cam.follower.rise_sense must be 'same' or 'opposite', not "
                           f"{sense!r}")
        r0 = (base_radius_oscillating(law, tau_adm, arm, dist, sense) if tau_adm is not None
              else as_float(cam["base_radius"], "cam.base_radius", positive=True))
        follower = OscillatingFollower(r0, arm, dist, roller, sense)
    return CamScene(title, law, follower, speed, rotation, count, loads, tau_adm)


def _load_loads(raw: Any, kind: str, stroke: float) -> CamLoads:
    other = "oscillating" if kind == "translating" else "translating"
    if isinstance(raw, dict):
        for key in raw:
            if key in LOAD_KEYS[other] and key not in LOAD_KEYS[kind]:
                raise CamError(f"cam.loads.{key} applies to an {other} follower, not a {kind} "
                               "one")
    tab = check_keys(raw, LOAD_KEYS[kind], "cam.loads")
    w = "cam.loads"
    if kind == "translating":
        loads = CamLoads(
            force=_opt_float(tab, "force", w), mass=_opt_float(tab, "mass", w, nonnegative=True),
            gravity=_opt_float(tab, "gravity", w),
            spring_rate=_opt_float(tab, "spring_rate", w, nonnegative=True),
            spring_preload=_opt_float(tab, "spring_preload", w),
            friction=_opt_float(tab, "friction", w, nonnegative=True),
            guide_length=_opt_float(tab, "guide_length", w, nonnegative=True),
            guide_gap=_opt_float(tab, "guide_gap", w, nonnegative=True))
        if loads.friction > 0.0:
            if loads.guide_length <= 0.0:
                raise CamError("cam.loads: guide friction needs guide_length (b, m) > 0")
            if "guide_gap" not in tab:
                raise CamError("cam.loads: guide friction needs guide_gap (a at the lowest "
                               "position, m)")
            if loads.guide_gap < stroke:
                raise CamError(f"cam.loads.guide_gap {loads.guide_gap:g} m is less than the "
                               f"stroke {stroke:g} m: the contact point would enter the guide")
        return loads
    loads = CamLoads(
        force=_opt_float(tab, "moment", w), mass=_opt_float(tab, "inertia", w, nonnegative=True),
        spring_rate=_opt_float(tab, "spring_rate", w, nonnegative=True),
        spring_preload=_opt_float(tab, "spring_preload", w),
        friction=_opt_float(tab, "friction", w, nonnegative=True),
        pin_radius=_opt_float(tab, "pin_radius", w, nonnegative=True))
    return loads


@dataclass
class CamResults:
    """Tables and summary of a solved cam scene (see ``docs/cam-scenes.md``)."""

    scene: CamScene
    motion: pd.DataFrame
    geometry: pd.DataFrame
    forces: pd.DataFrame
    summary: dict[str, Any]


def solve_cam(source: Any) -> CamResults:
    """Solve a ``[cam]`` scene: follower motion, transmission angle, profile, forces, torque.

    Parameters
    ----------
    source : path, TOML text, dict or CamScene

    Returns
    -------
    CamResults
        ``motion``, ``geometry``, ``forces`` (pandas DataFrames, one row per cam angle) and
        ``summary`` (a JSON-ready dict); columns and keys in ``docs/cam-scenes.md``.
    """
    sc = source if isinstance(source, CamScene) else load_cam_scene(source)
    law, fol, w, ld = sc.law, sc.follower, sc.speed, sc.loads
    table = cam_table(law, fol, sc.count, w, sc.rotation)
    phi = np.radians(table["angle"].to_numpy())
    s, ds, dds = law(phi)
    b, d1, _, u, vel = _points(fol, s, ds, dds)
    tau = _tau(b, d1, u)
    t = d1 - _perp(b)
    tn = np.hypot(t[0], t[1])
    vmax = float(np.max(np.abs(ds)))
    direction = np.where(np.abs(ds) > 1e-12 * vmax, np.sign(ds), 0.0)
    load = ld.force + ld.spring_preload + ld.spring_rate * s + ld.mass * (w * w * dds + ld.gravity)
    translating = isinstance(fol, TranslatingFollower)
    if translating:
        a = ld.guide_gap - s
        b_len = ld.guide_length if ld.friction > 0.0 else 1.0
        f12, n1, n2 = translating_follower_forces(load, tau, ld.friction, a, b_len, direction,
                                                  angles=phi)
        friction = ld.friction * (n1 + n2) * np.abs(direction)   # none in a dwell
        loss = friction * np.abs(ds)                       # friction work per rad of cam
    else:
        f12 = oscillating_follower_force(load, tau, fol.arm, ld.friction, ld.pin_radius,
                                         direction, angles=phi)
        friction = ld.friction * ld.pin_radius * f12 * np.abs(direction)   # Mf (eq. 1.46)
        loss = friction * np.abs(ds)
    torque = f12 * np.sum(b * d1, axis=0) / tn          # M = B x F12 n = F12 (B . dB) / |T|
    separation = f12 < 0.0

    motion = table[["angle", *table.columns[1:6]]].copy()
    geometry = table[["angle", "tau", "pressure_angle", "x_pitch", "y_pitch", "x_profile",
                      "y_profile", "x_outer", "y_outer", "radius", "curvature"]].copy()
    forces = pd.DataFrame({"angle": table["angle"], "load": load, "F12": f12})
    if translating:
        forces["N1"], forces["N2"] = n1, n2
    else:
        forces["F02"] = f12
    forces["friction"] = friction
    forces["torque"] = torque
    forces["separation"] = separation

    tau_min, tau_at = cycle_extreme(law, lambda p, s_, ds_, dds_: -_tau(*_sel(fol, s_, ds_, dds_)))
    kmax, _ = cycle_extreme(law, lambda p, s_, ds_, dds_: _curv(fol, s_, ds_, dds_))
    rise_rows = direction > 0
    summary: dict[str, Any] = {
        "follower": "translating" if translating else "oscillating",
        "base_radius": fol.base_radius,
        "working_base_radius": fol.base_radius - fol.roller_radius,
        "transmission_angle_min": math.degrees(-tau_min),
        "transmission_angle_min_at": math.degrees(tau_at),
        "pressure_angle_max": 90.0 - math.degrees(-tau_min),
        ("velocity_max" if translating else "omega2_max"): w * vmax,
        ("acceleration_max" if translating else "eps2_max"): w * w * float(np.max(np.abs(dds))),
        "F12_max": float(np.max(f12)),
        "F12_max_at": float(table["angle"].iloc[int(np.argmax(f12))]),
        "torque_max": float(np.max(torque)),
        "torque_min": float(np.min(torque)),
        "torque_mean": float(np.trapezoid(torque, phi) / (phi[-1] - phi[0])),
        "friction_work": float(np.trapezoid(loss, phi)),
        "efficiency_rise": _rise_efficiency(phi, torque, load * ds, rise_rows),
        "curvature_max": kmax,
        "undercut": bool(fol.roller_radius > 0.0 and kmax * fol.roller_radius >= 1.0),
        "separation_rows": int(np.count_nonzero(separation)),
        "preload_needed": float(max(0.0, -float(np.min(load)))),
    }
    if translating:
        summary.update(offset=fol.offset, s0=fol.s0, stroke=law.stroke)
        if ld.friction > 0.0:
            cr = critical_transmission_angle(ld.friction, ld.guide_gap - s, ld.guide_length)
            summary["critical_angle_max"] = math.degrees(float(np.max(cr)))
    else:
        summary.update(beta0=math.degrees(fol.beta0), stroke_angle=math.degrees(law.stroke))
        if ld.friction > 0.0:
            summary["critical_angle_max"] = math.degrees(critical_transmission_angle_oscillating(
                ld.friction, ld.pin_radius, fol.arm))
    if sc.transmission_angle is not None:
        summary["transmission_angle_admissible"] = math.degrees(sc.transmission_angle)
    return CamResults(sc, motion, geometry, forces, summary)


def _sel(fol: Follower, s: np.ndarray, ds: np.ndarray,
         dds: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    b, d1, _, u, _ = _points(fol, s, ds, dds)
    return b, d1, u


def _curv(fol: Follower, s: np.ndarray, ds: np.ndarray, dds: np.ndarray) -> np.ndarray:
    b, d1, d2, _, _ = _points(fol, s, ds, dds)
    t = d1 - _perp(b)
    return -_cross(t, d2 - 2.0 * _perp(d1) - b) / np.hypot(t[0], t[1]) ** 3


def _rise_efficiency(phi: np.ndarray, torque: np.ndarray, useful: np.ndarray,
                     rows: np.ndarray) -> float | None:
    """Mean efficiency of the rise rows (eq. 4.22): work against the load / work of the cam."""
    if np.count_nonzero(rows) < 2:
        return None
    idx = np.flatnonzero(rows)
    runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)
    motor = sum(float(np.trapezoid(torque[r], phi[r])) for r in runs if r.size > 1)
    work = sum(float(np.trapezoid(useful[r], phi[r])) for r in runs if r.size > 1)
    if motor <= 0.0:
        return None
    return mean_efficiency(work, motor)


__all__: Sequence[str] = (
    "ALIASES", "LAWS", "LAW_COEFFICIENTS", "CamError", "CamLaw", "CamLoads", "CamResults",
    "CamScene", "OscillatingFollower", "Segment", "TranslatingFollower",
    "base_radius_oscillating", "base_radius_translating", "cam_table",
    "constant_acceleration", "cosine_acceleration", "critical_transmission_angle",
    "critical_transmission_angle_oscillating", "cycle_extreme", "fall", "law_name",
    "law_peaks", "load_cam_scene", "optimal_offset", "oscillating_follower_force",
    "polar_profile_oscillating", "polar_profile_translating", "profile", "rise",
    "sine_acceleration", "solve_cam", "transmission_angle", "translating_follower_forces",
    "zero_acceleration",
)
