"""The best estimate beside the seed's amplitude methods, and the conditioning warnings.

:func:`estimate` fits the readings of one ``[[resonance_test]]`` by maximum likelihood
(:mod:`balance.amplitude_fit`: every reading noisy, A1 included, 1-sigma
sigma_k = sqrt((relative A_k)^2 + absolute^2)) and reports the contract's
``estimate``: the unbalance m r |u| / a (kg m, eq. 3.30 with the fitted amplitudes),
the correction's angle theta_u + 180 deg, profile-likelihood intervals at the stated
confidence, chi2 and its consistency test. :func:`warnings_for` compares the seed's
result with it and says, with numbers, when the readings do not determine the
correction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from kinetostatics.common.angles import degree_value

from ..common import check_number, deg360
from ..errors import BalanceError
from .amplitude_fit import fit_amplitudes
from .chi2 import chi2_quantile

__all__ = ["DEFAULT_NOISE", "WIDE", "Estimate", "check_model", "estimate", "warnings_for"]

DEFAULT_NOISE = (0.01, 0.0)
"""(relative, absolute) 1-sigma noise of a reading when the scene gives none."""

WIDE = 0.25
"""The estimate is "not determined" when its interval leaves more than this fraction of
the unbalance uncorrected: the unbalance interval's half width over the estimate, or an
angle half width beyond 2 asin(WIDE / 2) (14.4 deg)."""

WIDE_ANGLE = degree_value(2.0 * math.asin(WIDE / 2.0))

FIT_RATIO = 0.25
"""Runs: a linear fit whose |(A1 A cos, A1 A sin)| / (A1 A) strays from 1 by more than
this is flagged (consistent readings give 1)."""


@dataclass(frozen=True)
class Estimate:
    """The maximum-likelihood estimate of one resonance test (the contract's ``estimate``).

    Attributes
    ----------
    unbalance, correction_mass : float
        m r |u| / a (kg m) and unbalance / correction_radius (kg).
    angle, mirror_angle : float or None
        The correction's angle at the best minimum (deg, [0, 360)); the other minimum
        the readings cannot tell from it (three runs at 0 and 180 deg: the mirror
        image), else None. None for both when A1 = 0.
    A : float
        The fitted amplitude of the trial mass alone (the amplitudes' unit).
    chi2 : float
        sum ((A_k - model_k) / sigma_k)^2 at the best minimum.
    dof : int
        Readings minus the 3 unknowns (0 for three runs). When A1 = 0 is read without
        noise (sigma of A1 = 0: no absolute noise) the reading pins the unbalance to 0
        exactly, its angle drops out and A is the one unknown left: the trial runs'
        amplitudes must all equal A, and dof = trial runs - 1 (1 for three runs). That
        is the chi-square the consistency test needs: chi2 is then the scatter of the
        trial runs about their weighted mean, distributed as chi2(runs - 1).
    consistent : bool or None
        chi2 within its chi-square quantile at ``confidence``; None when dof = 0.
    interval, mirror_interval : dict or None
        ``{unbalance: [lo, hi], angle: [lo, hi]}`` round ``angle`` and round
        ``mirror_angle``: profile-likelihood intervals at ``confidence``; an angle
        interval runs counterclockwise from lo to hi, [0, 360] is the whole circle,
        an unbounded limit is None.
    confidence : float
    noise : tuple of float
        (relative, absolute) 1-sigma noise of a reading.
    rho : float
        |u| / a, the unbalance over the trial mass (U/T).
    at_bound : bool
        The best minimum sits on the edge of the searched range of U/T (1e-4 or 1e4): the
        likelihood still rises beyond it, the estimate is a bound, not a maximum (a
        warning says so).
    """

    unbalance: float
    correction_mass: float
    angle: float | None
    mirror_angle: float | None
    A: float
    chi2: float
    dof: int
    consistent: bool | None
    interval: dict[str, Any] | None
    mirror_interval: dict[str, Any] | None
    confidence: float
    noise: tuple[float, float]
    rho: float
    at_bound: bool = False

    def to_dict(self) -> dict[str, Any]:
        """The contract's keys of ``estimate``; ``at_bound = true`` marks an estimate on
        the bound of the searched range (the key is absent otherwise)."""
        out = {"unbalance": self.unbalance, "correction_mass": self.correction_mass,
               "angle": self.angle, "mirror_angle": self.mirror_angle, "A": self.A,
               "chi2": self.chi2, "dof": self.dof, "consistent": self.consistent,
               "interval": self.interval, "mirror_interval": self.mirror_interval}
        if self.at_bound:
            out["at_bound"] = True
        return out


def check_model(noise: Any, confidence: Any, where: str) -> tuple[tuple[float, float], float]:
    """The noise model (relative, absolute) and the confidence, checked."""
    try:
        rel, ab = noise
    except (TypeError, ValueError):
        raise BalanceError(f"{where}: noise must be (relative, absolute), got {noise!r}") \
            from None
    rel = check_number(rel, f"{where}: noise relative", nonnegative=True)
    ab = check_number(ab, f"{where}: noise absolute", nonnegative=True)
    if rel == 0.0 and ab == 0.0:
        raise BalanceError(f"{where}: noise relative and absolute are both 0; a reading "
                           "without noise has no likelihood: give the instrument's noise")
    c = check_number(confidence, f"{where}: confidence")
    if not 0.0 < c < 1.0:
        raise BalanceError(f"{where}: confidence must lie in (0, 1), got {c:g} (e.g. 0.95)")
    return (rel, ab), c


def _angle_interval(lo: float, hi: float) -> list[float]:
    if math.isnan(lo) or math.isnan(hi):
        return [0.0, 360.0]
    return [deg360(degree_value(lo) + 180.0), deg360(degree_value(hi) + 180.0)]


def estimate(A1: float, marks: np.ndarray, amps: np.ndarray, mr: float, rc: float,
             noise: tuple[float, float], confidence: float,
             symmetric: bool = False) -> Estimate:
    """The maximum-likelihood estimate of one resonance test.

    Parameters
    ----------
    A1 : float
        Amplitude without trial mass.
    marks, amps : numpy.ndarray
        Trial marks (deg) and the amplitudes read there.
    mr : float
        m r of the trial mass (kg m).
    rc : float
        Correction radius (m).
    noise, confidence
        As checked by :func:`check_model`.
    symmetric : bool
        Marks at 0 and 180 deg only (three runs): two equal minima are ordered as the
        seed's ``angle`` and ``mirror_angle`` (the unbalance 0..180 deg from the mark
        first).
    """
    rel, ab = noise
    readings = np.concatenate([[A1], amps])
    sigma = np.hypot(rel * readings, ab)
    q1 = chi2_quantile(confidence, 1)
    dof = readings.size - 3
    if sigma[0] == 0.0:          # A1 = 0 read without noise: u = 0 exactly, one unknown a
        w = 1.0 / sigma[1:] ** 2
        a = float((w * amps).sum() / w.sum())
        chi2 = float((w * (amps - a) ** 2).sum())
        dof0 = amps.size - 1
        return Estimate(0.0, 0.0, None, None, a, chi2, dof0,
                        None if dof0 == 0 else bool(chi2 <= chi2_quantile(confidence, dof0)),
                        {"unbalance": [0.0, 0.0], "angle": None}, None, confidence, noise, 0.0)
    fit = fit_amplitudes(readings[None, :], marks, sigma[None, :], q1)
    keep = [j for j in range(fit.rho.shape[1]) if np.isfinite(fit.chi2[0, j])]
    if symmetric and len(keep) == 2 and \
            abs(fit.chi2[0, 0] - fit.chi2[0, 1]) <= 1e-9 * max(1.0, fit.chi2[0, 0]) and \
            fit.theta[0, 0] > math.pi:
        keep = keep[::-1]
    best = keep[0]
    chi2 = float(fit.chi2[0, best])

    def interval(j: int) -> dict[str, Any]:
        hi = fit.rho_hi[0, j]
        return {"unbalance": [float(mr * fit.rho_lo[0, j]),
                              float(mr * hi) if np.isfinite(hi) else None],
                "angle": None if A1 == 0.0 else _angle_interval(fit.theta_lo[0, j],
                                                                fit.theta_hi[0, j])}

    def corr_angle(j: int) -> float | None:
        return None if A1 == 0.0 else deg360(degree_value(fit.theta[0, j]) + 180.0)

    other = keep[1] if len(keep) > 1 and A1 > 0.0 else None
    if other is not None and _in_arc(corr_angle(other), interval(best)["angle"]):
        other = None                     # a second point of the same basin, not a mirror
    unbalance = float(mr * fit.rho[0, best])
    return Estimate(
        unbalance=unbalance, correction_mass=unbalance / rc, angle=corr_angle(best),
        mirror_angle=None if other is None else corr_angle(other),
        A=float(fit.a[0, best]), chi2=chi2, dof=dof,
        consistent=None if dof == 0 else bool(chi2 <= chi2_quantile(confidence, dof)),
        interval=interval(best), mirror_interval=None if other is None else interval(other),
        confidence=confidence, noise=noise, rho=float(fit.rho[0, best]),
        at_bound=bool(fit.at_bound is not None and fit.at_bound[0, best]))


def _in_arc(angle: float, arc: list[float] | None) -> bool:
    if arc is None:
        return True
    lo, hi = arc
    if hi - lo == 360.0:
        return True
    return (angle - lo) % 360.0 <= (hi - lo) % 360.0


def _half_width(arc: list[float]) -> float:
    lo, hi = arc
    return 180.0 if hi - lo == 360.0 else ((hi - lo) % 360.0) / 2.0


def warnings_for(est: Estimate, *, method: str, A1: float, seed_unbalance: float | None,
                 seed_angles: tuple[float | None, ...], fit_ratio: float | None,
                 where: str) -> list[str]:
    """Conditioning warnings, each with its numbers (an empty list when all is well).

    - two minima the readings cannot tell apart (runs at marks too close for the noise);
    - an estimate the readings leave undetermined: an interval wider than :data:`WIDE`
      of the unbalance (a trial mass too small or too large for it, or marks too close);
    - readings inconsistent with the model at the stated noise (chi2 beyond its quantile);
    - the seed's result outside the estimate's intervals (or a linear fit whose ratio
      strays from 1 by more than :data:`FIT_RATIO`).
    """
    out: list[str] = []
    conf = f"{100.0 * est.confidence:g} %"
    if est.at_bound:
        side = "above 1e4" if est.rho > 1.0 else "below 1e-4"
        out.append(f"{where}: the estimate sits on the bound of the searched range: U/T = "
                   f"{est.rho:.4g} (the unbalance over the trial mass's, searched from 1e-4 to "
                   f"1e4); the readings put it {side}, so the estimate's unbalance "
                   f"{est.unbalance:.4g} kg m is a bound, not a maximum of the likelihood: "
                   "repeat the test with a trial mass nearer the unbalance")
    if est.mirror_angle is not None and method != "three-run":
        out.append(f"{where}: the readings cannot tell the correction angle {est.angle:.1f} "
                   f"deg from {est.mirror_angle:.1f} deg (both fit within the {conf} "
                   "threshold): the trial marks are too close together for the noise; add a "
                   "run at a mark about 90 deg away")
    if A1 > 0.0 and est.interval is not None:
        lo, hi = est.interval["unbalance"]
        u = est.unbalance
        rel_w = math.inf if hi is None or u == 0.0 else max(u - lo, hi - u) / u
        ang_w = _half_width(est.interval["angle"])
        if rel_w > WIDE or ang_w > WIDE_ANGLE:
            ratio = est.rho
            cause = (f"the trial mass is too small for the unbalance (U/T = {ratio:.3g})"
                     if ratio > 2.0 else
                     f"the trial mass is too large for the unbalance (U/T = {ratio:.3g})"
                     if ratio < 0.5 else "the trial marks and the noise do not fix it")
            span = "unbounded" if hi is None else f"{lo:.4g} .. {hi:.4g} kg m"
            out.append(f"{where}: the readings do not determine the correction: at {conf} "
                       f"the unbalance lies within {span} (estimate {u:.4g}) and the angle "
                       f"within +-{ang_w:.1f} deg; {cause}")
    if est.consistent is False:
        out.append(f"{where}: the readings do not fit a linear machine at the stated noise: "
                   f"chi2 = {est.chi2:.3g} for {est.dof} degree(s) of freedom, above its "
                   f"{conf} quantile {chi2_quantile(est.confidence, est.dof):.3g}; the "
                   "noise is larger than stated or a reading is wrong")
    if fit_ratio is not None and abs(fit_ratio - 1.0) > FIT_RATIO:
        out.append(f"{where}: the linear fit in squared amplitudes is inconsistent "
                   f"(|(A1 A cos, A1 A sin)| / (A1 A) = {fit_ratio:.3g}, 1 for consistent "
                   "readings): prefer the estimate")
    if A1 > 0.0 and est.interval is not None and seed_unbalance is not None:
        lo, hi = est.interval["unbalance"]
        arcs = [est.interval["angle"]] + ([est.mirror_interval["angle"]]
                                          if est.mirror_interval is not None else [])
        angles = [a for a in seed_angles if a is not None]
        off_u = seed_unbalance < lo or (hi is not None and seed_unbalance > hi)
        off_a = bool(angles) and not any(_in_arc(a, arc) for a in angles for arc in arcs)
        if off_u or off_a:
            what = "unbalance and angle" if off_u and off_a else \
                "unbalance" if off_u else "angle"
            out.append(f"{where}: the seed's result (unbalance {seed_unbalance:.4g} kg m, "
                       f"angle {', '.join(f'{a:.1f}' for a in angles)} deg) falls outside the "
                       f"estimate's {conf} interval for the {what}: the hand method is misled "
                       "by the noise; use the estimate")
    return out
