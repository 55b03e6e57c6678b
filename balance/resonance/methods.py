"""Experimental dynamic balancing at the resonance speed (seed 002, s. 3.3.2).

The rotor swings on a frame about an axis lying in one correction plane, so only
the unbalance U_1 = m_1 r_1 of the other plane excites it (eq. 3.22). At resonance
the amplitude is proportional to the exciting force (eq. 3.23): A1 = k m_1 r_1
omega^2 z. A trial mass m at radius r at the 0 deg mark gives A2 = k |F_1 + Q| z
(eqs 3.24-3.25), at the 180 deg mark A3 = k |F_1 - Q| z (eqs 3.26-3.27); the trial
alone would give A = k m r omega^2 z (eq. 3.28). The three amplitudes are the sides
and diagonals of the amplitude parallelogram (fig. 3.14), whence A (eq. 3.29), the
unbalance m_1 r_1 = m r A1 / A (eq. 3.30) and the angle phi between the unbalance and
the 0 deg mark (eq. 3.31, corrected: A1^2 + A^2 - A3^2 in the numerator).

Three amplitudes cannot tell phi from -phi (the mirror ambiguity): the result gives
both candidate correction angles. Trial runs at three or more marks that are not
all equal or opposite (e.g. 0, 120, 240 deg: the four-run method) fix the angle
uniquely by linear least squares in the squared amplitudes.

Beside the seed's result, every test carries ``estimate``, the maximum-likelihood fit
of the amplitudes themselves under a stated noise model, with intervals at a stated
confidence (:mod:`balance.resonance_estimate`), and ``warnings``: the conditioning
checks (trial mass too small or too large, marks too close for the noise, readings
inconsistent with the model, the seed's result outside the estimate's intervals). Each
warning is also issued as a :class:`~balance.errors.BalanceWarning`.

The second plane is balanced by the same computation after the rotor is turned end
for end in the frame (``plane = 2``). Angles are in degrees from the 0 deg mark in
the direction of the angle scale, in [0, 360).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from kinetostatics.common.angles import degree_column, degree_value, radian_column
from kinetostatics.model.tomlio import MIN_MAGNITUDE

from ..common import check_number, deg360
from ..errors import BalanceError, BalanceWarning
from ..uncertainty import Interval, propagate
from .estimate import DEFAULT_NOISE, Estimate, check_model, estimate, warnings_for

__all__ = [
    "COS_TOLERANCE",
    "ResonanceResult",
    "four_run",
    "parallelogram",
    "trial_runs",
]

COS_TOLERANCE = 1e-9
"""|cos phi| may exceed 1 by this much (rounding, noise) and is then clipped."""

SMALL_TRIAL = 0.1
"""A below this fraction of A1 (a trial mass much smaller than the unbalance) warns."""

_COND_LIMIT = 1e-9
"""Trial marks whose least-squares matrix has s_min / s_max below this are refused."""


@dataclass(frozen=True)
class ResonanceResult:
    """Result of the amplitude methods (:func:`parallelogram`, :func:`trial_runs`).

    Attributes
    ----------
    plane : int
        The correction plane (1 or 2).
    A : float or None
        The amplitude the trial mass alone would give (eq. 3.29, or the runs' fit; None
        where the runs' linear fit has no solution, A^2 <= 0).
    phi : float or None
        Three-run method: the angle (deg, [0, 180]) between the unbalance and the 0 deg
        mark (eq. 3.31). With runs: the unbalance's angle theta_u in [0, 360). None
        when A1 = 0.
    unbalance : float or None
        m_1 r_1 = m r A1 / A (kg m), eq. 3.30.
    correction_mass : float or None
        unbalance / correction_radius (kg).
    angle : float or None
        Where the correction mass goes: (180 + phi) mod 360 (deg).
    mirror_angle : float or None
        Three-run method: the other candidate (180 - phi) mod 360; None with runs.
    method : str
        ``"three-run"`` or ``"runs"``.
    A1 : float
        Amplitude without trial mass.
    marks, amplitudes : numpy.ndarray
        Trial marks (deg) and the amplitudes measured with the trial mass there.
    trial_mass, trial_radius, correction_radius : float
        The inputs (kg, m, m).
    cos_phi : float or None
        The arccos argument before clipping (three-run method).
    fit_ratio : float or None
        Runs: |(A1 A cos, A1 A sin)| / (A1 A) from the fit; 1 for consistent data.
    uncertainty : Interval or None
        Worst-case bounds of the correction mass and ``angle`` for a given +-dA.
    mirror_uncertainty : Interval or None
        Three-run method: the same bounds for ``mirror_angle`` (``uncertainty``'s
        ``mirror_angle`` in the dict).
    estimate : Estimate or None
        The maximum-likelihood estimate with its intervals.
    warnings : tuple of str
        The conditioning warnings (empty when all is well).
    """

    plane: int
    A: float | None
    phi: float | None
    unbalance: float | None
    correction_mass: float | None
    angle: float | None
    mirror_angle: float | None
    method: str
    A1: float
    marks: np.ndarray = field(repr=False)
    amplitudes: np.ndarray = field(repr=False)
    trial_mass: float = 0.0
    trial_radius: float = 0.0
    correction_radius: float = 0.0
    cos_phi: float | None = None
    fit_ratio: float | None = None
    uncertainty: Interval | None = None
    mirror_uncertainty: Interval | None = None
    estimate: Estimate | None = None
    warnings: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """The contract's keys, ``estimate`` and ``warnings``; ``uncertainty`` is added
        only when it was asked for."""
        d: dict[str, Any] = {
            "plane": self.plane, "A": self.A, "phi": self.phi, "unbalance": self.unbalance,
            "correction_mass": self.correction_mass, "angle": self.angle,
            "mirror_angle": self.mirror_angle,
            "estimate": None if self.estimate is None else self.estimate.to_dict(),
            "warnings": list(self.warnings),
        }
        if self.uncertainty is not None:
            d["uncertainty"] = self.uncertainty.to_dict()
            if self.mirror_uncertainty is not None and self.mirror_angle is not None:
                m = self.mirror_uncertainty
                d["uncertainty"]["mirror_angle"] = list(m.angle) if m.angle else None
        return d


# --------------------------------------------------------------------------- cores
def _three_run_core(A1: np.ndarray, A2: np.ndarray, A3: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Vectorised eqs 3.29 and 3.31: A^2, A (NaN where A^2 <= 0) and cos phi (unclipped)."""
    A_sq = (A2**2 + A3**2 - 2.0 * A1**2) / 2.0                    # eq. 3.29
    with np.errstate(invalid="ignore", divide="ignore"):
        A = np.where(A_sq > 0.0, np.sqrt(np.abs(A_sq)), np.nan)
        # eq. 3.31 corrected: (A1^2 + A^2 - A3^2) / (2 A1 A) = (A2^2 - A3^2) / (4 A1 A)
        cos_phi = (A2**2 - A3**2) / (4.0 * A1 * A)
    return A_sq, A, cos_phi


def _runs_matrix(marks: np.ndarray) -> np.ndarray:
    """Rows [1, 2 cos theta_k, 2 sin theta_k] of the runs' linear model.

    A_k^2 - A1^2 = A^2 + 2 A1 A cos(theta_k - theta_u) (law of cosines, fig. 3.14).
    """
    t = radian_column(marks)
    return np.column_stack([np.ones_like(t), 2.0 * np.cos(t), 2.0 * np.sin(t)])


def _runs_core(A1: np.ndarray, Ak: np.ndarray, pinv: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Least squares (scene-format s. 2) for many amplitude sets at once.

    Returns A^2, the fitted (A1 A cos theta_u, A1 A sin theta_u) as a complex number,
    and A (NaN where A^2 <= 0).
    """
    y = Ak**2 - (A1**2)[:, None]
    x = y @ pinv.T                                     # (k, 3): A^2, A1 A cos, A1 A sin
    with np.errstate(invalid="ignore"):
        A = np.where(x[:, 0] > 0.0, np.sqrt(np.abs(x[:, 0])), np.nan)
    return x[:, 0], x[:, 1] + 1j * x[:, 2], A


# ------------------------------------------------------------------------ checks
def _check_common(trial_mass: float, trial_radius: float, correction_radius: float,
                  plane: int, where: str) -> tuple[float, float, float, int]:
    m = check_number(trial_mass, f"{where}: trial_mass", positive=True)
    r = check_number(trial_radius, f"{where}: trial_radius", positive=True)
    rc = check_number(correction_radius, f"{where}: correction_radius", positive=True)
    if isinstance(plane, bool) or not isinstance(plane, int | np.integer) or plane not in (1, 2):
        raise BalanceError(f"{where}: plane must be 1 or 2, got {plane!r}")
    return m, r, rc, int(plane)


def _check_A1(A1: float, where: str) -> float:
    return check_number(A1, f"{where}: A1 (amplitude without trial mass)", nonnegative=True,
                        smallest=MIN_MAGNITUDE)


def _check_trial_amplitude(value: float, name: str) -> float:
    a = check_number(value, name, smallest=MIN_MAGNITUDE)
    if a <= 0.0:
        raise BalanceError(f"{name} must be a positive amplitude, got {a:g}: a run with the "
                           "trial mass that does not vibrate at all is not a usable reading")
    return a


def _small_trial(A: float, A1: float, where: str) -> list[str]:
    if A1 > 0.0 and A < SMALL_TRIAL * A1:
        return [f"{where}: the trial mass gives A = {A:.4g}, under {SMALL_TRIAL:g} of "
                f"A1 = {A1:.4g}; the result is very sensitive to amplitude errors, use a "
                "larger trial mass"]
    return []


def _finish(notes: list[str], est: Estimate | None, method: str, a1: float,
            unbalance: float | None, angles: tuple[float | None, ...], fit_ratio: float | None,
            where: str) -> tuple[str, ...]:
    """The result's warnings (the seed method's own, then the conditioning checks against
    the estimate), each also issued as a BalanceWarning."""
    if est is not None:
        notes = notes + warnings_for(est, method=method, A1=a1, seed_unbalance=unbalance,
                                     seed_angles=angles, fit_ratio=fit_ratio, where=where)
    for note in notes:
        warnings.warn(note, BalanceWarning, stacklevel=3)
    return tuple(notes)


# ------------------------------------------------------------------ three runs
def parallelogram(A1: float, A2: float, A3: float, trial_mass: float, trial_radius: float,
                  correction_radius: float, *, plane: int = 1,
                  dA: float | None = None, noise: tuple[float, float] | None = DEFAULT_NOISE,
                  confidence: float = 0.95) -> ResonanceResult:
    """The amplitude-parallelogram (three-run) method, eqs 3.22-3.31.

    A^2 = (A2^2 + A3^2 - 2 A1^2) / 2 (eq. 3.29); m_1 r_1 = m r A1 / A (eq. 3.30);
    cos phi = (A1^2 + A^2 - A3^2) / (2 A1 A) = (A2^2 - A3^2) / (4 A1 A) (eq. 3.31 with
    its misprint corrected: the seed prints A2 for A^2). The correction goes at
    ``angle`` = 180 + phi when the unbalance lies 0..180 deg from the mark, else at
    ``mirror_angle`` = 180 - phi: the three amplitudes cannot tell which.

    Parameters
    ----------
    A1 : float
        Amplitude at resonance without trial mass (>= 0; 0 means balanced).
    A2, A3 : float
        Amplitudes with the trial mass at the 0 deg and at the 180 deg mark (> 0).
    trial_mass, trial_radius : float
        m (kg) and r (m) of the trial mass (> 0).
    correction_radius : float
        Radius where the correction mass is fixed (m, > 0).
    plane : int
        1 or 2 (plane 2: rotor turned end for end in the frame).
    dA : float, optional
        Uncertainty +-dA on each of A1, A2, A3: adds ``uncertainty`` (corner
        evaluation of the 8 combinations, with linearised half widths; see
        :mod:`balance.uncertainty`) bounding the correction mass and ``angle``; a corner
        where no parallelogram closes (|cos phi| > 1) refuses the bounds.
    noise : (float, float) or None
        (relative, absolute) 1-sigma noise of each reading, sigma_k = sqrt((relative
        A_k)^2 + absolute^2), for ``estimate``; None: the seed's result alone (no
        estimate, no conditioning checks).
    confidence : float
        Of the estimate's intervals and of its consistency test, in (0, 1).

    Returns
    -------
    ResonanceResult

    Raises
    ------
    BalanceError
        A negative A1, non-positive A2, A3 or trial data, A^2 <= 0
        (A2^2 + A3^2 <= 2 A1^2), or |cos phi| > 1 + 1e-9: no parallelogram joins
        these amplitudes.

    Warns
    -----
    BalanceWarning
        Each entry of ``warnings``: |cos phi| exceeded 1 by at most 1e-9 and was
        clipped; the trial mass is much smaller than the unbalance (A < 0.1 A1); the
        conditioning checks of :func:`balance.resonance_estimate.warnings_for`.

    Examples
    --------
    >>> r = parallelogram(546.5, 1071.9, 495.0, 0.002, 0.06, 0.05)
    >>> round(r.A, 6), round(r.phi, 6), round(r.angle, 6), round(r.mirror_angle, 6)
    (631.137905, 49.065926, 229.065926, 130.934074)
    """
    where = f"resonance_test (plane {plane})"
    m, r, rc, plane = _check_common(trial_mass, trial_radius, correction_radius, plane, where)
    model = None if noise is None else check_model(noise, confidence, where)
    a1 = _check_A1(A1, where)
    a2 = _check_trial_amplitude(A2, f"{where}: A2 (trial mass at 0 deg)")
    a3 = _check_trial_amplitude(A3, f"{where}: A3 (trial mass at 180 deg)")
    A_sq, A, cos_phi = (float(x[0]) for x in _three_run_core(
        np.array([a1]), np.array([a2]), np.array([a3])))
    if not A_sq > 0.0:
        raise BalanceError(
            f"{where}: A2^2 + A3^2 - 2 A1^2 = {2 * A_sq:.6g} <= 0 (A1 = {a1:g}, A2 = {a2:g}, "
            f"A3 = {a3:g}): no amplitude parallelogram has these sides and diagonals; "
            "check the readings or use a larger trial mass")
    notes = _small_trial(A, a1, where)
    unbalance = m * r * a1 / A                                   # eq. 3.30
    if a1 == 0.0:
        phi = angle = mirror = None
        cos_out = None
    else:
        if abs(cos_phi) > 1.0 + COS_TOLERANCE:
            raise BalanceError(
                f"{where}: cos phi = {cos_phi:.12g} lies outside [-1, 1] (eq. 3.31; A1 = "
                f"{a1:g}, A2 = {a2:g}, A3 = {a3:g}): no parallelogram joins these amplitudes; "
                "repeat the runs")
        if abs(cos_phi) > 1.0:
            notes.insert(0, f"{where}: cos phi = {cos_phi:.15g} exceeds 1 by at most "
                            f"{COS_TOLERANCE:g}; clipped")
        cos_out = cos_phi
        phi = degree_value(math.acos(min(1.0, max(-1.0, cos_phi))))   # eq. 3.31, [0, 180]
        angle, mirror = deg360(180.0 + phi), deg360(180.0 - phi)      # fig. 3.15
    unc = mirror_unc = None
    if dA is not None:
        d = check_number(dA, f"{where}: dA", nonnegative=True)

        def batch(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            _, Ab, cb = _three_run_core(pts[:, 0], pts[:, 1], pts[:, 2])
            mass = m * r * pts[:, 0] / Ab / rc
            # a corner where no parallelogram closes has no solution: never clipped
            mass = np.where((pts[:, 0] > 0.0) & (np.abs(cb) > 1.0 + COS_TOLERANCE), np.nan, mass)
            with np.errstate(invalid="ignore"):
                phi_b = degree_column(np.arccos(np.clip(cb, -1.0, 1.0)))
                ang = np.where(pts[:, 0] > 0.0, 180.0 + phi_b, np.nan)
                mir = np.where(pts[:, 0] > 0.0, 180.0 - phi_b, np.nan)
            return np.column_stack([mass, mass]), np.column_stack([ang, mir])

        unc, mirror_unc = propagate(batch, np.array([a1, a2, a3]), d, "amplitudes A1, A2, A3")
    marks = np.array([0.0, 180.0])
    est = None if model is None else estimate(a1, marks, np.array([a2, a3]), m * r, rc,
                                              *model, symmetric=True)
    notes = _finish(notes, est, "three-run", a1, unbalance, (angle, mirror), None, where)
    return ResonanceResult(
        plane=plane, A=A, phi=phi, unbalance=unbalance, correction_mass=unbalance / rc,
        angle=angle, mirror_angle=mirror, method="three-run", A1=a1,
        marks=marks, amplitudes=np.array([a2, a3]), trial_mass=m,
        trial_radius=r, correction_radius=rc, cos_phi=cos_out, uncertainty=unc,
        mirror_uncertainty=mirror_unc,
        estimate=est, warnings=notes)


# ----------------------------------------------------------------- any marks
def _parse_runs(runs: Iterable[Any], where: str) -> tuple[np.ndarray, np.ndarray]:
    marks, amps = [], []
    for k, run in enumerate(runs):
        w = f"{where}: run {k + 1}"
        if isinstance(run, Mapping):
            for key in run:
                if key not in ("angle", "A"):
                    raise BalanceError(f"{w}: unknown key {key!r}; a run is "
                                       "{{angle = <deg>, A = <amplitude>}}")
            if "angle" not in run or "A" not in run:
                raise BalanceError(f"{w}: a run needs both 'angle' and 'A'")
            ang, amp = run["angle"], run["A"]
        elif isinstance(run, Sequence) and not isinstance(run, str) and len(run) == 2:
            ang, amp = run
        else:
            raise BalanceError(f"{w} must be {{angle, A}} or a pair (angle, A)")
        marks.append(check_number(ang, f"{w}: angle"))
        amps.append(_check_trial_amplitude(amp, f"{w}: A"))
    return np.array(marks, dtype=float), np.array(amps, dtype=float)


def _check_marks(marks: np.ndarray, where: str) -> np.ndarray:
    """Refuse too few runs or marks that leave the angle ambiguous; return pinv."""
    if marks.size < 3:
        raise BalanceError(f"{where}: {marks.size} trial run(s) given; the runs method needs "
                           "at least three, at marks not all equal or opposite (e.g. 0, 120, "
                           "240 deg)")
    key = np.round(np.mod(marks, 360.0), 9) % 360.0
    distinct = np.unique(key)
    lines = np.unique(np.round(np.mod(marks, 180.0), 9) % 180.0)
    if lines.size == 1:
        raise BalanceError(f"{where}: the trial marks {', '.join(f'{a:g}' for a in marks)} deg "
                           "are all equal or opposite; they cannot tell the unbalance's angle "
                           "from its mirror image: add runs at other marks (e.g. 0, 120, 240)")
    if distinct.size < 3:
        raise BalanceError(f"{where}: the trial marks {', '.join(f'{a:g}' for a in marks)} deg "
                           "hold only two different positions, which leave a mirror ambiguity; "
                           "add a run at a third mark (e.g. 0, 120, 240)")
    M = _runs_matrix(marks)
    s = np.linalg.svd(M, compute_uv=False)
    if s[-1] <= _COND_LIMIT * s[0]:
        raise BalanceError(f"{where}: the trial marks {', '.join(f'{a:g}' for a in marks)} deg "
                           "lie too close together to fix the angle; spread them round the "
                           "rotor")
    return np.linalg.pinv(M)


def trial_runs(A1: float, runs: Iterable[Any], trial_mass: float, trial_radius: float,
               correction_radius: float, *, plane: int = 1,
               dA: float | None = None, noise: tuple[float, float] | None = DEFAULT_NOISE,
               confidence: float = 0.95) -> ResonanceResult:
    """Unbalance from three or more trial runs at any marks (the runs method).

    Each run k (trial mass at mark theta_k) obeys the law of cosines of the
    parallelogram (fig. 3.14, eqs 3.24-3.27 generalised to any mark):
    A_k^2 - A1^2 = A^2 + 2 A1 A cos(theta_k - theta_u). Solved by linear least
    squares for (A^2, A1 A cos theta_u, A1 A sin theta_u): A is the root of the first,
    theta_u the angle of the other two; then m_1 r_1 = m r A1 / A (eq. 3.30) and the
    correction goes at theta_u + 180. For three runs at 0, 120 and 240 deg this is
    the classic four-run method (A^2 = mean(A_k^2) - A1^2).

    Parameters
    ----------
    A1 : float
        Amplitude without trial mass (>= 0).
    runs : iterable
        Trial runs: dicts ``{angle, A}`` or pairs ``(angle_deg, amplitude)``; at
        least three, at marks not all equal or opposite and at three or more
        different positions.
    trial_mass, trial_radius, correction_radius : float
        As in :func:`parallelogram`.
    plane : int
        1 or 2.
    dA : float, optional
        Uncertainty on every amplitude (A1 and the runs'): adds ``uncertainty``.
    noise, confidence
        As in :func:`parallelogram`.

    Returns
    -------
    ResonanceResult
        ``phi`` = theta_u in [0, 360), ``angle`` = theta_u + 180, ``mirror_angle`` None.
        Where the linear fit has no solution (A^2 <= 0, or no angular part) its keys
        are None, a warning says why, and ``estimate`` is still given.

    Raises
    ------
    BalanceError
        Fewer than three runs; marks all equal or opposite, or at only two
        positions, or too close together to fix the angle at all; non-positive
        amplitudes or trial data.
    """
    where = f"resonance_test (plane {plane})"
    m, r, rc, plane = _check_common(trial_mass, trial_radius, correction_radius, plane, where)
    model = None if noise is None else check_model(noise, confidence, where)
    a1 = _check_A1(A1, where)
    marks, amps = _parse_runs(runs, where)
    pinv = _check_marks(marks, where)
    A_sq, c, A = (x[0] for x in _runs_core(np.array([a1]), amps[None, :], pinv))
    A_sq, A = float(A_sq), float(A)
    notes: list[str] = []
    phi = angle = fit = unbalance = None
    if not A_sq > 0.0:
        A = None
        notes.append(f"{where}: the runs' linear fit in squared amplitudes gives A^2 = "
                     f"{A_sq:.6g} <= 0, so its unbalance and angle are null: the amplitudes "
                     "are inconsistent with a trial-mass effect that large; see the estimate")
    else:
        notes += _small_trial(A, a1, where)
        unbalance = m * r * a1 / A                                   # eq. 3.30
        if a1 > 0.0 and abs(c) <= 1e-12 * a1 * A:
            notes.append(f"{where}: the runs' linear fit does not fix the unbalance's angle "
                         "(its angular part vanishes); see the estimate")
        elif a1 > 0.0:
            phi = deg360(degree_value(math.atan2(c.imag, c.real)))  # theta_u
            angle = deg360(phi + 180.0)
            fit = float(abs(c) / (a1 * A))
    unc = None
    if dA is not None and A is not None:
        d = check_number(dA, f"{where}: dA", nonnegative=True)

        def batch(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            _, cb, Ab = _runs_core(pts[:, 0], pts[:, 1:], pinv)
            mass = m * r * pts[:, 0] / Ab / rc
            ang = np.where(pts[:, 0] > 0.0, degree_column(np.angle(cb)) + 180.0, np.nan)
            return mass[:, None], ang[:, None]

        unc = propagate(batch, np.concatenate([[a1], amps]), d, "amplitudes A1 and runs")[0]
    est = None if model is None else estimate(a1, marks, amps, m * r, rc, *model)
    notes = _finish(notes, est, "runs", a1, unbalance, (angle,), fit, where)
    return ResonanceResult(
        plane=plane, A=A, phi=phi, unbalance=unbalance,
        correction_mass=None if unbalance is None else unbalance / rc,
        angle=angle, mirror_angle=None, method="runs", A1=a1, marks=marks, amplitudes=amps,
        trial_mass=m, trial_radius=r, correction_radius=rc, fit_ratio=fit, uncertainty=unc,
        estimate=est, warnings=notes)


def four_run(A1: float, A2: float, A3: float, A4: float, trial_mass: float,
             trial_radius: float, correction_radius: float, *, plane: int = 1,
             dA: float | None = None, noise: tuple[float, float] | None = DEFAULT_NOISE,
             confidence: float = 0.95) -> ResonanceResult:
    """The four-run method: trial mass at the 0, 120 and 240 deg marks.

    The same as :func:`trial_runs` with runs ``[(0, A2), (120, A3), (240, A4)]``:
    A^2 = (A2^2 + A3^2 + A4^2) / 3 - A1^2 and a unique correction angle.

    Parameters
    ----------
    A1 : float
        Amplitude without trial mass.
    A2, A3, A4 : float
        Amplitudes with the trial mass at 0, 120 and 240 deg.
    trial_mass, trial_radius, correction_radius, plane, dA, noise, confidence
        As in :func:`trial_runs`.

    Returns
    -------
    ResonanceResult
    """
    return trial_runs(A1, [(0.0, A2), (120.0, A3), (240.0, A4)], trial_mass, trial_radius,
                      correction_radius, plane=plane, dA=dA, noise=noise,
                      confidence=confidence)
