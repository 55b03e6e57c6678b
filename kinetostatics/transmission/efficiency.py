"""Mechanical efficiency (seed 002 s. 4.3): mean, series, parallel, mixed, instantaneous.

Works are in J, powers in W; every efficiency is a plain number (or an array of them).
The mean efficiency of a mechanism over a kinematic cycle is the ratio of the work of the
useful resistances to the motor work (eq. 4.22); arrangements of mechanisms with known
efficiencies combine by eqs 4.26-4.32; where the losses change a lot along the cycle (cams
at small transmission angles), the instantaneous efficiency of eq. 4.35 describes them.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from ..model.errors import WorkbenchError


class EfficiencyError(WorkbenchError):
    """Efficiencies or works that do not describe a working mechanism."""


def _etas(etas: Any, what: str) -> np.ndarray:
    e = np.atleast_1d(np.asarray(etas, dtype=float))
    if e.ndim != 1 or e.size == 0:
        raise EfficiencyError(f"{what}: give a non-empty list of efficiencies")
    if not np.all(np.isfinite(e)) or np.any(e <= 0.0) or np.any(e > 1.0):
        raise EfficiencyError(f"{what}: every efficiency must lie in (0, 1], got {e.tolist()}")
    return e


def _works(works: Any, n: int, what: str) -> np.ndarray:
    w = np.atleast_1d(np.asarray(works, dtype=float))
    if w.shape != (n,):
        raise EfficiencyError(f"{what}: give one work per mechanism ({n}), got {w.size}")
    if not np.all(np.isfinite(w)) or np.any(w < 0.0) or not np.any(w > 0.0):
        raise EfficiencyError(f"{what}: works must be non-negative, and not all zero")
    return w


def mean_efficiency(useful_work: float, motor_work: float) -> float:
    """Mean efficiency over a kinematic cycle, eta = L_ru / L_m (eq. 4.22).

    Parameters
    ----------
    useful_work : float
        L_ru, J: work of the useful (technological) resistances over the cycle.
    motor_work : float
        L_m, J: work of the motor forces over the same cycle (> 0).
    """
    if not motor_work > 0.0:
        raise EfficiencyError(f"the motor work must be positive, got {motor_work!r}")
    return float(useful_work) / float(motor_work)


def loss_coefficient(passive_work: float, motor_work: float) -> float:
    """Loss coefficient psi = L_rp / L_m, so that eta = 1 - psi (eq. 4.23, L_m = L_ru + L_rp).

    The seed writes the coefficient with the letter phi.
    """
    if not motor_work > 0.0:
        raise EfficiencyError(f"the motor work must be positive, got {motor_work!r}")
    return float(passive_work) / float(motor_work)


def cycle_work(x: Any, y: Any) -> float:
    """Work over a cycle, the integral of a moment over the angle (or of a power over time).

    Composite Simpson's rule on an evenly spaced grid with an odd number of points (exact
    for cubics), the trapezoid rule otherwise.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if x.ndim != 1 or x.shape != y.shape or x.size < 2:
        raise EfficiencyError("cycle_work: x and y must be 1-D arrays of the same length >= 2")
    h = np.diff(x)
    if x.size % 2 == 1 and np.allclose(h, h[0], rtol=1e-12, atol=0.0):
        return float(h[0] / 3.0 * (y[0] + y[-1] + 4.0 * y[1:-1:2].sum() + 2.0 * y[2:-1:2].sum()))
    return float(np.trapezoid(y, x))


def cycle_efficiency(x: Any, motor: Any, useful: Any) -> float:
    """Mean efficiency (eq. 4.22) from a motor and a useful moment (or power) along a cycle.

    ``x`` is the driver angle (rad) with moments, or the time (s) with powers; the works
    L_m and L_ru are the integrals of :func:`cycle_work`.
    """
    return mean_efficiency(cycle_work(x, useful), cycle_work(x, motor))


def mean_powers(cycle_time: float, motor_work: float, useful_work: float,
                passive_work: float = 0.0) -> dict[str, float]:
    """Mean powers over a cycle of duration t_c: P = L / t_c (eq. 4.24), and eta = P_ru / P_m
    = 1 - P_rp / P_m (eq. 4.25)."""
    if not cycle_time > 0.0:
        raise EfficiencyError(f"the cycle time must be positive, got {cycle_time!r}")
    pm = motor_work / cycle_time
    return {"motor": pm, "useful": useful_work / cycle_time,
            "passive": passive_work / cycle_time,
            "efficiency": mean_efficiency(useful_work, motor_work)}


def series_works(motor_work: float, etas: Sequence[float]) -> np.ndarray:
    """Useful works at the output of each mechanism of a chain in series (eq. 4.26):
    L_ru,k = eta_1 ... eta_k L_m."""
    return float(motor_work) * np.cumprod(_etas(etas, "series_works"))


def series_efficiency(etas: Sequence[float]) -> float:
    """Mechanisms in series: eta = eta_1 eta_2 ... eta_n (eq. 4.27)."""
    return float(np.prod(_etas(etas, "series_efficiency")))


def parallel_efficiency(etas: Sequence[float], motor_works: Sequence[float] | None = None,
                        useful_works: Sequence[float] | None = None) -> float:
    """Mechanisms in parallel, given how the work is shared (eqs 4.28-4.30).

    With the motor works L_mi each mechanism receives: eta = sum(eta_i L_mi) / sum(L_mi)
    (eq. 4.29); with the useful works L_ru,i each delivers: eta = sum(L_ru,i) /
    sum(L_ru,i / eta_i) (eq. 4.30). Give exactly one of the two.
    """
    e = _etas(etas, "parallel_efficiency")
    if (motor_works is None) == (useful_works is None):
        raise EfficiencyError("parallel_efficiency: give exactly one of motor_works and "
                              "useful_works")
    if motor_works is not None:
        lm = _works(motor_works, e.size, "parallel_efficiency motor_works")
        return float(np.dot(e, lm) / lm.sum())
    lu = _works(useful_works, e.size, "parallel_efficiency useful_works")
    return float(lu.sum() / np.sum(lu / e))


def mixed_efficiency(series_etas: Sequence[float], parallel_etas: Sequence[float],
                     motor_works: Sequence[float] | None = None,
                     useful_works: Sequence[float] | None = None) -> float:
    """p mechanisms in series with a group of n in parallel (fig. 4.4, eqs 4.31-4.32).

    eta = eta_a1 ... eta_ap (sum eta_i L_mi) / (sum L_mi) (eq. 4.31), or with the useful
    works of the parallel branches eta = eta_a1 ... eta_ap (sum L_ru,i) / (sum L_ru,i / eta_i)
    (eq. 4.32).
    """
    return series_efficiency(series_etas) * parallel_efficiency(parallel_etas, motor_works,
                                                                useful_works)


def instantaneous_efficiency(motor_power: Any, useful_power: Any, gravity_power: Any = 0.0,
                             inertia_power: Any = 0.0, undefined: float = np.nan) -> np.ndarray:
    """Instantaneous efficiency (eq. 4.35).

    With P_G and P_i the powers of the weights and of the inertia forces (P_i = -dEc/dt,
    eq. 4.34), counted positive where they drive the mechanism:
    eta_i = (P_ru + |P_G + P_i|) / P_m where P_G + P_i resists (< 0), and
    eta_i = P_ru / (P_m + |P_G + P_i|) where it drives (>= 0). By the energy balance
    P_m - P_ru - P_rp + P_G + P_i = 0 (eq. 4.34) both equal 1 - P_rp / (power put in).

    Parameters
    ----------
    motor_power, useful_power : array_like
        P_m (W, delivered by the motor) and P_ru (W, absorbed by the useful resistances).
    gravity_power, inertia_power : array_like
        P_G and P_i, W, positive when driving.
    undefined : float
        Value where the power put in (P_m, plus P_G + P_i when they drive) is not positive.

    Returns
    -------
    numpy.ndarray
    """
    pm, pru, q = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (
        motor_power, useful_power, np.asarray(gravity_power, float) + inertia_power)))
    num = np.where(q < 0.0, pru - q, pru)
    den = np.where(q < 0.0, pm, pm + q)
    ok = den > 0.0
    return np.where(ok, num / np.where(ok, den, 1.0), undefined)


def efficiency_ratio(ideal_power: Any, real_power: Any, undefined: float = np.nan) -> np.ndarray:
    """Instantaneous efficiency as the ratio of the driving power without friction to the
    driving power with friction, eta = P_ideal / P_real (same load and motion).

    Only where no other power flows than the useful load and friction (no weights, no
    inertia forces: slow motion) does this equal eq. 4.35, P_ideal = P_ru and
    P_real = P_m = P_ru + P_rp; with inertia use :func:`instantaneous_efficiency`. The
    ratio is an efficiency only where both powers are driving powers: rows where
    ``real_power <= 0`` (the mechanism drives the motor) or ``ideal_power < 0`` get
    ``undefined``.
    """
    pi, pr = np.broadcast_arrays(np.asarray(ideal_power, float), np.asarray(real_power, float))
    ok = (pr > 0.0) & (pi >= 0.0)
    return np.where(ok, pi / np.where(ok, pr, 1.0), undefined)


__all__ = [
    "EfficiencyError", "cycle_efficiency", "cycle_work", "efficiency_ratio",
    "instantaneous_efficiency", "loss_coefficient", "mean_efficiency", "mean_powers",
    "mixed_efficiency", "parallel_efficiency", "series_efficiency", "series_works",
]
