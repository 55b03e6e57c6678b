"""Motion of the reduction element under forces (seed 002 ch. 4), generic over callables.

The mechanism enters only through its reduced quantities, as functions of the driver angle
phi (rad; arrays in, arrays out):

- ``inertia(phi) -> (I_r, dI_r/dphi)``: the reduced moment of inertia (eq. 2.75, with any
  flywheel) and its derivative, kg m^2 and kg m^2/rad;
- ``moment(phi, omega, t) -> M``: the total reduced moment, N m (motor plus loads,
  M_r = M_m - M_r^r, eqs 4.6-4.7). It is called with arrays of any shape (0-d included).

The motion obeys the equation in differential form (eqs 4.9-4.11)

    d(I_r omega^2 / 2)/dphi = M(phi, omega, t),    i.e.
    I_r omega domega/dphi + omega^2/2 dI_r/dphi = M,    dt/dphi = 1/omega,

whose finite form between two positions is the energy balance (eq. 4.8)
I_2 omega_2^2/2 - I_1 omega_1^2/2 = integral of M dphi.

Solvers:

- :func:`solve_recurrence`: the seed's explicit recurrence (eqs 4.13-4.16), first order;
- :func:`solve_energy`: position-only moments, omega^2 = (I_1 omega_1^2 + 2 int M dphi)/I
  (eq. 4.8) with Gauss-Legendre quadrature (the reference of SPEC's note on 4.14);
- :func:`simulate`: any M(phi, omega, t), a Dormand-Prince 5(4) integrator in phi with step
  control for (u, t), u = I_r omega^2 (twice the kinetic energy: du/dphi = 2M is smooth
  where omega is not), with the quartic dense output of Shampine (1986); optionally on a
  fixed grid per cycle with I_r evaluated once (``periodic_inertia``); the result,
  :class:`MotionSolution`, gives omega(phi), t(phi), alpha(phi), omega(t), eps(t), the
  extremes over the continuous cycle, the ``motion`` table and summary of the contract;
- :func:`periodic_solution`, :func:`flywheel_for_delta`, :func:`stopping`: the phases of
  s. 4.2, the degree of irregularity (eq. 4.20) and the dynamicity coefficient (eq. 4.21);
- :func:`recurrence_convergence`: the recurrence's error against the accurate solution.

Misprints noticed in the seed: the first line of eq. 4.11 drops a factor omega
(I_r omega domega/dphi = I_r domega/dt); eq. 4.14 solved from eq. 4.13 reads
omega_{i+1} = M_i dphi / (I_i omega_i) + omega_i (3 I_i - I_{i+1}) / (2 I_i).
"""

from __future__ import annotations

import math
import time as _time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from ..model.errors import WorkbenchError

TWO_PI = 2.0 * math.pi

Inertia = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]
Moment = Callable[[Any, Any, Any], Any]


class MotionError(WorkbenchError):
    """The motion cannot be computed: a stall, no periodic steady state, bad reduced data."""


# --------------------------------------------------------------------------- helpers

_GOLD = 0.5 * (3.0 - math.sqrt(5.0))


def golden_max(f: Callable[[float], float], a: float, b: float, *, xtol: float = 1e-12,
               maxiter: int = 200) -> tuple[float, float]:
    """Maximum of a unimodal function on [a, b] by golden-section search.

    The ends are compared too, so a maximum at an end (or at a corner) is found.

    Returns
    -------
    (x, f(x)) : tuple of float
    """
    if b < a:
        a, b = b, a
    fa, fb = f(a), f(b)
    x1, x2 = a + _GOLD * (b - a), b - _GOLD * (b - a)
    f1, f2 = f(x1), f(x2)
    for _ in range(maxiter):
        if b - a <= xtol * max(1.0, abs(a), abs(b)):
            break
        if f1 >= f2:
            b, x2, f2 = x2, x1, f1
            x1 = a + _GOLD * (b - a)
            f1 = f(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = b - _GOLD * (b - a)
            f2 = f(x2)
    best = max(((x1, f1), (x2, f2), (a, fa), (b, fb)), key=lambda p: p[1])
    return float(best[0]), float(best[1])


def _inertia_values(inertia: Inertia, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    out = inertia(phi)
    try:
        i_r, di_r = out
    except (TypeError, ValueError):
        raise MotionError("inertia(phi) must return a pair (I_r, dI_r/dphi)") from None
    i_r = np.broadcast_to(np.asarray(i_r, dtype=float), np.shape(phi))
    di_r = np.broadcast_to(np.asarray(di_r, dtype=float), np.shape(phi))
    bad = ~(i_r > 0.0) | ~np.isfinite(i_r) | ~np.isfinite(di_r)
    if np.any(bad):
        j = int(np.argmax(bad.ravel()))
        raise MotionError(f"the reduced moment of inertia must be positive and finite: I_r = "
                          f"{i_r.ravel()[j]!r} at driver angle "
                          f"{math.degrees(float(np.ravel(phi)[j])):.6g} deg")
    return i_r, di_r


def _moment_values(moment: Moment, phi: Any, omega: Any, t: Any) -> np.ndarray:
    m = np.asarray(moment(phi, omega, t), dtype=float)
    m = np.broadcast_to(m, np.broadcast(np.asarray(phi), np.asarray(omega)).shape)
    if not np.all(np.isfinite(m)):
        j = int(np.argmax(~np.isfinite(m).ravel()))
        raise MotionError(f"the reduced moment is not finite at driver angle "
                          f"{math.degrees(float(np.ravel(phi)[j % np.size(phi)])):.6g} deg")
    return m


def _position_moment(moment: Moment, phi: np.ndarray) -> np.ndarray:
    """M at positions for a moment that depends on the position only (omega, t = NaN)."""
    nan = np.full_like(phi, np.nan)
    m = np.asarray(moment(phi, nan, nan), dtype=float)
    if not np.all(np.isfinite(m)):
        raise MotionError("the moment is not finite when omega and t are unknown: it depends on "
                          "them, so it is not a position-only moment")
    return np.broadcast_to(m, phi.shape)


def _where(phi: float, phi0: float, cycle: float) -> str:
    k = math.floor((phi - phi0) / cycle + 1e-12)
    pos = math.degrees(phi0 + (phi - phi0) - k * cycle)
    return f"cycle {k + 1} at driver angle {pos:.6g} deg"


def _stall(phi: float, t: float | None, phi0: float, cycle: float) -> MotionError:
    when = "" if t is None else f" (t = {t:.6g} s)"
    return MotionError(f"the mechanism stalls: omega falls to 0 in {_where(phi, phi0, cycle)}"
                       f"{when}; the driving moment cannot overcome the loads there")


# --------------------------------------------------------------------------- recurrence

def solve_recurrence(inertia: Inertia, moment: Moment, phi: Any, omega0: float, *,
                     t0: float = 0.0, position_only: bool = False,
                     cycle: float = TWO_PI) -> pd.DataFrame:
    """The seed's recurrence (eqs 4.13-4.16) on a grid of driver angles; first order.

    omega_{i+1} = M_i dphi / (I_i omega_i) + omega_i (3 I_i - I_{i+1}) / (2 I_i)   (4.14)
    t_{i+1} = t_i + 2 dphi / (omega_i + omega_{i+1})                                (4.16)
    alpha_i = (M_i - omega_i^2 dI_i/2) / I_i      (eq. 4.10 times omega: alpha = omega domega/dphi)

    Parameters
    ----------
    inertia, moment : callable
        See the module docstring.
    phi : array_like
        Strictly increasing driver angles, rad; omega0 is the speed at phi[0].
    omega0 : float
        rad/s, > 0.
    t0 : float
        Time at phi[0], s.
    position_only : bool
        The moment ignores omega and t: it is evaluated once, vectorised, over the grid.
    cycle : float
        Length of a cycle (rad), to name the cycle in an error.

    Returns
    -------
    pandas.DataFrame
        ``phi`` (rad), ``time`` (s), ``omega`` (rad/s), ``alpha`` (rad/s^2).

    Raises
    ------
    MotionError
        If omega reaches 0 (a stall), naming the cycle and the driver angle.
    """
    phi = np.asarray(phi, dtype=float)
    if phi.ndim != 1 or phi.size < 2 or np.any(np.diff(phi) <= 0.0):
        raise MotionError("phi must be a strictly increasing 1-D array of at least 2 angles")
    if not omega0 > 0.0:
        raise MotionError(f"omega0 must be positive, got {omega0!r}")
    i_r, di_r = _inertia_values(inertia, phi)
    fixed = _position_moment(moment, phi) if position_only else None
    n = phi.size
    w = np.empty(n)
    t = np.empty(n)
    m = np.empty(n)
    w[0], t[0] = omega0, t0
    ir, ph = i_r.tolist(), phi.tolist()
    for i in range(n - 1):
        mi = fixed[i] if fixed is not None else float(_moment_values(moment, ph[i], w[i], t[i]))
        m[i] = mi
        dphi = ph[i + 1] - ph[i]
        w1 = mi * dphi / (ir[i] * w[i]) + w[i] * (3.0 * ir[i] - ir[i + 1]) / (2.0 * ir[i])
        if not w1 > 0.0:
            raise _stall(ph[i + 1], t[i], phi[0], cycle)
        w[i + 1] = w1
        t[i + 1] = t[i] + 2.0 * dphi / (w[i] + w1)
    m[-1] = fixed[-1] if fixed is not None else float(_moment_values(moment, ph[-1], w[-1], t[-1]))
    alpha = (m - 0.5 * w * w * di_r) / i_r
    return pd.DataFrame({"phi": phi, "time": t, "omega": w, "alpha": alpha})


# --------------------------------------------------------------------------- energy form

_GL_X, _GL_W = np.polynomial.legendre.leggauss(10)


def solve_energy(inertia: Inertia, moment: Moment, phi: Any, omega0: float, *,
                 t0: float = 0.0, breaks: Sequence[float] = (), tol: float = 1e-13,
                 cycle: float = TWO_PI) -> pd.DataFrame:
    """Exact motion for a position-only moment: the energy form of eq. 4.8.

    omega(phi)^2 = (I_r(phi_0) omega_0^2 + 2 W(phi)) / I_r(phi), W = integral of M from
    phi_0, and t(phi) = t0 + integral of dphi / omega. Both integrals use 10-point
    Gauss-Legendre panels, halved until two successive results agree to ``tol`` (relative
    to the kinetic energy and to the time span); give the angles where M has corners or
    jumps as ``breaks`` to keep the quadrature's high order.

    Parameters
    ----------
    inertia : callable
    moment : callable
        M(phi, omega, t); it is called with omega = t = NaN and must ignore them.
    phi : array_like
        Strictly increasing angles (rad) where the motion is wanted; omega0 at phi[0].
    omega0, t0 : float
    breaks : sequence of float
        Angles (rad) of corners of M (or I_r) inside the span.
    tol : float
    cycle : float
        Length of a cycle (rad), to name the cycle in an error.

    Returns
    -------
    pandas.DataFrame
        ``phi, time, omega, alpha`` as :func:`solve_recurrence`; ``attrs["quadrature_error"]``
        holds the last change of the relative energy and time.

    Raises
    ------
    MotionError
        If the kinetic energy reaches zero (a stall, located to 1e-12 rad).
    """
    phi = np.asarray(phi, dtype=float)
    if phi.ndim != 1 or phi.size < 1 or np.any(np.diff(phi) <= 0.0):
        raise MotionError("phi must be a strictly increasing 1-D array")
    if not omega0 > 0.0:
        raise MotionError(f"omega0 must be positive, got {omega0!r}")
    i0 = float(_inertia_values(inertia, phi[:1])[0][0])
    u0 = i0 * omega0 * omega0
    a, b = float(phi[0]), float(phi[-1])
    fixed = np.unique(np.concatenate((phi, [x for x in breaks if a < x < b])))
    counts = np.maximum(1, np.ceil(np.diff(fixed) / (cycle / 32.0) - 1e-9)).astype(int)
    prev = None
    err = (math.inf, math.inf)
    for _ in range(12):
        knots = _subdivide(fixed, counts)
        w_k, t_k = _energy_panels(inertia, moment, knots, u0, t0, phi[0], cycle)
        on = np.searchsorted(knots, fixed)
        w_f, t_f = w_k[on], t_k[on]
        if prev is not None:
            span_t = max(abs(t_f[-1] - t0), 1e-300)
            err = (float(np.max(np.abs(w_f - prev[0]))) / max(u0, float(np.max(np.abs(w_f)))),
                   float(np.max(np.abs(t_f - prev[1]))) / span_t)
            if max(err) <= tol:
                break
        prev = (w_f, t_f)
        counts = 2 * counts
    idx = np.searchsorted(fixed, phi)
    u = u0 + 2.0 * w_f[idx]
    i_r, di_r = _inertia_values(inertia, phi)
    w = np.sqrt(u / i_r)
    m = _position_moment(moment, phi)
    out = pd.DataFrame({"phi": phi, "time": t_f[idx], "omega": w,
                        "alpha": (m - 0.5 * w * w * di_r) / i_r})
    out.attrs["quadrature_error"] = err
    return out


def _subdivide(fixed: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """The fixed points with interval i cut into counts[i] equal panels (vectorised)."""
    if fixed.size == 1:
        return fixed
    start = np.repeat(fixed[:-1], counts)
    size = np.repeat(np.diff(fixed) / counts, counts)
    j = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    inner = start + j * size
    return np.concatenate((inner, fixed[-1:]))


def _energy_panels(inertia: Inertia, moment: Moment, knots: np.ndarray, u0: float, t0: float,
                   phi0: float, cycle: float) -> tuple[np.ndarray, np.ndarray]:
    """Work W and time t at the knots (Gauss-Legendre on each panel, nested for the time)."""
    if knots.size == 1:
        return np.zeros(1), np.full(1, t0)
    lo, hi = knots[:-1], knots[1:]
    half = 0.5 * (hi - lo)
    z = (lo + half)[:, None] + half[:, None] * _GL_X          # (m, n) panel nodes
    mz = _position_moment(moment, z)
    w_k = np.concatenate(([0.0], np.cumsum(half * (mz @ _GL_W))))
    # partial integrals from each panel's start to its nodes
    d = 0.5 * (z - lo[:, None])
    y = lo[:, None, None] + d[:, :, None] * (1.0 + _GL_X)
    w_z = w_k[:-1, None] + d * (_position_moment(moment, y) @ _GL_W)
    u_z = u0 + 2.0 * w_z
    u_k = u0 + 2.0 * w_k
    bad = np.any(u_z <= 0.0, axis=1) | (u_k[1:] <= 0.0)
    if np.any(bad):
        p = int(np.argmax(bad))
        end = z[p, int(np.argmax(u_z[p] <= 0.0))] if np.any(u_z[p] <= 0.0) else hi[p]
        raise _stall(_energy_zero(moment, lo[p], end, u0 + 2.0 * w_k[p]), None, phi0, cycle)
    i_z = _inertia_values(inertia, z)[0]
    t_k = t0 + np.concatenate(([0.0], np.cumsum(half * (np.sqrt(i_z / u_z) @ _GL_W))))
    return w_k, t_k


def _energy_zero(moment: Moment, lo: float, hi: float, u_lo: float) -> float:
    """Where u = u_lo + 2 int_lo^x M falls to zero in [lo, hi] (bisection)."""
    def u(x: float) -> float:
        h = 0.5 * (x - lo)
        nodes = lo + h * (1.0 + _GL_X)
        return u_lo + 2.0 * h * float(_position_moment(moment, nodes) @ _GL_W)
    a, b = lo, hi
    for _ in range(100):
        mid = 0.5 * (a + b)
        if u(mid) > 0.0:
            a = mid
        else:
            b = mid
        if b - a <= 1e-13 * max(1.0, abs(b)):
            break
    return 0.5 * (a + b)


# --------------------------------------------------------------------------- DP5(4)

_C = (1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0)
_A21 = 1 / 5
_A31, _A32 = 3 / 40, 9 / 40
_A41, _A42, _A43 = 44 / 45, -56 / 15, 32 / 9
_A51, _A52, _A53, _A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
_A61, _A62, _A63, _A64, _A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
_B1, _B3, _B4, _B5, _B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
_E1, _E3, _E4, _E5, _E6, _E7 = (-71 / 57600, 71 / 16695, -71 / 1920, 17253 / 339200,
                                -22 / 525, 1 / 40)
# Shampine's (1986) quartic continuous extension of the Dormand-Prince pair:
# y(p + theta h) = y + h sum_i k_i sum_j P_ij theta^j (j = 1..4).
_P = np.array([
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


def _scalar(moment: Moment, p: float, w: float, t: float) -> float:
    r = moment(p, w, t)
    x = r if isinstance(r, float) else float(np.asarray(r, dtype=float).item())
    if not math.isfinite(x):
        raise MotionError(f"the reduced moment is not finite at driver angle "
                          f"{math.degrees(p):.6g} deg (omega = {w:.6g} rad/s)")
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
            raise MotionError(f"driver angle outside the integrated span [{math.degrees(lo):.6g}"
                              f", {math.degrees(hi):.6g}] deg")
        n = self.phi.size - 1
        k = np.clip(np.searchsorted(self.phi, phi, side="right") - 1, 0, max(n - 1, 0))
        if n == 0:
            return np.full(phi.shape, self.u[0]), np.full(phi.shape, self.t[0])
        h = self.phi[k + 1] - self.phi[k]
        th = np.clip((phi - self.phi[k]) / h, 0.0, 1.0)
        powers = np.stack((th, th * th, th**3, th**4), axis=-1)            # (..., 4)
        inc = np.einsum("...cj,...j->...c", self.q[k], powers) * h[..., None]
        return self.u[k] + inc[..., 0], self.t[k] + inc[..., 1]

    def state(self, phi: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """omega (rad/s), t (s) and alpha = domega/dt (rad/s^2) at driver angles ``phi``.

        alpha = omega domega/dphi = (M - omega^2 dI_r/dphi / 2) / I_r (eqs 4.10-4.11).
        """
        phi = np.asarray(phi, dtype=float)
        u, t = self._dense(phi)
        i_r, di_r = _inertia_values(self.inertia, phi)
        w = np.sqrt(np.maximum(u, 0.0) / i_r)
        m = _moment_values(self.moment, phi, w, t)
        return w, t, (m - 0.5 * w * w * di_r) / i_r

    def omega(self, phi: Any) -> np.ndarray:
        """omega (rad/s) at driver angles ``phi`` (rad)."""
        phi = np.asarray(phi, dtype=float)
        return np.sqrt(np.maximum(self._dense(phi)[0], 0.0)
                       / _inertia_values(self.inertia, phi)[0])

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
            i_r = _inertia_values(self.inertia, p)[0]
            dp = (times - t) * np.sqrt(np.maximum(u, 1e-300) / i_r)
            p = np.clip(p + dp, self.phi[k], self.phi[k + 1])
            if np.all(np.abs(dp) <= 1e-15 * np.maximum(1.0, np.abs(p))):
                break
        w, _, alpha = self.state(p)
        return p, w, alpha

    def extremes(self, a: float, b: float, per_step: int = 8) -> dict[str, float]:
        """omega_max, omega_min and max |alpha| over [a, b] (rad) and where they are.

        The dense output is sampled ``per_step`` times per step; the best samples are refined
        by golden-section search on the dense output (omega) and on alpha computed from it.
        """
        nodes = self.phi[(self.phi > a) & (self.phi < b)]
        edges = np.concatenate(([a], nodes, [b]))
        th = np.arange(per_step) / per_step
        x = np.concatenate(((edges[:-1, None] + np.diff(edges)[:, None] * th).ravel(), [b]))
        w, _, alpha = self.state(x)
        out: dict[str, float] = {}
        for name, vals, fun in (
                ("omega_max", w, lambda p: float(self.omega(np.array([p]))[0])),
                ("omega_min", -w, lambda p: -float(self.omega(np.array([p]))[0])),
                ("alpha_abs_max", np.abs(alpha),
                 lambda p: abs(float(self.state(np.array([p]))[2][0])))):
            best_x, best_v = x[int(np.argmax(vals))], float(np.max(vals))
            for j in _top_peaks(vals, 3):
                xm, vm = golden_max(fun, x[max(j - 1, 0)], x[min(j + 1, x.size - 1)],
                                    xtol=1e-13)
                if vm > best_v:
                    best_x, best_v = xm, vm
            out[name] = -best_v if name == "omega_min" else best_v
            out[name + "_at"] = best_x
        return out

    def cycle_stats(self, k: int | None = None) -> dict[str, float]:
        """Speed fluctuation over cycle ``k`` (1-based; default the last complete one).

        ``omega_mean`` = cycle / period (the time average), ``omega_max``, ``omega_min``,
        ``delta`` = (omega_max - omega_min) / omega_mean (eq. 4.20), ``alpha_max`` = max
        |alpha|, ``chi`` = alpha_max / omega_mean^2 (eq. 4.21), ``period`` (s), and the
        driver angles (rad) of the extremes.
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
        ex = self.extremes(a, b)
        return {"omega_mean": mean, "omega_max": ex["omega_max"], "omega_min": ex["omega_min"],
                "delta": (ex["omega_max"] - ex["omega_min"]) / mean,
                "alpha_max": ex["alpha_abs_max"], "chi": ex["alpha_abs_max"] / mean**2,
                "period": period, "omega_max_at": ex["omega_max_at"],
                "omega_min_at": ex["omega_min_at"], "alpha_max_at": ex["alpha_abs_max_at"]}

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
        start = math.degrees(self.phi0)
        span = math.degrees(self.cycle)
        pos = (np.linspace(start, start + span, 361) if positions is None
               else np.asarray(positions, dtype=float))
        if np.any(pos < start - 1e-9) or np.any(pos > start + span + 1e-9):
            raise MotionError(f"positions must lie within [{start:g}, {start + span:g}] deg")
        n = self.complete_cycles
        cyc = np.repeat(np.arange(1, n + 1), pos.size)
        p = np.tile(pos, n)
        phi = np.radians(p) + (cyc - 1) * self.cycle
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
            start = math.degrees(self.phi0)
            pos = (np.linspace(start, start + math.degrees(self.cycle), 361)
                   if positions is None else np.asarray(positions, dtype=float))
            phi = np.radians(pos) + (n - 1) * self.cycle
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


def simulate(inertia: Inertia, moment: Moment, phi0: float, omega0: float, cycles: int = 1, *,
             t0: float = 0.0, rtol: float = 1e-12, cycle: float = TWO_PI,
             span: float | None = None, stop_at_rest: bool = False,
             periodic_inertia: bool = False, max_steps: int = 2_000_000) -> MotionSolution:
    """Integrate the equation of motion (eq. 4.9) for any M(phi, omega, t).

    Dormand-Prince 5(4) in phi on the state (u, t), u = I_r omega^2:
    du/dphi = 2 M(phi, sqrt(u/I_r), t), dt/dphi = sqrt(I_r/u). Steps are at most cycle/32
    long and land on every cycle boundary phi0 + k cycle. M is evaluated stage by stage (it
    depends on the state); I_r, at stage angles known before the stage is taken:

    - by default the step size is controlled and each step evaluates I_r at its five new
      stage angles in one vectorised call;
    - with ``periodic_inertia`` (I_r has the cycle as its period, e.g. a mechanism's reduced
      inertia over a crank turn) the steps form a fixed grid of n per cycle, n chosen cycle
      by cycle (doubled from 64 while some step's error estimate exceeds ``rtol``, halved
      when all are far below); I_r is evaluated in one call at all 5n stage angles of a
      grid, once per grid size, and reused for every cycle. Use it when I_r is costly (a
      kinematic solve). Near a stall the adaptive integrator takes over.

    Parameters
    ----------
    inertia, moment : callable
        See the module docstring.
    phi0 : float
        Start angle, rad.
    omega0 : float
        Speed at phi0, rad/s, > 0.
    cycles : int
        Number of cycles to integrate.
    t0 : float
        Time at phi0, s.
    rtol : float
        Local relative tolerance of a step on u and t. The default gives omega to about
        1e-10 relative over tens of cycles.
    cycle : float
        Length of a cycle, rad (the period of I_r and M in phi).
    span : float, optional
        Integrate from phi0 to phi0 + span instead of whole cycles (not with
        ``periodic_inertia``).
    stop_at_rest : bool
        If omega falls to 0, end there (``rest`` holds where and when) instead of raising.
    periodic_inertia : bool
        Evaluate I_r once per cycle on a fixed grid (see above).
    max_steps : int
        Limit of the adaptive integrator's steps.

    Returns
    -------
    MotionSolution

    Raises
    ------
    MotionError
        A stall (omega falls to 0: names the cycle and the driver angle), unless
        ``stop_at_rest``.
    """
    if not omega0 > 0.0:
        raise MotionError(f"omega0 must be positive, got {omega0!r}")
    if span is None:
        if int(cycles) != cycles or cycles < 1:
            raise MotionError(f"cycles must be an integer >= 1, got {cycles!r}")
        span = cycles * cycle
    elif periodic_inertia:
        raise MotionError("periodic_inertia integrates whole cycles: give cycles, not span")
    if not span > 0.0:
        raise MotionError("the span to integrate must be positive")
    phi0 = float(phi0)
    i0 = float(_inertia_values(inertia, np.array([phi0]))[0][0])
    u0 = i0 * omega0 * omega0
    if periodic_inertia:
        return _dp5_grid(_CycleGrid(inertia, phi0, cycle), 0.0, inertia, moment, u0, float(t0),
                         int(cycles), rtol, stop_at_rest)
    return _dp5(inertia, moment, phi0, u0, float(t0), phi0 + span, rtol, cycle, stop_at_rest,
                max_steps)


def _step(moment: Moment, p: float, h: float, u: float, t: float, ku1: float, kt1: float,
          stage_i: Sequence[float]) -> tuple | None:
    """One Dormand-Prince 5(4) step of (u, t) from p to p + h; ``stage_i`` holds I_r at
    p + c h for c = 1/5, 3/10, 4/5, 8/9, 1. None where a stage would have u <= 0."""
    u2 = u + h * _A21 * ku1
    if not u2 > 0.0:
        return None
    t2 = t + h * _A21 * kt1
    w = math.sqrt(u2 / stage_i[0])
    ku2, kt2 = 2.0 * _scalar(moment, p + _C[0] * h, w, t2), 1.0 / w
    u3 = u + h * (_A31 * ku1 + _A32 * ku2)
    if not u3 > 0.0:
        return None
    t3 = t + h * (_A31 * kt1 + _A32 * kt2)
    w = math.sqrt(u3 / stage_i[1])
    ku3, kt3 = 2.0 * _scalar(moment, p + _C[1] * h, w, t3), 1.0 / w
    u4 = u + h * (_A41 * ku1 + _A42 * ku2 + _A43 * ku3)
    if not u4 > 0.0:
        return None
    t4 = t + h * (_A41 * kt1 + _A42 * kt2 + _A43 * kt3)
    w = math.sqrt(u4 / stage_i[2])
    ku4, kt4 = 2.0 * _scalar(moment, p + _C[2] * h, w, t4), 1.0 / w
    u5 = u + h * (_A51 * ku1 + _A52 * ku2 + _A53 * ku3 + _A54 * ku4)
    if not u5 > 0.0:
        return None
    t5 = t + h * (_A51 * kt1 + _A52 * kt2 + _A53 * kt3 + _A54 * kt4)
    w = math.sqrt(u5 / stage_i[3])
    ku5, kt5 = 2.0 * _scalar(moment, p + _C[3] * h, w, t5), 1.0 / w
    u6 = u + h * (_A61 * ku1 + _A62 * ku2 + _A63 * ku3 + _A64 * ku4 + _A65 * ku5)
    if not u6 > 0.0:
        return None
    t6 = t + h * (_A61 * kt1 + _A62 * kt2 + _A63 * kt3 + _A64 * kt4 + _A65 * kt5)
    w = math.sqrt(u6 / stage_i[4])
    ku6, kt6 = 2.0 * _scalar(moment, p + h, w, t6), 1.0 / w
    un = u + h * (_B1 * ku1 + _B3 * ku3 + _B4 * ku4 + _B5 * ku5 + _B6 * ku6)
    if not un > 0.0:
        return None
    tn = t + h * (_B1 * kt1 + _B3 * kt3 + _B4 * kt4 + _B5 * kt5 + _B6 * kt6)
    w = math.sqrt(un / stage_i[4])
    ku7, kt7 = 2.0 * _scalar(moment, p + h, w, tn), 1.0 / w
    eu = h * (_E1 * ku1 + _E3 * ku3 + _E4 * ku4 + _E5 * ku5 + _E6 * ku6 + _E7 * ku7)
    et = h * (_E1 * kt1 + _E3 * kt3 + _E4 * kt4 + _E5 * kt5 + _E6 * kt6 + _E7 * kt7)
    ks = ((ku1, kt1), (ku2, kt2), (ku3, kt3), (ku4, kt4), (ku5, kt5), (ku6, kt6), (ku7, kt7))
    return un, tn, ks, eu, et


class _Track:
    """Accepted nodes and stage slopes, turned into a :class:`MotionSolution` at the end."""

    def __init__(self, p: float, u: float, t: float) -> None:
        self.ps, self.us, self.ts, self.ks = [p], [u], [t], []

    def add(self, p: float, u: float, t: float, ks: tuple) -> None:
        self.ps.append(p)
        self.us.append(u)
        self.ts.append(t)
        self.ks.append(ks)

    def solution(self, inertia: Inertia, moment: Moment, phi0: float, cycle: float,
                 rest: tuple[float, float] | None) -> MotionSolution:
        k = np.asarray(self.ks, dtype=float).reshape(-1, 7, 2)
        q = np.einsum("nsc,sj->ncj", k, _P)
        return MotionSolution(np.asarray(self.ps), np.asarray(self.us), np.asarray(self.ts), q,
                              inertia, moment, phi0, cycle, rest)


def _tolerances(rtol: float, cycle: float, u0: float, i0: float) -> tuple[float, float]:
    """Absolute tolerances of u and t (J, s) that go with rtol."""
    return 1e-9 * rtol * u0, rtol * cycle / math.sqrt(u0 / i0)


def _dp5(inertia: Inertia, moment: Moment, phi0: float, u0: float, t0: float, end: float,
         rtol: float, cycle: float, stop_at_rest: bool, max_steps: int,
         track: _Track | None = None, origin: float | None = None) -> MotionSolution:
    """Adaptive Dormand-Prince 5(4) from (phi0, u0, t0) to ``end``; ``origin`` is where
    cycle 1 starts (for the cycle boundaries and the messages)."""
    origin = phi0 if origin is None else origin
    h_max = cycle / 32.0
    h_min = 1e-13 * max(cycle, abs(end))
    i0 = float(_inertia_values(inertia, np.array([phi0]))[0][0])
    atol_u, atol_t = _tolerances(rtol, cycle, u0, i0)
    p, u, t = phi0, u0, t0
    w = math.sqrt(u / i0)
    ku1, kt1 = 2.0 * _scalar(moment, p, w, t), 1.0 / w
    track = _Track(p, u, t) if track is None else track
    h = h_max / 4.0
    nb = 1
    rest = None
    steps = 0
    while p < end:
        while origin + nb * cycle <= p + 1e-12 * cycle:
            nb += 1
        target = min(end, origin + nb * cycle)
        last = h >= target - p
        if last:
            h = target - p
        steps += 1
        if steps > max_steps:
            raise MotionError(f"no progress after {max_steps} steps near "
                              f"{_where(p, origin, cycle)}")
        stage_i = _inertia_values(inertia, np.array([p + c * h for c in _C]))[0].tolist()
        out = _step(moment, p, h, u, t, ku1, kt1, stage_i)
        if out is not None:
            un, tn, ks, eu, et = out
            err = max(abs(eu) / (atol_u + rtol * max(u, un)),
                      abs(et) / (atol_t + rtol * max(abs(t), abs(tn))))
            if err <= 1.0:
                p = target if last else p + h
                u, t = un, tn
                ku1, kt1 = ks[6]
                track.add(p, u, t, ks)
                h = min(h_max, h * (5.0 if err == 0.0 else min(5.0, 0.9 * err ** -0.2)))
                continue
            h *= max(0.2, 0.9 * err ** -0.2)
        else:
            h *= 0.25
        if h < h_min:
            if ku1 >= 0.0:
                raise MotionError(f"the integration cannot proceed near "
                                  f"{_where(p, origin, cycle)}: check the moment and inertia")
            # omega ~ 0: u falls linearly (du/dphi = 2M), a uniform deceleration
            p_rest = p + u / -ku1
            t_rest = t + 2.0 * (p_rest - p) * kt1
            if not stop_at_rest:
                raise _stall(p_rest, t_rest, origin, cycle)
            rest = (p_rest, t_rest)
            break
    return track.solution(inertia, moment, origin, cycle, rest)


class _CycleGrid:
    """I_r at every stage angle of a grid of n equal steps per cycle, from one vectorised call;
    valid for every cycle when I_r has the cycle as its period. ``extra`` is a flywheel."""

    def __init__(self, inertia: Inertia, phi0: float, cycle: float) -> None:
        self.inertia, self.phi0, self.cycle = inertia, phi0, cycle
        self._cache: dict[int, list[list[float]]] = {}

    def stages(self, n: int) -> list[list[float]]:
        """Row j: I_r at phi0 + (j + c) h, c = 0, 1/5, 3/10, 4/5, 8/9, 1 (h = cycle / n)."""
        if n not in self._cache:
            c = np.array((0.0, *_C[:-1]))
            pts = self.phi0 + (np.arange(n)[:, None] + c) * (self.cycle / n)
            vals = _inertia_values(self.inertia, pts)[0]
            self._cache[n] = np.column_stack((vals, np.roll(vals[:, 0], -1))).tolist()
        return self._cache[n]


def _dp5_grid(grid: _CycleGrid, extra: float, inertia: Inertia, moment: Moment, u0: float,
              t0: float, cycles: int, rtol: float, stop_at_rest: bool) -> MotionSolution:
    """Dormand-Prince 5(4) on fixed grids of n steps per cycle, I_r from the grid's cache.

    Each cycle starts with the previous cycle's n (64 at first) and is redone with 2n while
    some step's error estimate exceeds rtol; n is halved for the next cycle when the largest
    estimate is below 1/64 of rtol. Beyond 4096 steps per cycle, or where a stage would
    reach omega = 0, the adaptive integrator takes over from the cycle's start (it locates
    a stall)."""
    phi0, cycle = grid.phi0, grid.cycle
    end = phi0 + cycles * cycle
    n = 64
    atol_u, atol_t = _tolerances(rtol, cycle, u0, grid.stages(n)[0][0] + extra)
    p, u, t = phi0, u0, t0
    w = math.sqrt(u / (grid.stages(n)[0][0] + extra))
    k1 = (2.0 * _scalar(moment, p, w, t), 1.0 / w)
    track = _Track(p, u, t)
    for c in range(cycles):
        start = phi0 + c * cycle
        while True:
            rows, h = grid.stages(n), cycle / n
            nodes, worst = [], 0.0
            uu, tt, (ku1, kt1) = u, t, k1
            for j in range(n):
                row = rows[j]
                pj = start + j * h
                out = _step(moment, pj, h, uu, tt, ku1, kt1,
                            [row[1] + extra, row[2] + extra, row[3] + extra, row[4] + extra,
                             row[5] + extra])
                if out is None:
                    worst = math.inf
                    break
                un, tn, ks, eu, et = out
                worst = max(worst, abs(eu) / (atol_u + rtol * max(uu, un)),
                            abs(et) / (atol_t + rtol * max(abs(tt), abs(tn))))
                if worst > 1.0:
                    break
                uu, tt = un, tn
                ku1, kt1 = ks[6]
                nodes.append((start + (j + 1) * h if j < n - 1 else start + cycle, uu, tt, ks))
            if worst <= 1.0:
                break
            if math.isinf(worst) or n >= 4096:
                return _dp5(inertia, moment, start, u, t, end, rtol, cycle, stop_at_rest,
                            2_000_000, track=track, origin=phi0)
            n *= 2
        for node in nodes:
            track.add(*node)
        u, t, k1 = uu, tt, (ku1, kt1)
        if worst < 1.0 / 64.0 and n > 64:
            n //= 2
    return track.solution(inertia, moment, phi0, cycle, None)


def _with_flywheel(inertia: Inertia, extra: float) -> Inertia:
    if extra == 0.0:
        return inertia

    def inertia_j(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        i_r, di_r = inertia(phi)
        return np.asarray(i_r, dtype=float) + extra, di_r
    return inertia_j


# --------------------------------------------------------------------------- phases

def stopping(inertia: Inertia, moment: Moment, phi0: float, omega0: float, *,
             max_cycles: int = 10_000, rtol: float = 1e-12,
             cycle: float = TWO_PI) -> MotionSolution:
    """The stopping phase (s. 4.2, eq. 4.18): integrate until omega falls to 0.

    ``moment`` is the reduced moment without the motor (the loads, friction, a brake).
    The result's ``rest`` holds the driver angle (rad) and the time (s) of rest; the last
    part of the run-down, where omega -> 0, is closed as a uniform deceleration.

    Raises
    ------
    MotionError
        If the mechanism is still moving after ``max_cycles`` cycles.
    """
    sol = simulate(inertia, moment, phi0, omega0, span=max_cycles * cycle, rtol=rtol,
                   cycle=cycle, stop_at_rest=True)
    if sol.rest is None:
        raise MotionError(f"the mechanism is still moving after {max_cycles} cycles")
    return sol


def periodic_solution(inertia: Inertia, moment: Moment, phi0: float, omega_guess: float, *,
                      rtol: float = 1e-12, cycle: float = TWO_PI, tol: float = 1e-10,
                      maxiter: int = 60, periodic_inertia: bool = False) -> MotionSolution:
    """The steady state (s. 4.2, eq. 4.19): the motion with omega(phi0) = omega(phi0 + cycle).

    The cycle map omega0 -> omega(phi0 + cycle) is solved for its fixed point by the secant
    method on g(omega0) = map(omega0) - omega0, from ``omega_guess`` and its image, to ``tol``
    relative. M must not depend on t explicitly (t restarts at 0). A position-only moment
    with zero net work per cycle leaves every speed periodic: the guess is returned.
    ``periodic_inertia`` as in :func:`simulate`.

    Returns
    -------
    MotionSolution
        One cycle from the periodic omega0; ``cycle_stats()`` gives delta and chi.

    Raises
    ------
    MotionError
        If no periodic speed is found within a factor 1000 of the guess (the net work per
        cycle does not vanish at any speed, or the mechanism stalls).
    """
    grid = _CycleGrid(inertia, float(phi0), cycle) if periodic_inertia else None
    return _periodic(inertia, moment, float(phi0), omega_guess, rtol, cycle, tol, maxiter,
                     grid, 0.0)


def _periodic(inertia: Inertia, moment: Moment, phi0: float, omega_guess: float, rtol: float,
              cycle: float, tol: float, maxiter: int, grid: _CycleGrid | None,
              extra: float) -> MotionSolution:
    inertia_j = _with_flywheel(inertia, extra)
    i0 = float(_inertia_values(inertia_j, np.array([phi0]))[0][0])

    def run(w: float) -> tuple[MotionSolution, float]:
        if grid is None:
            sol = _dp5(inertia_j, moment, phi0, i0 * w * w, 0.0, phi0 + cycle, rtol, cycle,
                       False, 2_000_000)
        else:
            sol = _dp5_grid(grid, extra, inertia_j, moment, i0 * w * w, 0.0, 1, rtol, False)
        return sol, sol.omega_end - w

    w0 = float(omega_guess)
    if not w0 > 0.0:
        raise MotionError(f"omega_guess must be positive, got {omega_guess!r}")
    s0, g0 = run(w0)
    if abs(g0) <= tol * w0:
        return s0
    w1 = w0 + g0
    for _ in range(maxiter):
        for _ in range(40):
            try:
                s1, g1 = run(w1)
                break
            except MotionError:
                w1 = 0.5 * (w1 + w0)
        else:
            raise MotionError("no periodic steady state: the mechanism stalls near the "
                              f"speeds tried ({w0:.6g} rad/s)")
        if abs(g1) <= tol * w1:
            return s1
        if g1 == g0:
            break
        w2 = w1 - g1 * (w1 - w0) / (g1 - g0)
        if w2 <= 0.0:
            w2 = 0.5 * w1
        if not 1e-3 * omega_guess < w2 < 1e3 * omega_guess:
            break                       # running away: no steady state near the guess
        w0, g0, w1 = w1, g1, w2
    raise MotionError(f"no periodic steady state found from omega = {omega_guess:.6g} rad/s: "
                      f"the speed still changes by {g1:.3g} rad/s per cycle (the net work "
                      "per cycle does not vanish at any speed?)")


def flywheel_for_delta(inertia: Inertia, moment: Moment, target_delta: float, phi0: float,
                       omega_guess: float, *, rtol: float = 1e-12, cycle: float = TWO_PI,
                       tol: float = 1e-9, maxiter: int = 60,
                       periodic_inertia: bool = False) -> float:
    """Flywheel moment of inertia J whose periodic steady state has delta = target (eq. 4.20).

    J is added to I_r (pass I_r without any flywheel: J replaces it); 0 is returned when
    delta without a flywheel is already at most the target. delta falls roughly like
    1/(I_r + J), so the root of 1/delta(J) - 1/target (a nearly linear function) is found by
    the secant method inside a bracket, to ``tol`` relative in J (the workbench promises
    1e-6). ``periodic_inertia`` as in :func:`simulate`: I_r is then evaluated once for all
    the trials.

    Returns
    -------
    float
        J, kg m^2.
    """
    if not target_delta > 0.0:
        raise MotionError(f"target_delta must be positive, got {target_delta!r}")
    phi0 = float(phi0)
    grid = _CycleGrid(inertia, phi0, cycle) if periodic_inertia else None
    guess = [float(omega_guess)]

    def inv_delta(j: float) -> float:
        sol = _periodic(inertia, moment, phi0, guess[0], rtol, cycle, 1e-10, 60, grid, j)
        guess[0] = sol.omega0
        return 1.0 / sol.cycle_stats()["delta"] - 1.0 / target_delta

    h0 = inv_delta(0.0)
    if h0 >= 0.0:
        return 0.0
    i_mean = float(np.mean(_inertia_values(inertia, phi0 + cycle * np.arange(256) / 256)[0]))
    lo, h_lo = 0.0, h0
    hi = i_mean * max(1.0 / (target_delta * (h0 + 1.0 / target_delta)) - 1.0, 1e-3)
    h_hi = inv_delta(hi)
    while h_hi < 0.0:
        lo, h_lo = hi, h_hi
        hi *= 4.0
        h_hi = inv_delta(hi)
    x0, f0, x1, f1 = lo, h_lo, hi, h_hi
    for _ in range(maxiter):
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0) if f1 != f0 else 0.5 * (lo + hi)
        if not lo < x2 < hi:
            x2 = 0.5 * (lo + hi)
        f2 = inv_delta(x2)
        if f2 < 0.0:
            lo = x2
        else:
            hi = x2
        if abs(x2 - x1) <= tol * abs(x2) or f2 == 0.0:
            return x2
        x0, f0, x1, f1 = x1, f1, x2, f2
    raise MotionError("the flywheel for the target delta was not found")


# --------------------------------------------------------------------------- speed vs error

def recurrence_convergence(inertia: Inertia, moment: Moment, phi0: float, omega0: float, *,
                           span: float = TWO_PI, divisions: Sequence[int] = (
                               36, 72, 144, 288, 576, 1152),
                           position_only: bool = False, rtol: float = 1e-12) -> pd.DataFrame:
    """Error of the seed's recurrence (eq. 4.14) against the accurate solution, by step.

    The reference is :func:`solve_energy` for a position-only moment, else :func:`simulate`.

    Returns
    -------
    pandas.DataFrame
        ``step`` (deg), ``steps``, ``max_error`` (rad/s, the largest |omega - omega_ref| over
        the grid), ``max_rel_error`` (over omega_ref), ``wall_time`` (s, the recurrence).
        ``attrs``: ``order`` (slope of log max_error against log step), ``reference``
        (its method), ``reference_wall_time`` (s).
    """
    grids = [np.linspace(phi0, phi0 + span, n + 1) for n in divisions]
    tic = _time.perf_counter()
    if position_only:
        finest = np.unique(np.concatenate(grids))
        ref = solve_energy(inertia, moment, finest, omega0)
        ref_w = ref["omega"].to_numpy()

        def reference(g: np.ndarray) -> np.ndarray:
            return ref_w[np.searchsorted(finest, g)]
        method = "energy form (eq. 4.8), Gauss-Legendre"
    else:
        sol = simulate(inertia, moment, phi0, omega0, span=span, rtol=rtol)

        def reference(g: np.ndarray) -> np.ndarray:
            return sol.omega(np.minimum(g, sol.phi[-1]))
        method = "Dormand-Prince 5(4), dense output"
    ref_time = _time.perf_counter() - tic
    rows = []
    for n, g in zip(divisions, grids, strict=True):
        tic = _time.perf_counter()
        rec = solve_recurrence(inertia, moment, g, omega0, position_only=position_only)
        wall = _time.perf_counter() - tic
        wr = reference(g)
        err = np.abs(rec["omega"].to_numpy() - wr)
        rows.append({"step": math.degrees(span / n), "steps": n, "max_error": float(err.max()),
                     "max_rel_error": float(np.max(err / wr)), "wall_time": wall})
    table = pd.DataFrame(rows)
    ok = table["max_error"] > 0.0
    table.attrs["order"] = (float(np.polyfit(np.log(table["step"][ok]),
                                             np.log(table["max_error"][ok]), 1)[0])
                            if ok.sum() >= 2 else math.nan)
    table.attrs["reference"] = method
    table.attrs["reference_wall_time"] = ref_time
    return table


__all__ = [
    "Inertia", "Moment", "MotionError", "MotionSolution", "flywheel_for_delta", "golden_max",
    "periodic_solution", "recurrence_convergence", "simulate", "solve_energy",
    "solve_recurrence", "stopping",
]
