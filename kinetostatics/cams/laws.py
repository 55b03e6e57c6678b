"""Motion laws of a cam follower and a cam's program of segments (seed 002 s. 1.2, eqs 1.1-1.21).

A law gives the lift ``s`` and its derivatives with respect to the cam angle, ``ds = v / omega``
and ``dds = a / omega^2`` (eqs 1.2-1.3); angles in radians.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from ..common.angles import degree_value, radian_value
from ..model.errors import WorkbenchError
from ..model.tomlio import suggest

TWO_PI = 2.0 * math.pi
SAMPLES = 801          # samples per segment when an extreme over the cycle is searched


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
        raise CamError(f"{name}: cam angles must lie in the phase [0, {degree_value(span):g}] "
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
            raise CamError(f"the segments' angles add up to {degree_value(total):.6g} deg, "
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
        segs = [Segment("rise", radian_value(rise_deg), rise_law)]
        if top_dwell_deg:
            segs.append(Segment("dwell", radian_value(top_dwell_deg)))
        segs.append(Segment("return", radian_value(return_deg), return_law))
        if bottom_dwell_deg:
            segs.append(Segment("dwell", radian_value(bottom_dwell_deg)))
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
                         "start": degree_value(c), "angle": degree_value(seg.angle),
                         "ds_max": v, "dds_max": a})
        return pd.DataFrame(rows)


def cycle_extreme(law: CamLaw, func: Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
                                               np.ndarray],
                  samples: int = SAMPLES) -> tuple[float, float]:
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
