"""Noise, intervals and conditioning of the influence-coefficient method.

Beyond the seed (its amplitude methods carry no phase). The noise model of a reading
V = A e^(i theta) is Gaussian and 1-sigma: sigma_A = sqrt((relative A)^2 + absolute^2)
on the amplitude (the same model as the resonance methods) and ``phase_noise``
(deg) on the phase, independent from reading to reading.

- **Intervals**: a parametric bootstrap. The readings are redrawn ``DRAWS`` times
  from the noise model around the measured values (fixed seed: the same scene
  gives the same interval), every draw is solved like the measurement, and the
  interval at confidence c is the (1 - c)/2 and (1 + c)/2 percentiles of each
  plane's correction mass and of its angle (angles as differences from the
  estimate, wrapped to (-180, 180]). Percentile intervals follow any monotonic
  transformation of the data (W = -V0 T / (V1 - V0) in one plane is one), so they
  keep their coverage when the correction is a ratio of noisy readings.
- **Conditioning**: the first-order perturbation bound of a least-squares solution,
  ||dW|| / ||W|| <= kappa(alpha) eps_V, with kappa the condition number (ratio of
  the extreme singular values) of the influence matrix and eps_V =
  ||sigma_V|| / ||V|| the relative 1-sigma noise of the readings the correction
  balances. Above ``AMPLIFICATION_LIMIT`` (10 % of the correction) the result gets
  a warning: the data do not determine the correction. The coefficients' own noise
  is checked run by run: a run whose reading change dV_k is less than 4 times its
  noise (||sigma_dV_k|| / ||dV_k|| > ``RUN_NOISE_LIMIT``) gets a warning too (the
  trial mass was too small for the noise).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from kinetostatics.common.angles import degree_column

from ..common import deg360
from ..model.noise import NoiseModel, parse_noise

__all__ = [
    "AMPLIFICATION_LIMIT",
    "DRAWS",
    "NoiseModel",
    "bootstrap_intervals",
    "conditioning",
    "conditioning_warnings",
    "parse_noise",
    "pinv_with_singular_values",
]

DRAWS = 4000
"""Bootstrap draws per interval (the percentiles' own scatter is then ~0.3 % of
coverage at 95 %)."""

AMPLIFICATION_LIMIT = 0.10
"""kappa * noise above this fraction of the correction gives a warning."""

RUN_NOISE_LIMIT = 0.25
"""A run whose reading change is less than 4 times its noise gives a warning."""

SEED = 20240514
"""Fixed seed of the bootstrap: repeated runs give the same interval."""


def pinv_with_singular_values(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``numpy.linalg.pinv(a)`` bit for bit and the singular values of a, from one SVD.

    pinv's own steps (numpy 2): the thin SVD of conj(a), singular values up to 1e-15 of
    the largest dropped, pinv = V S^+ U^H. A second ``svd(a, compute_uv=False)`` for the
    singular values cost half a pinv again (4000 2 x 2 matrices: 8 ms against 18 ms);
    these are the same numbers by another LAPACK road (dqds without the vectors, QR
    sweeps with them): they may differ in the last bit (measured: 4.4e-16 relative).

    Parameters
    ----------
    a : numpy.ndarray
        A stack of matrices (..., m, n).

    Returns
    -------
    pinv : numpy.ndarray
        (..., n, m), as ``numpy.linalg.pinv(a)``.
    s : numpy.ndarray
        The singular values (..., min(m, n)), descending.
    """
    u, s, vt = np.linalg.svd(a.conjugate(), full_matrices=False)
    cutoff = np.asarray(1e-15)[..., None] * np.amax(s, axis=-1, keepdims=True)
    large = s > cutoff
    inv = np.divide(1, s, where=large, out=s.copy())
    inv[~large] = 0
    return np.matmul(np.swapaxes(vt, -1, -2), inv[..., None] * np.swapaxes(u, -1, -2)), s


Solver = Callable[[np.ndarray, np.ndarray], np.ndarray]
"""Maps amplitudes and phases (k, rows, points) to corrections W (k, planes); NaN
rows where a draw cannot be solved."""


def bootstrap_intervals(solve: Solver, amps: np.ndarray, phases: np.ndarray,
                        W: np.ndarray, model: NoiseModel) -> tuple[list[dict], float]:
    """Percentile intervals of each plane's correction mass and angle.

    Parameters
    ----------
    solve : callable
        See :data:`Solver`.
    amps, phases : numpy.ndarray
        The measured readings (rows, points): amplitudes and phases (deg).
    W : numpy.ndarray of complex
        The estimate (planes,).
    model : NoiseModel

    Returns
    -------
    intervals : list of dict
        Per plane ``{"mass": [lo, hi], "angle": [lo, hi] or None}``; ``hi`` is None
        (unbounded) when more than (1 - confidence) / 2 of the draws could not be
        solved; the angle is [0, 360] when it is not bounded within a half turn.
    failed : float
        The fraction of draws that could not be solved.
    """
    rng = np.random.default_rng(SEED)
    shape = (DRAWS,) + amps.shape
    a = amps + model.amplitude_sigma(amps) * rng.standard_normal(shape)
    p = phases + model.phase * rng.standard_normal(shape)
    neg = a < 0.0                                  # a negative amplitude is the reading
    a, p = np.abs(a), np.where(neg, p + 180.0, p)  # half a turn away
    Wb = solve(a, p)
    ok = np.all(np.isfinite(Wb), axis=1)
    failed = 1.0 - float(ok.mean())
    tail = (1.0 - model.confidence) / 2.0
    q = (100.0 * tail, 100.0 * (1.0 - tail))
    out = []
    for j in range(W.size):
        mags = np.abs(Wb[:, j])
        mags = np.where(ok, mags, np.inf)          # an unsolvable draw: no bound
        lo, hi = np.percentile(mags, q)
        ang = None
        if abs(W[j]) > 0.0:
            d = degree_column(np.angle(Wb[ok, j] / W[j]))      # difference from the estimate
            dlo, dhi = np.percentile(d, q) if d.size else (-180.0, 180.0)
            c0 = degree_column(np.angle(W[j]))
            if failed > tail or dhi - dlo >= 180.0:
                ang = [0.0, 360.0]
            else:
                ang = [deg360(c0 + dlo), deg360(c0 + dhi)]
        out.append({"mass": [float(lo), float(hi) if np.isfinite(hi) else None],
                    "angle": ang})
    return out, failed


def conditioning(alpha: np.ndarray, V_amps: np.ndarray, dV: np.ndarray,
                 dV_sigma: np.ndarray, model: NoiseModel) -> tuple[float, float, np.ndarray]:
    """kappa(alpha), the amplification kappa eps_V and each run's relative noise.

    Parameters
    ----------
    alpha : numpy.ndarray of complex
        Influence coefficients (points, planes).
    V_amps : numpy.ndarray
        Amplitudes of the readings the correction balances (points,).
    dV : numpy.ndarray of complex
        The reading changes alpha was fitted to (runs, points); empty when the
        coefficients were given, not measured.
    dV_sigma : numpy.ndarray
        Their 1-sigma noise (runs, points).
    model : NoiseModel

    Returns
    -------
    kappa : float
        Ratio of the extreme singular values of alpha.
    amplification : float
        kappa eps_V, eps_V = ||sigma_V|| / ||V||: the first-order bound of the
        correction's relative error from the readings it balances.
    run_noise : numpy.ndarray
        ||sigma_dV_k|| / ||dV_k|| per run: how noisy the coefficients from it are.
    """
    s = np.linalg.svd(alpha, compute_uv=False)
    kappa = float(s[0] / s[-1]) if s[-1] > 0.0 else float("inf")
    norm_v = float(np.linalg.norm(V_amps))
    eps_v = float(np.linalg.norm(model.complex_sigma(V_amps))) / norm_v if norm_v else 0.0
    run_noise = np.zeros(0)
    if dV.size:
        with np.errstate(divide="ignore", invalid="ignore"):
            run_noise = np.linalg.norm(dV_sigma, axis=-1) / np.linalg.norm(dV, axis=-1)
    return kappa, kappa * eps_v, np.nan_to_num(run_noise, nan=np.inf)


def conditioning_warnings(kappa: float, amplification: float, run_noise: np.ndarray,
                          labels: list[str]) -> list[str]:
    """The warnings of :func:`conditioning`'s numbers (empty when all is well)."""
    out = []
    if amplification > AMPLIFICATION_LIMIT:
        out.append(f"the correction is not determined by the data: the influence matrix's "
                   f"condition number {kappa:.3g} times the readings' noise amplifies it to "
                   f"{100.0 * amplification:.3g} % of the correction (limit "
                   f"{100.0 * AMPLIFICATION_LIMIT:g} %); use other measurement points or "
                   "correction planes that act differently on them")
    for label, eps in zip(labels, run_noise, strict=True):
        if eps > RUN_NOISE_LIMIT:
            out.append(f"{label} changed the readings by only {1.0 / eps:.3g} times their "
                       f"noise (the influence coefficients from it are {100.0 * eps:.3g} % "
                       f"noise, limit {100.0 * RUN_NOISE_LIMIT:g} %): use a larger trial mass")
    return out
