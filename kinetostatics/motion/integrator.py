"""Integration of d(I_r omega^2 / 2)/dphi = M(phi, omega, t) (eq. 4.9) with the
Dormand-Prince 5(4) pair and step control, optionally on a fixed grid per cycle.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .equation import (
    TWO_PI,
    Inertia,
    Moment,
    MotionError,
    inertia_values,
    stall_error,
    where_text,
)
from .solution import (
    A21,
    A31,
    A32,
    A41,
    A42,
    A43,
    A51,
    A52,
    A53,
    A54,
    A61,
    A62,
    A63,
    A64,
    A65,
    B1,
    B3,
    B4,
    B5,
    B6,
    DP5_C,
    DP5_P,
    E1,
    E3,
    E4,
    E5,
    E6,
    E7,
    MotionSolution,
    moment_float,
    scalar_moment,
)


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
    i0 = float(inertia_values(inertia, np.array([phi0]))[0][0])
    u0 = i0 * omega0 * omega0
    if periodic_inertia:
        return dp5_grid(CycleGrid(inertia, phi0, cycle), 0.0, inertia, moment, u0, float(t0),
                         int(cycles), rtol, stop_at_rest)
    return dp5_run(inertia, moment, phi0, u0, float(t0), phi0 + span, rtol, cycle, stop_at_rest,
                max_steps)


def _slope(moment: Moment, at: float, u: float, t: float, inertia: float) -> tuple:
    """The stage's slopes of (u, t) at driver angle ``at``: du/dphi = 2 M(phi, omega, t),
    dt/dphi = 1 / omega, omega = sqrt(u / I_r) (eq. 4.9)."""
    w = math.sqrt(u / inertia)
    m = moment(at, w, t)
    if type(m) is not float or m - m != 0.0:       # numpy's, an array, inf or nan
        m = moment_float(m, at, w)
    return 2.0 * m, 1.0 / w


def _step(moment: Moment, p: float, h: float, u: float, t: float, ku1: float, kt1: float,
          stage_i: Sequence[float]) -> tuple | None:
    """One Dormand-Prince 5(4) step of (u, t) from p to p + h; ``stage_i`` holds I_r at
    p + c h for c = 1/5, 3/10, 4/5, 8/9, 1. None where a stage would have u <= 0.

    The tableau's rows written out (eq. 4.9's integrator; the sixth and seventh stages
    both sit at p + h, the last one the solution's own, FSAL): each sum left to right, a
    single-term row as (h a) k. Written out, not looped over the tableau, for the cost of
    the calls: the motion's integration is most of a motion run."""
    i1, i2, i3, i4, i5 = stage_i
    un = u + h * A21 * ku1
    if not un > 0.0:
        return None
    ku2, kt2 = _slope(moment, p + DP5_C[0] * h, un, t + h * A21 * kt1, i1)
    un = u + h * (A31 * ku1 + A32 * ku2)
    if not un > 0.0:
        return None
    ku3, kt3 = _slope(moment, p + DP5_C[1] * h, un, t + h * (A31 * kt1 + A32 * kt2), i2)
    un = u + h * (A41 * ku1 + A42 * ku2 + A43 * ku3)
    if not un > 0.0:
        return None
    tn = t + h * (A41 * kt1 + A42 * kt2 + A43 * kt3)
    ku4, kt4 = _slope(moment, p + DP5_C[2] * h, un, tn, i3)
    un = u + h * (A51 * ku1 + A52 * ku2 + A53 * ku3 + A54 * ku4)
    if not un > 0.0:
        return None
    tn = t + h * (A51 * kt1 + A52 * kt2 + A53 * kt3 + A54 * kt4)
    ku5, kt5 = _slope(moment, p + DP5_C[3] * h, un, tn, i4)
    un = u + h * (A61 * ku1 + A62 * ku2 + A63 * ku3 + A64 * ku4 + A65 * ku5)
    if not un > 0.0:
        return None
    tn = t + h * (A61 * kt1 + A62 * kt2 + A63 * kt3 + A64 * kt4 + A65 * kt5)
    ku6, kt6 = _slope(moment, p + h, un, tn, i5)
    un = u + h * (B1 * ku1 + B3 * ku3 + B4 * ku4 + B5 * ku5 + B6 * ku6)
    if not un > 0.0:
        return None
    tn = t + h * (B1 * kt1 + B3 * kt3 + B4 * kt4 + B5 * kt5 + B6 * kt6)
    ku7, kt7 = _slope(moment, p + h, un, tn, i5)
    eu = h * (E1 * ku1 + E3 * ku3 + E4 * ku4 + E5 * ku5 + E6 * ku6 + E7 * ku7)
    et = h * (E1 * kt1 + E3 * kt3 + E4 * kt4 + E5 * kt5 + E6 * kt6 + E7 * kt7)
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
        q = np.einsum("nsc,sj->ncj", k, DP5_P)
        return MotionSolution(np.asarray(self.ps), np.asarray(self.us), np.asarray(self.ts), q,
                              inertia, moment, phi0, cycle, rest)


def _tolerances(rtol: float, cycle: float, u0: float, i0: float) -> tuple[float, float]:
    """Absolute tolerances of u and t (J, s) that go with rtol."""
    return 1e-9 * rtol * u0, rtol * cycle / math.sqrt(u0 / i0)


def dp5_run(inertia: Inertia, moment: Moment, phi0: float, u0: float, t0: float, end: float,
         rtol: float, cycle: float, stop_at_rest: bool, max_steps: int,
         track: _Track | None = None, origin: float | None = None) -> MotionSolution:
    """Adaptive Dormand-Prince 5(4) from (phi0, u0, t0) to ``end``; ``origin`` is where
    cycle 1 starts (for the cycle boundaries and the messages)."""
    origin = phi0 if origin is None else origin
    h_max = cycle / 32.0
    h_min = 1e-13 * max(cycle, abs(end))
    i0 = float(inertia_values(inertia, np.array([phi0]))[0][0])
    atol_u, atol_t = _tolerances(rtol, cycle, u0, i0)
    p, u, t = phi0, u0, t0
    w = math.sqrt(u / i0)
    ku1, kt1 = 2.0 * scalar_moment(moment, p, w, t), 1.0 / w
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
                              f"{where_text(p, origin, cycle)}")
        stage_i = inertia_values(inertia, np.array([p + c * h for c in DP5_C]))[0].tolist()
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
                                  f"{where_text(p, origin, cycle)}: check the moment and inertia")
            # omega ~ 0: u falls linearly (du/dphi = 2M), a uniform deceleration
            p_rest = p + u / -ku1
            t_rest = t + 2.0 * (p_rest - p) * kt1
            if not stop_at_rest:
                raise stall_error(p_rest, t_rest, origin, cycle)
            rest = (p_rest, t_rest)
            break
    return track.solution(inertia, moment, origin, cycle, rest)


class CycleGrid:
    """I_r at every stage angle of a grid of n equal steps per cycle, from one vectorised call;
    valid for every cycle when I_r has the cycle as its period. ``extra`` is a flywheel."""

    def __init__(self, inertia: Inertia, phi0: float, cycle: float) -> None:
        self.inertia, self.phi0, self.cycle = inertia, phi0, cycle
        self._cache: dict[int, list[list[float]]] = {}

    def stages(self, n: int) -> list[list[float]]:
        """Row j: I_r at phi0 + (j + c) h, c = 0, 1/5, 3/10, 4/5, 8/9, 1 (h = cycle / n)."""
        if n not in self._cache:
            c = np.array((0.0, *DP5_C[:-1]))
            pts = self.phi0 + (np.arange(n)[:, None] + c) * (self.cycle / n)
            vals = inertia_values(self.inertia, pts)[0]
            self._cache[n] = np.column_stack((vals, np.roll(vals[:, 0], -1))).tolist()
        return self._cache[n]


def dp5_grid(grid: CycleGrid, extra: float, inertia: Inertia, moment: Moment, u0: float,
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
    k1 = (2.0 * scalar_moment(moment, p, w, t), 1.0 / w)
    track = _Track(p, u, t)
    with_extra: dict[int, list[list[float]]] = {}     # the stages' I_r + extra, once per n
    for c in range(cycles):
        start = phi0 + c * cycle
        while True:
            if n not in with_extra:
                with_extra[n] = [[x + extra for x in row[1:]] for row in grid.stages(n)]
            rows, h = with_extra[n], cycle / n
            nodes, worst = [], 0.0
            uu, tt, (ku1, kt1) = u, t, k1
            for j in range(n):
                pj = start + j * h
                out = _step(moment, pj, h, uu, tt, ku1, kt1, rows[j])
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
                return dp5_run(inertia, moment, start, u, t, end, rtol, cycle, stop_at_rest,
                            2_000_000, track=track, origin=phi0)
            n *= 2
        for node in nodes:
            track.add(*node)
        u, t, k1 = uu, tt, (ku1, kt1)
        if worst < 1.0 / 64.0 and n > 64:
            n //= 2
    return track.solution(inertia, moment, phi0, cycle, None)


def with_flywheel(inertia: Inertia, extra: float) -> Inertia:
    if extra == 0.0:
        return inertia

    def inertia_j(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        i_r, di_r = inertia(phi)
        return np.asarray(i_r, dtype=float) + extra, di_r
    if hasattr(inertia, "prefetch"):    # a cache filled ahead (motion.scene's), kept
        inertia_j.prefetch = inertia.prefetch
    return inertia_j
