"""Propagating a measured-amplitude uncertainty +-dA to a balancing correction.

Method (used by :mod:`balance.resonance` and :mod:`balance.influence`): every
amplitude a_i of the measurement lies in [a_i - dA, a_i + dA] (clipped at 0). The
correction (magnitude and angle of each correction mass) is evaluated

- at the 2^n corners of that box (all combinations of +-dA) and at the nominal
  point: the interval reported is the smallest one holding all these values. It is
  exact when each output is monotonic in each amplitude over the box, which holds
  for boxes small against the amplitudes; otherwise it may miss an interior extremum.
- by first-order (linearised) sensitivities from central differences: the half
  width sum_i |d output / d a_i| dA, reported beside the corner interval as a
  cross-check; with more than ``MAX_CORNER_DIMS`` amplitudes only this is used
  (the interval is then nominal +- half width).

Angles are unwrapped about the nominal angle (differences in (-180, 180]) so an
interval across the 0 deg mark is reported as (low, high) with low > high, read
counter-clockwise from low to high.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from .common import deg360
from .errors import BalanceError

__all__ = ["Interval", "MAX_CORNER_DIMS", "propagate"]

MAX_CORNER_DIMS = 14
"""Largest number of uncertain amplitudes evaluated at every corner (2^14 points)."""

BatchFunction = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]
"""Maps amplitudes (k, n) to (magnitudes (k, p), angles in deg (k, p)); NaN where
the amplitudes admit no solution (magnitude) or the angle is undefined (angle)."""


@dataclass(frozen=True)
class Interval:
    """The uncertainty of one correction (one plane).

    Attributes
    ----------
    dA : float
        The amplitude uncertainty propagated (+- dA on every amplitude).
    method : str
        ``"corners"`` (corner interval, linearised half widths beside it) or
        ``"linearised"`` (nominal +- first-order half width only).
    magnitude : tuple of float
        (low, high) of the correction magnitude (mass).
    angle : tuple of float or None
        (low, high) of the correction angle, deg in [0, 360), counter-clockwise from
        low to high; None where the angle is undefined (no unbalance).
    magnitude_linear, angle_linear : float or None
        First-order half widths sum_i |d/d a_i| dA; None where undefined (no angle,
        or the nominal point lies on the edge of what a solution fits).
    """

    dA: float
    method: str
    magnitude: tuple[float, float]
    angle: tuple[float, float] | None
    magnitude_linear: float | None
    angle_linear: float | None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict of the interval."""
        return {"dA": self.dA, "method": self.method, "magnitude": list(self.magnitude),
                "angle": list(self.angle) if self.angle is not None else None,
                "magnitude_linear": self.magnitude_linear, "angle_linear": self.angle_linear}


def _finite_or_none(x: float) -> float | None:
    return float(x) if np.isfinite(x) else None


def _wrap(d: np.ndarray) -> np.ndarray:
    """Angle differences (deg) into [-180, 180)."""
    return (d + 180.0) % 360.0 - 180.0


def propagate(func: BatchFunction, amplitudes: np.ndarray, dA: float,
              what: str = "amplitudes") -> list[Interval]:
    """Intervals of each output of ``func`` when every amplitude may be off by +-dA.

    Parameters
    ----------
    func : callable
        Vectorised evaluation, see :data:`BatchFunction`.
    amplitudes : numpy.ndarray
        The n nominal amplitudes.
    dA : float
        Uncertainty on each amplitude (>= 0, same unit).
    what : str
        Words naming the measurement in error messages.

    Returns
    -------
    list of Interval
        One per output column (correction plane).

    Raises
    ------
    BalanceError
        When some amplitudes within the box admit no solution: the correction
        cannot be bounded.
    """
    a0 = np.asarray(amplitudes, dtype=float)
    n = a0.size
    mag0, ang0 = (x[0] for x in func(a0[None, :]))

    # First-order sensitivities by central differences (step small against the data).
    h = 1e-6 * max(float(np.abs(a0).max()), dA, 1e-300)
    steps = np.eye(n) * h
    plus = np.maximum(a0 + steps, 0.0)
    minus = np.maximum(a0 - steps, 0.0)
    mp, ap = func(plus)
    mm, am = func(minus)
    width = (plus - minus).diagonal()[:, None]
    dmag = (mp - mm) / width
    dang = _wrap(ap - am) / width
    mag_lin = np.abs(dmag).sum(axis=0) * dA
    ang_lin = np.abs(dang).sum(axis=0) * dA

    if n <= MAX_CORNER_DIMS:
        method = "corners"
        signs = np.array(list(itertools.product((-1.0, 1.0), repeat=n)))
        pts = np.maximum(a0 + signs * dA, 0.0)
        mags, angs = func(pts)
        mags = np.vstack([mags, mag0[None, :]])
        angs = np.vstack([angs, ang0[None, :]])
        if np.isnan(mags).any():
            bad = pts[np.isnan(mags[:-1]).any(axis=1)][0]
            raise BalanceError(
                f"within +-{dA:g} the {what} reach values no solution fits (e.g. "
                f"{', '.join(f'{x:g}' for x in bad)}): the correction cannot be bounded; "
                "measure more precisely or use a larger trial mass")
        mag_lo, mag_hi = mags.min(axis=0), mags.max(axis=0)
        delta = _wrap(angs - ang0[None, :])
        delta[np.isnan(delta)] = 0.0       # corners with an undefined angle (no unbalance)
        ang_lo, ang_hi = ang0 + delta.min(axis=0), ang0 + delta.max(axis=0)
    else:
        method = "linearised"
        if np.isnan(mp).any() or np.isnan(mm).any():
            raise BalanceError(f"the {what} lie on the edge of what a solution fits: the "
                               "correction cannot be bounded")
        mag_lo, mag_hi = np.maximum(mag0 - mag_lin, 0.0), mag0 + mag_lin
        ang_lo, ang_hi = ang0 - ang_lin, ang0 + ang_lin

    out = []
    for j in range(mag0.size):
        undefined = bool(np.isnan(ang0[j]))
        out.append(Interval(
            dA=float(dA),
            method=method,
            magnitude=(float(mag_lo[j]), float(mag_hi[j])),
            angle=None if undefined else (deg360(ang_lo[j]), deg360(ang_hi[j])),
            magnitude_linear=_finite_or_none(mag_lin[j]),
            angle_linear=None if undefined else _finite_or_none(ang_lin[j]),
        ))
    return out
