"""The Dormand-Prince 5(4) tableau with Shampine's quartic dense output, and
:class:`MotionSolution`: omega(phi), t(phi), alpha(phi), the extremes over the continuous
cycle, the ``motion`` table and its summary (eqs 4.20, 4.21).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from ..common.angles import degree_value, degrees_text, radian_column
from .equation import (
    TWO_PI,
    Inertia,
    Moment,
    MotionError,
    golden_max,
    inertia_at,
    inertia_values,
    moment_values,
)

# --------------------------------------------------------------------------- DP5(4)

DP5_C = (1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0)
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
B1, B3, B4, B5, B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
E1, E3, E4, E5, E6, E7 = (-71 / 57600, 71 / 16695, -71 / 1920, 17253 / 339200,
                                -22 / 525, 1 / 40)
# Shampine's (1986) quartic continuous extension of the Dormand-Prince pair:
# y(p + theta h) = y + h sum_i k_i sum_j P_ij theta^j (j = 1..4).
DP5_P = np.array([
    [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933,
     87487479700 / 32700410799],
    [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408,
     701980252875 / 199316789632],
    [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
])


def scalar_moment(moment: Moment, p: float, w: float, t: float) -> float:
    return moment_float(moment(p, w, t), p, w)


def moment_float(r: Any, p: float, w: float) -> float:
    """The moment ``r`` returned at driver angle ``p`` and speed ``w`` as a Python float
    (the same number), checked finite."""
    x = float(r) if isinstance(r, float) else float(np.asarray(r, dtype=float).item())
    if not math.isfinite(x):
        raise MotionError(f"the reduced moment is not finite at driver angle "
                          f"{degrees_text(p)} deg (omega = {w:.6g} rad/s)")
    return x


@dataclass
class MotionSolution:
    """The integrated motion: nodes of the accepted steps and their dense output.

    Evaluate anywhere in the span with :meth:`state` (omega, t, alpha at driver angles),
    :meth:`at_time` (phi, omega, alpha at times), and summarise a cycle with
    :meth:`cycle_stats` (eqs 4.20-4.21).

    Attributes
    ----------
    phi, u, t : numpy.ndarray
        Driver angle (rad), u = I_r omega^2 (J, twice the kinetic energy) and time (s) at the
        nodes.
    phi0 : float
        Start of the motion, rad (cycle 1 starts here).
    cycle : float
        Length of a cycle, rad.
    rest : tuple of float or None
        (phi, t) where the motion came to rest, for :func:`stopping`.
    omega0 : float
        Speed at phi0.
    """

    phi: np.ndarray
    u: np.ndarray
    t: np.ndarray
    q: np.ndarray = field(repr=False)
    inertia: Inertia = field(repr=False)
    moment: Moment = field(repr=False)
    phi0: float = 0.0
    cycle: float = TWO_PI
    rest: tuple[float, float] | None = None

    @property
    def omega0(self) -> float:
        """Speed at the start, rad/s."""
        return float(self.state(np.array([self.phi[0]]))[0][0])

    @property
    def omega_end(self) -> float:
        """Speed at the last node, rad/s."""
        return float(self.state(np.array([self.phi[-1]]))[0][0])

    @property
    def complete_cycles(self) -> int:
        """Number of whole cycles integrated from phi0."""
        return int(math.floor((self.phi[-1] - self.phi0) / self.cycle + 1e-9))

    def _dense(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        phi = np.asarray(phi, dtype=float)
        lo, hi = self.phi[0], self.phi[-1]
        tol = 1e-9 * max(1.0, abs(hi))
        if phi.size and (np.min(phi) < lo - tol or np.max(phi) > hi + tol):
            raise MotionError(f"driver angle outside the integrated span [{degrees_text(lo)}"
                              f", {degrees_text(hi)}] deg")
        n = self.phi.size - 1
        k = np.clip(np.searchsorted(self.phi, phi, side="right") - 1, 0, max(n - 1, 0))
        if n == 0:
            return np.full(phi.shape, self.u[0]), np.full(phi.shape, self.t[0])
        h = self.phi[k + 1] - self.phi[k]
        th = np.clip((phi - self.phi[k]) / h, 0.0, 1.0)
        powers = np.stack((th, th * th, th**3, th**4), axis=-1)            # (..., 4)
        inc = np.einsum("...cj,...j->...c", self.q[k], powers) * h[..., None]
        return self.u[k] + inc[..., 0], self.t[k] + inc[..., 1]

    def omega_at(self, phi: float) -> float:
        """omega (rad/s) at one driver angle: ``float(omega(np.array([phi]))[0])``, the same
        number (the same operations on the one point, numpy's where the order of a sum or a
        power is numpy's), at a tenth of the cost; for the searches of :meth:`extremes`."""
        n = self.phi.size - 1
        if n == 0 or not self.phi[0] <= phi <= self.phi[-1]:
            return float(self.omega(np.array([phi]))[0])      # an end case, or an error
        k = min(bisect.bisect_right(self.phi, phi) - 1, n - 1)   # searchsorted, clipped
        a = float(self.phi[k])
        h = float(self.phi[k + 1]) - a
        th = min(max((phi - a) / h, 0.0), 1.0)
        thv = np.array([th])
        powers = np.array([[th, th * th, (thv**3)[0], (thv**4)[0]]])
        inc = np.einsum("...cj,...j->...c", self.q[k:k + 1], powers)[0, 0] * h
        u = float(self.u[k]) + inc
        return math.sqrt(max(u, 0.0) / inertia_at(self.inertia, np.array([phi])))

    def state(self, phi: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """omega (rad/s), t (s) and alpha = domega/dt (rad/s^2) at driver angles ``phi``.

        alpha = omega domega/dphi = (M - omega^2 dI_r/dphi / 2) / I_r (eqs 4.10-4.11).
        """
        phi = np.asarray(phi, dtype=float)
        u, t = self._dense(phi)
        i_r, di_r = inertia_values(self.inertia, phi)
        w = np.sqrt(np.maximum(u, 0.0) / i_r)
        m = moment_values(self.moment, phi, w, t)
        return w, t, (m - 0.5 * w * w * di_r) / i_r

    def omega(self, phi: Any) -> np.ndarray:
        """omega (rad/s) at driver angles ``phi`` (rad)."""
        phi = np.asarray(phi, dtype=float)
        return np.sqrt(np.maximum(self._dense(phi)[0], 0.0)
                       / inertia_values(self.inertia, phi)[0])

    def at_time(self, times: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """phi (rad), omega (rad/s) and epsilon = alpha (rad/s^2) at ``times`` (s).

        The dense output's t(phi) is inverted by Newton's method in each step
        (dt/dphi = 1/omega), so omega(t) and eps(t) keep the integrator's accuracy.
        """
        times = np.asarray(times, dtype=float)
        if times.size and (np.min(times) < self.t[0] - 1e-12 * abs(self.t[-1])
                           or np.max(times) > self.t[-1] * (1 + 1e-12) + 1e-300):
            raise MotionError(f"time outside the integrated span [{self.t[0]:.6g}, "
                              f"{self.t[-1]:.6g}] s")
        k = np.clip(np.searchsorted(self.t, times, side="right") - 1, 0, self.t.size - 2)
        p = self.phi[k] + (self.phi[k + 1] - self.phi[k]) * np.clip(
            (times - self.t[k]) / (self.t[k + 1] - self.t[k]), 0.0, 1.0)
        for _ in range(30):
            u, t = self._dense(p)
            i_r = inertia_values(self.inertia, p)[0]
            dp = (times - t) * np.sqrt(np.maximum(u, 1e-300) / i_r)
            p = np.clip(p + dp, self.phi[k], self.phi[k + 1])
            if np.all(np.abs(dp) <= 1e-15 * np.maximum(1.0, np.abs(p))):
                break
        w, _, alpha = self.state(p)
        return p, w, alpha

    def extremes(self, a: float, b: float, per_step: int = 8,
                 alpha: bool = True) -> dict[str, float]:
        """omega_max, omega_min and max |alpha| over [a, b] (rad) and where they are.

        The dense output is sampled ``per_step`` times per step; the best samples are refined
        by golden-section search on the dense output (omega) and on alpha computed from it.
        ``alpha=False`` leaves max |alpha| out (a third of the searches): the speeds are
        the same numbers, found first either way.
        """
        nodes = self.phi[(self.phi > a) & (self.phi < b)]
        edges = np.concatenate(([a], nodes, [b]))
        th = np.arange(per_step) / per_step
        x = np.concatenate(((edges[:-1, None] + np.diff(edges)[:, None] * th).ravel(), [b]))
        # (omega alone: state's omega, bit for bit, without the moment at every sample)
        w, _, acc = self.state(x) if alpha else (self.omega(x), None, None)
        out: dict[str, float] = {}
        searches = [("omega_max", w, self.omega_at),
                    ("omega_min", -w, lambda p: -self.omega_at(p))]
        if alpha:
            searches.append(("alpha_abs_max", np.abs(acc),
                             lambda p: abs(float(self.state(np.array([p]))[2][0]))))
        for name, vals, fun in searches:
            best_x, best_v = x[int(np.argmax(vals))], float(np.max(vals))
            for j in _top_peaks(vals, 3):
                xm, vm = golden_max(fun, x[max(j - 1, 0)], x[min(j + 1, x.size - 1)],
                                    xtol=1e-13, ahead=getattr(self.inertia, "prefetch", None))
                if vm > best_v:
                    best_x, best_v = xm, vm
            out[name] = -best_v if name == "omega_min" else best_v
            out[name + "_at"] = best_x
        return out

    def cycle_stats(self, k: int | None = None, alpha: bool = True) -> dict[str, float]:
        """Speed fluctuation over cycle ``k`` (1-based; default the last complete one).

        ``omega_mean`` = cycle / period (the time average), ``omega_max``, ``omega_min``,
        ``delta`` = (omega_max - omega_min) / omega_mean (eq. 4.20), ``alpha_max`` = max
        |alpha|, ``chi`` = alpha_max / omega_mean^2 (eq. 4.21), ``period`` (s), and the
        driver angles (rad) of the extremes. ``alpha=False``: the speeds only (no
        ``alpha_max``, ``chi``, ``alpha_max_at``; see :meth:`extremes`).
        """
        n = self.complete_cycles
        if n < 1:
            raise MotionError("less than one whole cycle was integrated")
        k = n if k is None else k
        if not 1 <= k <= n:
            raise MotionError(f"cycle {k} is not among the {n} integrated")
        a = self.phi0 + (k - 1) * self.cycle
        b = a + self.cycle
        ta, tb = self._dense(np.array([a, b]))[1]
        period = float(tb - ta)
        mean = self.cycle / period
        ex = self.extremes(a, b, alpha=alpha)
        out = {"omega_mean": mean, "omega_max": ex["omega_max"], "omega_min": ex["omega_min"],
               "delta": (ex["omega_max"] - ex["omega_min"]) / mean, "period": period,
               "omega_max_at": ex["omega_max_at"], "omega_min_at": ex["omega_min_at"]}
        if alpha:
            out.update(alpha_max=ex["alpha_abs_max"], chi=ex["alpha_abs_max"] / mean**2,
                       alpha_max_at=ex["alpha_abs_max_at"])
        return out

    def cycles(self, steady_tol: float = 1e-6) -> pd.DataFrame:
        """One row per whole cycle: speeds at its ends, period, the work of M over it, phase.

        ``work`` = integral of M dphi = change of the kinetic energy (eq. 4.8; I_r is periodic)
        and ``phase`` (s. 4.2): ``start-up`` where the speed grows over the cycle (L_m > L_r,
        eq. 4.17), ``stopping`` where it falls (eq. 4.18), ``steady`` where it repeats to
        ``steady_tol`` of omega_mean (L_m = L_r, eq. 4.19).
        """
        n = self.complete_cycles
        ends = self.phi0 + self.cycle * np.arange(n + 1)
        u, t = self._dense(ends)
        w = self.omega(ends)
        period = np.diff(t)
        mean = self.cycle / period
        dw = np.diff(w)
        phase = np.where(np.abs(dw) <= steady_tol * mean, "steady",
                         np.where(dw > 0.0, "start-up", "stopping"))
        return pd.DataFrame({"cycle": np.arange(1, n + 1), "omega_start": w[:-1],
                             "omega_end": w[1:], "period": period, "omega_mean": mean,
                             "work": 0.5 * np.diff(u), "phase": phase})

    def table(self, positions: Any = None) -> pd.DataFrame:
        """The motion at given driver positions of every whole cycle.

        Parameters
        ----------
        positions : array_like, optional
            Driver angles in degrees within [start, start + cycle] (start = degrees(phi0));
            default 361 positions over the cycle.

        Returns
        -------
        pandas.DataFrame
            ``cycle`` (from 1), ``position`` (deg), ``time`` (s since the start),
            ``omega`` (rad/s), ``alpha`` (rad/s^2).
        """
        start = degree_value(self.phi0)
        span = degree_value(self.cycle)
        pos = (np.linspace(start, start + span, 361) if positions is None
               else np.asarray(positions, dtype=float))
        if np.any(pos < start - 1e-9) or np.any(pos > start + span + 1e-9):
            raise MotionError(f"positions must lie within [{start:g}, {start + span:g}] deg")
        n = self.complete_cycles
        cyc = np.repeat(np.arange(1, n + 1), pos.size)
        p = np.tile(pos, n)
        phi = radian_column(p) + (cyc - 1) * self.cycle
        w, t, alpha = self.state(phi)
        return pd.DataFrame({"cycle": cyc, "position": p, "time": t, "omega": w,
                             "alpha": alpha})

    def summary(self, positions: Any = None, steady_tol: float = 1e-6) -> dict[str, Any]:
        """The last whole cycle's ``omega_mean, omega_max, omega_min, delta, chi, period`` and
        ``steady`` (the largest change of omega between the last two cycles, over the
        positions, at most ``steady_tol`` omega_mean; false with one cycle)."""
        st = self.cycle_stats()
        out: dict[str, Any] = {key: st[key] for key in ("omega_mean", "omega_max", "omega_min",
                                                        "delta", "chi", "period")}
        n = self.complete_cycles
        steady = False
        if n >= 2:
            start = degree_value(self.phi0)
            pos = (np.linspace(start, start + degree_value(self.cycle), 361)
                   if positions is None else np.asarray(positions, dtype=float))
            phi = radian_column(pos) + (n - 1) * self.cycle
            change = np.max(np.abs(self.omega(phi) - self.omega(phi - self.cycle)))
            steady = bool(change <= steady_tol * st["omega_mean"])
        out["steady"] = steady
        return out


def _top_peaks(vals: np.ndarray, count: int) -> list[int]:
    """Indices of the ``count`` largest local maxima of a sampled sequence (ends included)."""
    left = np.concatenate(([True], vals[1:] >= vals[:-1]))
    right = np.concatenate((vals[:-1] >= vals[1:], [True]))
    peaks = np.flatnonzero(left & right)
    return peaks[np.argsort(vals[peaks])[::-1][:count]].tolist()
