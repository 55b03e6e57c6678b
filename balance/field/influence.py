"""The influence-coefficient method: balancing with measured amplitude AND phase.

Beyond the seed (which measures amplitudes only, s. 3.3.2): with a phase reference
each reading is a complex number V = A e^(i theta). For a rigid rotor at a given
speed the readings depend linearly on the correction masses W (complex: mass at
angle) in the planes, V = V0 + alpha W, with one influence coefficient
alpha_ij = dV_i / dW_j per measurement point i (a sensor, at one speed) and plane j.

- Trial runs k with trial masses T_k (a vector over the planes, complex) give
  V_k - V0 = alpha T_k; with at least as many runs as planes alpha is the linear
  least-squares solution of these equations (exact for one run per plane).
- The correction minimises |V0 + alpha W|: W = -alpha^+ V0 (exact with as many
  measurement points as planes; least squares over several sensors or speeds).

Conventions: each trial run is measured from the initial state (the previous trial
mass removed; to leave it on, give the cumulative trial vector). Phases and mass
angles must be measured in the same sense with respect to the rotor; if an
instrument reports phase lag in the opposite sense, negate its phases. Masses come
out in the trial masses' unit (kg, g, ...) at the trial radius; give
``trial_radius`` and ``correction_radius`` to rescale. Angles in degrees, [0, 360).

Trim runs: after a correction C has been fitted, the readings V' measured with it
are one more equation, V' - V = alpha C (V the state it was fitted to). With
measured trial runs the trim runs join them in the least squares for alpha; with
influence coefficients given from an earlier session each trim run updates them by
Broyden's rank-one update, alpha + (V' - V - alpha C) C^H / (C^H C), the smallest
change (Frobenius norm) that makes alpha reproduce what the correction did. The
next correction balances the latest readings: W = -alpha^+ V'.

Every result carries intervals at a stated confidence from the readings' amplitude
and phase noise, the condition number of alpha and a ``warnings`` list; see
:mod:`balance.influence_stats`.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from kinetostatics.common.angles import degree_column, radian_column

from ..common import angle_of, check_number, deg360_array, polar, radius_ratio
from ..errors import BalanceError
from ..uncertainty import Interval, propagate
from .influence_stats import (
    NoiseModel,
    bootstrap_intervals,
    conditioning,
    conditioning_warnings,
    pinv_with_singular_values,
)
from .weights import Split, split_correction

__all__ = [
    "InfluenceResult",
    "influence_balance",
    "influence_coefficients",
    "influence_single_plane",
    "influence_two_plane",
    "trim_balance",
]

_COND_LIMIT = 1e-9


@dataclass(frozen=True)
class InfluenceResult:
    """Result of the influence-coefficient method.

    Attributes
    ----------
    masses : numpy.ndarray
        Correction mass per plane (trial masses' unit, at the correction radius).
    angles : numpy.ndarray
        Their angles (deg, [0, 360)).
    corrections : numpy.ndarray of complex
        The correction vectors W (mass e^(i angle)).
    coefficients : numpy.ndarray of complex
        alpha, shape (measurement points, planes): reading per unit trial mass (after
        the trim runs, when there are any).
    initial : numpy.ndarray of complex
        The initial readings V0.
    residual : numpy.ndarray of complex
        Predicted readings after correction, V + alpha W (V the readings balanced:
        V0, or the last trim run's); zero for square systems.
    uncertainty : list of Interval or None
        Per plane, worst-case bounds of mass and angle for +-dA on every amplitude.
    intervals : list of dict
        Per plane ``{"mass": [lo, hi], "angle": [lo, hi]}`` at ``noise.confidence``
        (bootstrap; an angle interval runs counterclockwise from lo to hi; hi None
        where unbounded).
    noise : NoiseModel
        The noise model the intervals and the conditioning check used.
    condition_number : float
        kappa(alpha), ratio of its extreme singular values.
    amplification : float
        kappa eps_V: first-order bound of ||dW|| / ||W|| from the readings' noise.
    warnings : list of str
        Why the correction may not be determined by the data (empty when all is well).
    current : numpy.ndarray of complex
        The readings the correction balances (V0 without trim runs).
    trim_runs : int
        How many trim runs updated the coefficients.
    splits : list of Split or None
        Each plane's correction split onto fixed positions, when asked.
    name : str
        A label (the scene section's ``name``).
    points : tuple of str or None
        Names of the measurement points.
    """

    masses: np.ndarray
    angles: np.ndarray
    corrections: np.ndarray = field(repr=False)
    coefficients: np.ndarray = field(repr=False)
    initial: np.ndarray = field(repr=False)
    residual: np.ndarray = field(repr=False)
    uncertainty: list[Interval] | None = None
    intervals: list[dict] = field(default_factory=list)
    noise: NoiseModel = field(default_factory=NoiseModel)
    condition_number: float = 1.0
    amplification: float = 0.0
    warnings: list[str] = field(default_factory=list)
    current: np.ndarray | None = field(default=None, repr=False)
    trim_runs: int = 0
    splits: list[Split] | None = None
    name: str = ""
    points: tuple[str, ...] | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: corrections per plane with their intervals (and splits), the
        coefficients, the predicted residual readings, the conditioning and the
        warnings; masses in the trial masses' unit, vibration in the readings'."""
        corr = []
        for j, (m, a) in enumerate(zip(self.masses, self.angles, strict=True)):
            c: dict[str, Any] = {"plane": j + 1, "mass": float(m), "angle": float(a)}
            if self.intervals:
                c["interval"] = self.intervals[j]
            if self.splits is not None:
                c["split"] = self.splits[j].to_dict()
            corr.append(c)
        res = [{"amplitude": float(abs(v)), "phase": angle_of(complex(v))}
               for v in self.residual]
        for r, p in zip(res, self.points or (), strict=False):
            r["point"] = p
        d: dict[str, Any] = {
            **({"name": self.name} if self.name else {}),
            "corrections": corr,
            "residual_vibration": res,
            "coefficients": [[{"amplitude": float(abs(a)), "phase": angle_of(complex(a))}
                              for a in row] for row in self.coefficients],
            "condition_number": self.condition_number,
            "noise_amplification": self.amplification,
            "noise": self.noise.to_dict(),
            "trim_runs": self.trim_runs,
            "warnings": list(self.warnings),
        }
        if self.uncertainty is not None:
            d["uncertainty"] = [iv.to_dict() for iv in self.uncertainty]
        return d


# ------------------------------------------------------------------- parsing
def _reading(x: Any, where: str) -> tuple[float, float]:
    """A reading as (amplitude, phase deg), from a pair or a complex number."""
    if isinstance(x, complex | np.complexfloating):
        return abs(x), angle_of(complex(x))
    if isinstance(x, Sequence) and not isinstance(x, str) and len(x) == 2:
        a = check_number(x[0], f"{where}: amplitude", nonnegative=True)
        return a, check_number(x[1], f"{where}: phase")
    raise BalanceError(f"{where} must be (amplitude, phase_deg) or a complex number, "
                       f"not {x!r}")


def _is_pair_of_numbers(x: Any) -> bool:
    return (isinstance(x, Sequence) and not isinstance(x, str) and len(x) == 2
            and all(isinstance(v, int | float | np.integer | np.floating)
                    and not isinstance(v, bool) for v in x))


def _readings(xs: Any, where: str) -> np.ndarray:
    """Readings as an (n, 2) array of (amplitude, phase deg); one reading is allowed."""
    if isinstance(xs, complex | np.complexfloating) or _is_pair_of_numbers(xs):
        xs = [xs]
    if not isinstance(xs, Iterable):
        raise BalanceError(f"{where} must be a list of readings (amplitude, phase_deg)")
    out = [_reading(x, f"{where}[{i}]") for i, x in enumerate(xs)]
    if not out:
        raise BalanceError(f"{where}: no readings")
    return np.array(out, dtype=float)


def _mass(x: Any, where: str) -> complex:
    """A trial mass as a complex number: (mass, angle deg), a complex, or 0 / None."""
    if x is None:
        return 0j
    if isinstance(x, complex | np.complexfloating):
        return complex(x)
    if isinstance(x, int | float | np.number) and not isinstance(x, bool):
        if x == 0:
            return 0j
        raise BalanceError(f"{where}: a trial mass is (mass, angle_deg), not a bare number")
    if isinstance(x, Sequence) and len(x) == 2:
        m = check_number(x[0], f"{where}: mass", nonnegative=True)
        return polar(m, check_number(x[1], f"{where}: angle"))
    raise BalanceError(f"{where} must be (mass, angle_deg), a complex number or None")


def _to_complex(amp: np.ndarray, phase_deg: np.ndarray) -> np.ndarray:
    return amp * np.exp(1j * radian_column(phase_deg))


# -------------------------------------------------------------------- solving
@dataclass(frozen=True)
class _Data:
    """Every reading and what changed between them.

    amps, phases: (rows, points), row 0 the initial readings, then one row per run
    (trial runs, then trim runs); T: (runs, planes) the masses each run added; base:
    (runs,) the row each run is measured against; alpha0: given coefficients (then
    the runs are trim runs only, applied by Broyden updates); current: the row the
    correction balances.
    """

    amps: np.ndarray
    phases: np.ndarray
    T: np.ndarray
    base: np.ndarray
    alpha0: np.ndarray | None
    current: int
    trims: int


def _solve_batch(amps: np.ndarray, phases: np.ndarray, d: _Data
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Influence coefficients and corrections for many reading sets at once.

    amps, phases: (k, rows, points). Returns alpha (k, points, planes) and W (k, planes);
    W is NaN for a set whose alpha cannot separate the planes.
    """
    V = _to_complex(amps, phases)
    dV = V[:, 1:, :] - V[:, d.base, :]                   # V_k - V_base = alpha T_k
    if d.alpha0 is None:
        alpha = np.swapaxes(np.linalg.pinv(d.T) @ dV, 1, 2)   # least squares over runs
    else:
        alpha = np.repeat(d.alpha0[None], V.shape[0], axis=0).astype(complex)
        for i, C in enumerate(d.T):                      # Broyden: meet each secant
            miss = dV[:, i, :] - alpha @ C               # (k, points)
            alpha = alpha + miss[:, :, None] * C.conj()[None, None, :] / np.vdot(C, C).real
    Vc = V[:, d.current, :]
    alpha_pinv, s = pinv_with_singular_values(alpha)
    W = -(alpha_pinv @ Vc[..., None])[..., 0]            # min |V + alpha W|
    bad = (s[:, 0] == 0.0) | (s[:, -1] <= _COND_LIMIT * s[:, 0])
    W[bad] = np.nan
    return alpha, W


def influence_coefficients(initial: Any, runs: Iterable[tuple[Any, Any]]) -> np.ndarray:
    """The influence coefficients alpha (points x planes) from trial runs.

    Parameters
    ----------
    initial : sequence
        Initial readings, one per measurement point: (amplitude, phase_deg) pairs or
        complex numbers.
    runs : iterable of (trials, readings)
        ``trials``: the trial mass in each plane, (mass, angle_deg), complex or None;
        ``readings``: the readings with those trial masses, as ``initial``.

    Returns
    -------
    numpy.ndarray of complex
    """
    d = _prepare(initial, runs)
    alpha, _ = _solve_batch(d.amps[None], d.phases[None], d)
    return alpha[0]


def _masses(t: Any, where: str) -> list[complex]:
    if isinstance(t, complex | np.complexfloating) or _is_pair_of_numbers(t):
        t = [t]                                          # one plane: a single mass
    if not isinstance(t, Sequence) or isinstance(t, str):
        raise BalanceError(f"{where}: give the masses per plane as a list of "
                           "(mass, angle_deg), complex numbers or None")
    return [_mass(x, f"{where}, plane {j + 1}") for j, x in enumerate(t)]


def _coefficients(coefficients: Any) -> np.ndarray:
    """Given influence coefficients as a complex array (points, planes)."""
    if isinstance(coefficients, np.ndarray) and np.iscomplexobj(coefficients):
        alpha = np.atleast_2d(coefficients).astype(complex)
    else:
        rows = coefficients if isinstance(coefficients, Sequence) else None
        if not rows:
            raise BalanceError("coefficients must be a list of rows (one per measurement "
                               "point) of (amplitude, phase_deg) per plane")
        out = []
        for i, row in enumerate(rows):
            r = _readings(row, f"coefficients[{i}]")
            out.append(_to_complex(r[:, 0], r[:, 1]))
        if len({len(r) for r in out}) != 1:
            raise BalanceError("coefficients: every row needs one entry per plane")
        alpha = np.array(out)
    if not np.all(np.isfinite(alpha)):
        raise BalanceError("coefficients must be finite numbers")
    return alpha


def _prepare(initial: Any, runs: Iterable[tuple[Any, Any]] = (),
             trims: Iterable[tuple[Any, Any]] = (), coefficients: Any = None) -> _Data:
    V0 = _readings(initial, "initial readings")
    runs, trims = list(runs), list(trims)
    alpha0 = None if coefficients is None else _coefficients(coefficients)
    if alpha0 is None and not runs:
        raise BalanceError("influence method: no trial runs given (or give the influence "
                           "coefficients of an earlier session)")
    if alpha0 is not None and runs:
        raise BalanceError("influence method: give trial runs or coefficients, not both")
    masses, reads = [], []
    for kind, items in (("trial run", runs), ("trim run", trims)):
        for k, run in enumerate(items):
            if not (isinstance(run, Sequence) and len(run) == 2):
                raise BalanceError(f"{kind} {k + 1} must be a pair (masses, readings)")
            t, v = run
            masses.append(_masses(t, f"{kind} {k + 1}"))
            rk = _readings(v, f"{kind} {k + 1} readings")
            if rk.shape[0] != V0.shape[0]:
                raise BalanceError(f"{kind} {k + 1}: {rk.shape[0]} readings, but the initial "
                                   f"run has {V0.shape[0]}; give one per measurement point")
            reads.append(rk)
    n_planes = alpha0.shape[1] if alpha0 is not None else len(masses[0])
    if any(len(t) != n_planes for t in masses):
        raise BalanceError(f"the runs give masses for different numbers of planes (the "
                           f"{'coefficients have' if alpha0 is not None else 'first run has'}"
                           f" {n_planes})")
    if alpha0 is not None and alpha0.shape[0] != V0.shape[0]:
        raise BalanceError(f"coefficients: {alpha0.shape[0]} rows for {V0.shape[0]} "
                           "measurement points; give one row per point")
    T = np.array(masses, dtype=complex).reshape(len(masses), n_planes)
    if alpha0 is None:
        if len(runs) < n_planes:
            raise BalanceError(f"{len(runs)} trial run(s) for {n_planes} planes: give at "
                               "least one trial run per plane")
        s = np.linalg.svd(T[:len(runs)], compute_uv=False)
        if s[-1] <= _COND_LIMIT * s[0]:
            raise BalanceError("the trial runs do not put trial masses in every plane "
                               "independently (their trial vectors are dependent)")
    if any(not np.any(t) for t in T[len(runs):]):
        raise BalanceError("a trim run applied no mass: give the correction it applied")
    if V0.shape[0] < n_planes:
        raise BalanceError(f"{V0.shape[0]} measurement point(s) for {n_planes} planes: give "
                           "at least as many readings (sensors or speeds) as planes")
    R = len(runs)                                        # rows: 0 initial, 1..R trial runs,
    base = np.array([0] * R + [0 if k == 0 else R + k for k in range(len(trims))],
                    dtype=int)                           # then trim k against the row before
    data = np.stack([V0] + reads)                        # (rows, points, 2)
    return _Data(amps=data[..., 0], phases=data[..., 1], T=T, base=base, alpha0=alpha0,
                 current=R + len(trims) if trims else 0,
                 trims=len(trims))


def influence_balance(initial: Any, runs: Iterable[tuple[Any, Any]] = (), *,
                      trims: Iterable[tuple[Any, Any]] = (),
                      coefficients: Any = None,
                      trial_radius: float | None = None,
                      correction_radius: float | None = None,
                      dA: float | None = None,
                      noise: NoiseModel | None = None,
                      split: tuple[int, float] | int | None = None) -> InfluenceResult:
    """Correction masses by the influence-coefficient method, any number of planes.

    alpha from V_k - V0 = alpha T_k over the trial runs (least squares when there
    are more runs than planes), then W = -alpha^+ V0 (least squares over the
    measurement points: several sensors and/or several speeds stacked in the
    readings). Trim runs refine alpha and move the target to their readings. See
    the module docstring for conventions.

    Parameters
    ----------
    initial : sequence
        Initial readings V0: (amplitude, phase_deg) pairs or complex numbers, one per
        measurement point (sensor, or sensor at one speed).
    runs : iterable of (trials, readings)
        Trial masses per plane ((mass, angle_deg), complex or None) and the readings.
    trims : iterable of (applied, readings)
        Trim runs in order: the correction masses added per plane (as ``trials``) and
        the readings with them on (each on top of the previous ones).
    coefficients : array or list of rows, optional
        Influence coefficients from an earlier session, (points, planes) complex or
        rows of (amplitude, phase_deg) per unit mass; instead of ``runs``.
    trial_radius, correction_radius : float, optional
        Give both to convert masses at the trial radius to the correction radius.
    dA : float, optional
        Worst-case bound +-dA on every amplitude (phases exact): adds per-plane bounds
        (corners, see :mod:`balance.uncertainty`).
    noise : NoiseModel, optional
        1-sigma amplitude and phase noise and the confidence of the intervals
        (default 1 %, 1 deg, 0.95); see :mod:`balance.influence_stats`.
    split : int or (int, float), optional
        Split each plane's correction onto N equally spaced positions (the first at
        the given angle, default 0 deg).

    Returns
    -------
    InfluenceResult

    Raises
    ------
    BalanceError
        Fewer runs than planes, dependent trial vectors, fewer readings than planes,
        or influence coefficients that cannot separate the planes (the trial masses
        changed the readings too little or alike).
    """
    d = _prepare(initial, runs, trims, coefficients)
    model = noise if noise is not None else NoiseModel()
    ratio = radius_ratio(trial_radius, "trial_radius", correction_radius, "correction_radius",
                         "give both trial_radius and correction_radius, or neither")
    alpha, W = _solve_batch(d.amps[None], d.phases[None], d)
    alpha, W = alpha[0], W[0]
    if not np.all(np.isfinite(W)):
        raise BalanceError("the influence coefficients cannot separate the planes: the trial "
                           "masses changed the readings too little or in the same way; use "
                           "larger trial masses or other measurement points")
    V = _to_complex(d.amps, d.phases)
    residual = V[d.current] + alpha @ W
    Wc = W * ratio

    def solve(a: np.ndarray, p: np.ndarray) -> np.ndarray:
        return _solve_batch(a, p, d)[1] * ratio

    intervals, failed = bootstrap_intervals(solve, d.amps, d.phases, Wc, model)
    sig = model.complex_sigma(d.amps)
    dV, dV_sigma = V[1:] - V[d.base], np.hypot(sig[1:], sig[d.base])
    n_runs = len(d.T) - d.trims
    labels = [f"trial run {k + 1}" for k in range(n_runs)]
    labels += [f"trim run {k + 1}" for k in range(d.trims)]
    if d.alpha0 is not None:                             # given coefficients: not measured
        dV, dV_sigma, labels = dV[:0], dV_sigma[:0], []
    kappa, amp, run_noise = conditioning(alpha, d.amps[d.current], dV, dV_sigma, model)
    warns = conditioning_warnings(kappa, amp, run_noise, labels)
    if failed > 0.0:
        warns.append(f"{100.0 * failed:.3g} % of the noise draws could not separate the "
                     "planes: the trial masses barely changed the readings")
    unc = None
    if dA is not None:
        dd = check_number(dA, "dA", nonnegative=True)
        shape = d.amps.shape

        def batch(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            a = pts.reshape((-1,) + shape)
            Wb = solve(a, np.broadcast_to(d.phases, a.shape))
            return np.abs(Wb), degree_column(np.angle(Wb))

        unc = propagate(batch, d.amps.ravel(), dd, "measured amplitudes")
    splits = None
    if split is not None:
        n, first = (split, 0.0) if isinstance(split, int | np.integer) else split
        splits = [split_correction(abs(w), angle_of(complex(w)), n, first) for w in Wc]
    return InfluenceResult(masses=np.abs(Wc), angles=deg360_array(degree_column(np.angle(Wc))),
                           corrections=Wc, coefficients=alpha, initial=V[0],
                           residual=residual, uncertainty=unc, intervals=intervals,
                           noise=model, condition_number=kappa, amplification=amp,
                           warnings=warns, current=V[d.current], trim_runs=d.trims,
                           splits=splits)


def trim_balance(initial: Any, trims: Iterable[tuple[Any, Any]], *, coefficients: Any = None,
                 runs: Iterable[tuple[Any, Any]] = (), **kwargs: Any) -> InfluenceResult:
    """A trim correction: the coefficients updated by the corrections already applied.

    Parameters
    ----------
    initial : sequence
        The readings the first applied correction was fitted to.
    trims : iterable of (applied, readings)
        Each correction applied (masses per plane) and the readings with it on.
    coefficients : optional
        Influence coefficients of an earlier session (updated by Broyden's rule), or
    runs : optional
        the trial runs they came from (the trim runs join the least squares).
    **kwargs
        As :func:`influence_balance`.

    Returns
    -------
    InfluenceResult
        ``corrections``: what to add now; ``coefficients``: the updated alpha.
    """
    trims = list(trims)
    if not trims:
        raise BalanceError("trim: give at least one trim run (the correction applied and the "
                           "readings with it)")
    return influence_balance(initial, runs, trims=trims, coefficients=coefficients, **kwargs)


def influence_single_plane(initial: Any, trial: Any, trial_mass: float,
                           trial_angle: float = 0.0, *,
                           dA: float | None = None,
                           noise: NoiseModel | None = None) -> InfluenceResult:
    """Single-plane balancing with phase: W = -V0 / alpha, alpha = (V1 - V0) / T.

    Parameters
    ----------
    initial : (amplitude, phase_deg) or list of them
        Reading(s) without trial mass; several readings (sensors or speeds) are
        combined by least squares.
    trial : same shape as ``initial``
        Reading(s) with the trial mass.
    trial_mass : float
        The trial mass (any unit; the correction comes out in it).
    trial_angle : float
        Its angle (deg).
    dA : float, optional
        Uncertainty on every amplitude, see :func:`influence_balance`.
    noise : NoiseModel, optional
        See :func:`influence_balance`.

    Returns
    -------
    InfluenceResult
    """
    m = check_number(trial_mass, "trial_mass", positive=True)
    t = check_number(trial_angle, "trial_angle")
    return influence_balance(initial, [((m, t), trial)], dA=dA, noise=noise)


def influence_two_plane(initial: Any, trial_plane1: Any, trial_plane2: Any,
                        trial_mass: float, trial_angle: float = 0.0,
                        trial_mass2: float | None = None, trial_angle2: float | None = None,
                        *, dA: float | None = None,
                        noise: NoiseModel | None = None) -> InfluenceResult:
    """Two-plane balancing with phase (two sensors, or more points in least squares).

    Runs: initial; trial mass in plane 1 only; trial mass in plane 2 only (the
    first removed). alpha_i1 = (V1_i - V0_i) / T1, alpha_i2 = (V2_i - V0_i) / T2 and
    the corrections solve alpha W = -V0.

    Parameters
    ----------
    initial : list of (amplitude, phase_deg)
        One reading per sensor (at least two).
    trial_plane1, trial_plane2 : list of (amplitude, phase_deg)
        Readings with the trial mass in plane 1, then in plane 2.
    trial_mass, trial_angle : float
        Trial mass in plane 1 and its angle (deg).
    trial_mass2, trial_angle2 : float, optional
        The plane-2 trial mass and angle; default: the same as in plane 1.
    dA, noise : optional
        Uncertainty on every amplitude, or a noise model: see :func:`influence_balance`.

    Returns
    -------
    InfluenceResult

    Examples
    --------
    >>> r = influence_two_plane([(170, 112), (53, 78)], [(235, 94), (58, 68)],
    ...                         [(185, 115), (77, 104)], 1.15, 0.0)
    >>> [round(float(x), 3) for x in r.masses], [round(float(a), 1) for a in r.angles]
    ([1.979, 1.071], [236.2, 121.8])
    """
    m1 = check_number(trial_mass, "trial_mass", positive=True)
    t1 = check_number(trial_angle, "trial_angle")
    m2 = m1 if trial_mass2 is None else check_number(trial_mass2, "trial_mass2", positive=True)
    t2 = t1 if trial_angle2 is None else check_number(trial_angle2, "trial_angle2")
    runs = [([(m1, t1), None], trial_plane1), ([None, (m2, t2)], trial_plane2)]
    return influence_balance(initial, runs, dA=dA, noise=noise)
