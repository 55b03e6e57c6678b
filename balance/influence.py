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
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ._util import angle_of, check_number, deg360_array, polar
from .errors import BalanceError
from .uncertainty import Interval, propagate

__all__ = [
    "InfluenceResult",
    "influence_balance",
    "influence_coefficients",
    "influence_single_plane",
    "influence_two_plane",
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
        alpha, shape (measurement points, planes): reading per unit trial mass.
    initial : numpy.ndarray of complex
        The initial readings V0.
    residual : numpy.ndarray of complex
        Predicted readings after correction, V0 + alpha W (zero for square systems).
    uncertainty : list of Interval or None
        Per plane, bounds of mass and angle for a given +-dA on every amplitude.
    """

    masses: np.ndarray
    angles: np.ndarray
    corrections: np.ndarray = field(repr=False)
    coefficients: np.ndarray = field(repr=False)
    initial: np.ndarray = field(repr=False)
    residual: np.ndarray = field(repr=False)
    uncertainty: list[Interval] | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: corrections per plane and the predicted residual readings."""
        d: dict[str, Any] = {
            "corrections": [{"plane": j + 1, "mass": float(m), "angle": float(a)}
                            for j, (m, a) in enumerate(zip(self.masses, self.angles,
                                                           strict=True))],
            "residual_vibration": [{"amplitude": float(abs(v)), "phase": angle_of(complex(v))}
                                   for v in self.residual],
        }
        if self.uncertainty is not None:
            d["uncertainty"] = [u.to_dict() for u in self.uncertainty]
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
    return amp * np.exp(1j * np.radians(phase_deg))


# -------------------------------------------------------------------- solving
def _solve_batch(amps: np.ndarray, phases: np.ndarray, T_pinv: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Influence coefficients and corrections for many amplitude sets at once.

    amps, phases: (k, runs + 1, points), row 0 the initial readings.
    Returns alpha (k, points, planes) and W (k, planes).
    """
    V = _to_complex(amps, phases)
    dV = V[:, 1:, :] - V[:, :1, :]                       # V_k - V0 = alpha T_k
    alpha = np.swapaxes(T_pinv @ dV, 1, 2)               # least squares over the runs
    W = -(np.linalg.pinv(alpha) @ V[:, 0, :, None])[..., 0]   # min |V0 + alpha W|
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
    _, _, T, amps, phases = _prepare(initial, runs)
    alpha, _ = _solve_batch(amps[None], phases[None], np.linalg.pinv(T))
    return alpha[0]


def _prepare(initial: Any, runs: Iterable[tuple[Any, Any]]):
    V0 = _readings(initial, "initial readings")
    runs = list(runs)
    if not runs:
        raise BalanceError("influence method: no trial runs given")
    trials, reads = [], []
    for k, run in enumerate(runs):
        if not (isinstance(run, Sequence) and len(run) == 2):
            raise BalanceError(f"trial run {k + 1} must be a pair (trial masses, readings)")
        t, v = run
        if isinstance(t, complex | np.complexfloating) or _is_pair_of_numbers(t):
            t = [t]                                      # one plane: a single trial mass
        trials.append([_mass(x, f"trial run {k + 1}, plane {j + 1}") for j, x in enumerate(t)])
        rk = _readings(v, f"trial run {k + 1} readings")
        if rk.shape[0] != V0.shape[0]:
            raise BalanceError(f"trial run {k + 1}: {rk.shape[0]} readings, but the initial "
                               f"run has {V0.shape[0]}; give one per measurement point")
        reads.append(rk)
    n_planes = len(trials[0])
    if any(len(t) != n_planes for t in trials):
        raise BalanceError("trial runs give trial masses for different numbers of planes")
    T = np.array(trials, dtype=complex)                  # (runs, planes)
    if len(runs) < n_planes:
        raise BalanceError(f"{len(runs)} trial run(s) for {n_planes} planes: give at least "
                           "one trial run per plane")
    s = np.linalg.svd(T, compute_uv=False)
    if s[-1] <= _COND_LIMIT * s[0]:
        raise BalanceError("the trial runs do not put trial masses in every plane "
                           "independently (their trial vectors are dependent)")
    if V0.shape[0] < n_planes:
        raise BalanceError(f"{V0.shape[0]} measurement point(s) for {n_planes} planes: give "
                           "at least as many readings (sensors or speeds) as planes")
    data = np.stack([V0] + reads)                        # (runs + 1, points, 2)
    return V0, n_planes, T, data[..., 0], data[..., 1]


def influence_balance(initial: Any, runs: Iterable[tuple[Any, Any]], *,
                      trial_radius: float | None = None,
                      correction_radius: float | None = None,
                      dA: float | None = None) -> InfluenceResult:
    """Correction masses by the influence-coefficient method, any number of planes.

    alpha from V_k - V0 = alpha T_k over the trial runs (least squares when there
    are more runs than planes), then W = -alpha^+ V0 (least squares over the
    measurement points: several sensors and/or several speeds stacked in the
    readings). See the module docstring for conventions.

    Parameters
    ----------
    initial : sequence
        Initial readings V0: (amplitude, phase_deg) pairs or complex numbers, one per
        measurement point (sensor, or sensor at one speed).
    runs : iterable of (trials, readings)
        Trial masses per plane ((mass, angle_deg), complex or None) and the readings.
    trial_radius, correction_radius : float, optional
        Give both to convert masses at the trial radius to the correction radius.
    dA : float, optional
        Uncertainty +-dA on every amplitude (phases taken as exact): adds per-plane
        intervals of mass and angle (corner evaluation over all amplitudes, with
        linearised half widths; see :mod:`balance.uncertainty`).

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
    V0, n_planes, T, amps, phases = _prepare(initial, runs)
    if (trial_radius is None) != (correction_radius is None):
        raise BalanceError("give both trial_radius and correction_radius, or neither")
    ratio = 1.0
    if trial_radius is not None:
        ratio = (check_number(trial_radius, "trial_radius", positive=True)
                 / check_number(correction_radius, "correction_radius", positive=True))
    T_pinv = np.linalg.pinv(T)
    alpha, W = _solve_batch(amps[None], phases[None], T_pinv)
    alpha, W = alpha[0], W[0]
    s = np.linalg.svd(alpha, compute_uv=False)
    if s[0] == 0.0 or s[-1] <= _COND_LIMIT * s[0]:
        raise BalanceError("the influence coefficients cannot separate the planes: the trial "
                           "masses changed the readings too little or in the same way; use "
                           "larger trial masses or other measurement points")
    V0c = _to_complex(amps[0], phases[0])
    residual = V0c + alpha @ W
    Wc = W * ratio
    unc = None
    if dA is not None:
        d = check_number(dA, "dA", nonnegative=True)
        shape = amps.shape

        def batch(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            a = pts.reshape((-1,) + shape)
            p = np.broadcast_to(phases, a.shape)
            _, Wb = _solve_batch(a, p, T_pinv)
            Wb = Wb * ratio
            return np.abs(Wb), np.degrees(np.angle(Wb))

        unc = propagate(batch, amps.ravel(), d, "measured amplitudes")
    return InfluenceResult(masses=np.abs(Wc), angles=deg360_array(np.degrees(np.angle(Wc))),
                           corrections=Wc, coefficients=alpha, initial=V0c, residual=residual,
                           uncertainty=unc)


def influence_single_plane(initial: Any, trial: Any, trial_mass: float,
                           trial_angle: float = 0.0, *,
                           dA: float | None = None) -> InfluenceResult:
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

    Returns
    -------
    InfluenceResult
    """
    m = check_number(trial_mass, "trial_mass", positive=True)
    t = check_number(trial_angle, "trial_angle")
    return influence_balance(initial, [((m, t), trial)], dA=dA)


def influence_two_plane(initial: Any, trial_plane1: Any, trial_plane2: Any,
                        trial_mass: float, trial_angle: float = 0.0,
                        trial_mass2: float | None = None, trial_angle2: float | None = None,
                        *, dA: float | None = None) -> InfluenceResult:
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
    dA : float, optional
        Uncertainty on every amplitude, see :func:`influence_balance`.

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
    return influence_balance(initial, runs, dA=dA)
