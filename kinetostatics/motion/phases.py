"""The phases of the motion (seed 002 s. 4.2): stopping, the periodic steady state, the
flywheel for a target degree of irregularity (eq. 4.20), and the recurrence's error
against the accurate solution.
"""

from __future__ import annotations

import math
import time as _time
from collections.abc import Sequence

import numpy as np
import pandas as pd

from ..common.angles import degree_value
from .equation import (
    TWO_PI,
    Inertia,
    Moment,
    MotionError,
    inertia_values,
    solve_energy,
    solve_recurrence,
)
from .integrator import (
    CycleGrid,
    dp5_grid,
    dp5_run,
    simulate,
    with_flywheel,
)
from .solution import (
    MotionSolution,
)

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
    grid = CycleGrid(inertia, float(phi0), cycle) if periodic_inertia else None
    return _periodic(inertia, moment, float(phi0), omega_guess, rtol, cycle, tol, maxiter,
                     grid, 0.0)


def _periodic(inertia: Inertia, moment: Moment, phi0: float, omega_guess: float, rtol: float,
              cycle: float, tol: float, maxiter: int, grid: CycleGrid | None,
              extra: float) -> MotionSolution:
    inertia_j = with_flywheel(inertia, extra)
    i0 = float(inertia_values(inertia_j, np.array([phi0]))[0][0])

    def run(w: float) -> tuple[MotionSolution, float]:
        if grid is None:
            sol = dp5_run(inertia_j, moment, phi0, i0 * w * w, 0.0, phi0 + cycle, rtol, cycle,
                       False, 2_000_000)
        else:
            sol = dp5_grid(grid, extra, inertia_j, moment, i0 * w * w, 0.0, 1, rtol, False)
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
    grid = CycleGrid(inertia, phi0, cycle) if periodic_inertia else None
    guess = [float(omega_guess)]

    def inv_delta(j: float) -> float:
        sol = _periodic(inertia, moment, phi0, guess[0], rtol, cycle, 1e-10, 60, grid, j)
        guess[0] = sol.omega0
        return 1.0 / sol.cycle_stats(alpha=False)["delta"] - 1.0 / target_delta

    h0 = inv_delta(0.0)
    if h0 >= 0.0:
        return 0.0
    i_mean = float(np.mean(inertia_values(inertia, phi0 + cycle * np.arange(256) / 256)[0]))
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
        rows.append({"step": degree_value(span / n), "steps": n, "max_error": float(err.max()),
                     "max_rel_error": float(np.max(err / wr)), "wall_time": wall})
    table = pd.DataFrame(rows)
    ok = table["max_error"] > 0.0
    table.attrs["order"] = (float(np.polyfit(np.log(table["step"][ok]),
                                             np.log(table["max_error"][ok]), 1)[0])
                            if ok.sum() >= 2 else math.nan)
    table.attrs["reference"] = method
    table.attrs["reference_wall_time"] = ref_time
    return table
