"""The equation of motion of the reduction element (seed 002 ch. 4): its types, the seed's
explicit recurrence (eqs 4.13-4.16, first order) and the energy form for position-only
moments (eq. 4.8).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import pandas as pd

from ..common.angles import degrees_text
from ..model.errors import WorkbenchError

TWO_PI = 2.0 * math.pi

Inertia = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]
Moment = Callable[[Any, Any, Any], Any]


class MotionError(WorkbenchError):
    """The motion cannot be computed: a stall, no periodic steady state, bad reduced data."""


# --------------------------------------------------------------------------- helpers

_GOLD = 0.5 * (3.0 - math.sqrt(5.0))


_AHEAD = 5
"""Iterations of :func:`golden_max` whose points are announced at once (``ahead``): 62
points a batch. A kinematic solve of 1 to 126 angles costs about the same (0.7 ms), so on
four_bar_motion 5 makes 210 solves where 3 made 331 (0.36 s -> 0.16 s of CPU), 6 178."""


def _branches(a: float, b: float, x1: float, x2: float, depth: int) -> list[float]:
    """Every point the next ``depth`` iterations of :func:`golden_max` may evaluate from
    the bracket (a, x1, x2, b), whichever way each comparison goes (the same expressions
    as the search's, so the same numbers): 2 + 4 + ... + 2^depth points."""
    out, states = [], [(a, b, x1, x2)]
    for _ in range(depth):
        nxt = []
        for a_, b_, x1_, x2_ in states:
            lo = a_ + _GOLD * (x2_ - a_)        # f1 >= f2: b <- x2, x2 <- x1, a new x1
            hi = b_ - _GOLD * (b_ - x1_)        # else: a <- x1, x1 <- x2, a new x2
            out += [lo, hi]
            nxt += [(a_, x2_, lo, x1_), (x1_, b_, x2_, hi)]
        states = nxt
    return out


def golden_max(f: Callable[[float], float], a: float, b: float, *, xtol: float = 1e-12,
               maxiter: int = 200,
               ahead: Callable[[list[float]], None] | None = None) -> tuple[float, float]:
    """Maximum of a unimodal function on [a, b] by golden-section search.

    The ends are compared too, so a maximum at an end (or at a corner) is found.
    ``ahead``, when given, is told every :data:`_AHEAD` iterations the points those
    iterations may evaluate (:func:`_branches`), e.g. to compute them in one batch
    where one point costs as much as many; it changes no result.

    Returns
    -------
    (x, f(x)) : tuple of float
    """
    if b < a:
        a, b = b, a
    x1, x2 = a + _GOLD * (b - a), b - _GOLD * (b - a)
    if ahead is not None:
        ahead([a, b, x1, x2, *_branches(a, b, x1, x2, _AHEAD)])
    fa, fb = f(a), f(b)
    f1, f2 = f(x1), f(x2)
    for i in range(maxiter):
        if b - a <= xtol * max(1.0, abs(a), abs(b)):
            break
        if ahead is not None and i and i % _AHEAD == 0:
            ahead(_branches(a, b, x1, x2, _AHEAD))
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


def inertia_values(inertia: Inertia, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
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
                          f"{degrees_text(float(np.ravel(phi)[j]))} deg")
    return i_r, di_r


def inertia_at(inertia: Inertia, phi: np.ndarray) -> float:
    """I_r at one driver angle (``phi``: an array of one): ``inertia_values(inertia,
    phi)[0]``'s number, without its arrays; where it is not positive and finite (or not
    one number), :func:`inertia_values` is asked again and says why."""
    out = inertia(phi)
    if type(out) is tuple and len(out) == 2:
        i_r, di_r = np.asarray(out[0], dtype=float), np.asarray(out[1], dtype=float)
        if i_r.size == 1 and di_r.size == 1:
            x, d = float(i_r.item()), float(di_r.item())
            if x > 0.0 and math.isfinite(x) and math.isfinite(d):
                return x
    return float(inertia_values(inertia, phi)[0].ravel()[0])


def moment_values(moment: Moment, phi: Any, omega: Any, t: Any) -> np.ndarray:
    m = np.asarray(moment(phi, omega, t), dtype=float)
    m = np.broadcast_to(m, np.broadcast(np.asarray(phi), np.asarray(omega)).shape)
    if not np.all(np.isfinite(m)):
        j = int(np.argmax(~np.isfinite(m).ravel()))
        raise MotionError(f"the reduced moment is not finite at driver angle "
                          f"{degrees_text(float(np.ravel(phi)[j % np.size(phi)]))} deg")
    return m


def _position_moment(moment: Moment, phi: np.ndarray) -> np.ndarray:
    """M at positions for a moment that depends on the position only (omega, t = NaN)."""
    nan = np.full_like(phi, np.nan)
    m = np.asarray(moment(phi, nan, nan), dtype=float)
    if not np.all(np.isfinite(m)):
        raise MotionError("the moment is not finite when omega and t are unknown: it depends on "
                          "them, so it is not a position-only moment")
    return np.broadcast_to(m, phi.shape)


def where_text(phi: float, phi0: float, cycle: float) -> str:
    k = math.floor((phi - phi0) / cycle + 1e-12)
    return f"cycle {k + 1} at driver angle {degrees_text(phi0 + (phi - phi0) - k * cycle)} deg"


def stall_error(phi: float, t: float | None, phi0: float, cycle: float) -> MotionError:
    when = "" if t is None else f" (t = {t:.6g} s)"
    return MotionError(f"the mechanism stalls: omega falls to 0 in {where_text(phi, phi0, cycle)}"
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
    i_r, di_r = inertia_values(inertia, phi)
    fixed = _position_moment(moment, phi) if position_only else None
    n = phi.size
    w = np.empty(n)
    t = np.empty(n)
    m = np.empty(n)
    w[0], t[0] = omega0, t0
    ir, ph = i_r.tolist(), phi.tolist()
    for i in range(n - 1):
        mi = fixed[i] if fixed is not None else float(moment_values(moment, ph[i], w[i], t[i]))
        m[i] = mi
        dphi = ph[i + 1] - ph[i]
        w1 = mi * dphi / (ir[i] * w[i]) + w[i] * (3.0 * ir[i] - ir[i + 1]) / (2.0 * ir[i])
        if not w1 > 0.0:
            raise stall_error(ph[i + 1], t[i], phi[0], cycle)
        w[i + 1] = w1
        t[i + 1] = t[i] + 2.0 * dphi / (w[i] + w1)
    m[-1] = fixed[-1] if fixed is not None else float(moment_values(moment, ph[-1], w[-1], t[-1]))
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
    i0 = float(inertia_values(inertia, phi[:1])[0][0])
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
    i_r, di_r = inertia_values(inertia, phi)
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
        raise stall_error(_energy_zero(moment, lo[p], end, u0 + 2.0 * w_k[p]), None, phi0, cycle)
    i_z = inertia_values(inertia, z)[0]
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
