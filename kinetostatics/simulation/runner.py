"""The pymunk cross-check: simulated reactions against kinetostatics (:func:`crosscheck`).

:func:`crosscheck` runs a scene's mechanism in pymunk at the driver's constant speed
and compares, at the simulated driver positions, the magnitude of the reaction in
every joint, the couple of every locked prismatic joint and the driving moment
(force) with :func:`kinetostatics.solve` evaluated exactly at those positions
(:mod:`.comparison`). :func:`crosscheck_many` cross-checks many scenes (the bundled
cases, an exercise's variants) as a batch of top-level work items on plain data
(:func:`~kinetostatics.simulation.run_batch`): by default one process per core, or any
``concurrent.futures.Executor`` (a dask.distributed ``Client.get_executor()``).
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Iterable
from concurrent.futures import Executor
from typing import Any

import numpy as np

from ..common.angles import radian_value
from ..model.memory import check_memory
from ..model.scene import Scene, load_scene
from ..solver.footprint import solve_bytes
from .batch import run_batch
from .comparison import CrossCheck, compare
from .drift import drift_bound
from .errors import SimulationDiverged, SimulationError
from .model import build_space, check_scene
from .reference import reference_solution
from .stepper import PYMUNK_VERSION, run
from .stepsize import first_guess_steps

__all__ = ["ACCEPTABLE_ERROR", "AUTO_ITERATIONS", "BUDGET", "DEFAULT_STEPS_PER_REVOLUTION",
           "MAX_AUTO_STEPS", "MAX_STEPS", "SETTLE_FRACTION", "STEP_WORK", "TARGET_ERROR",
           "WORK_BUDGET", "converged_iterations", "crosscheck", "crosscheck_many", "plan"]

DEFAULT_STEPS_PER_REVOLUTION = 3600
"""Steps per revolution of a run given ``dt = None`` and no steps by a caller of
:func:`plan` (the cross-check itself chooses them per scene, :func:`crosscheck`)."""

MAX_AUTO_STEPS = 40_000
"""The automatic choice of steps per revolution stays at or below this."""

MAX_STEPS = 50_000_000
# the record of a run (the bodies' states at each sample) and the kinetostatic solve at
# the samples it is compared with: twice a solve's estimate (solver/footprint.py)
RECORD_FACTOR = 2.0
"""A run longer than this is refused (minutes of wall time)."""

SETTLE_FRACTION = 0.01
"""A sweep shorter than a turn: its first 1 % is left out of the errors."""


def rebuildable_scene(scene: Any) -> Scene:
    sc = load_scene(scene)
    if not sc.raw:
        raise SimulationError("the scene has no raw table to rebuild it from; pass a path, "
                              "TOML text or a dict")
    return sc


def plan(scene: Scene, *, dt: float | None, steps_per_revolution: int | None,
         revolutions: float, samples_per_revolution: int) -> dict[str, Any]:
    """How a cross-check run is laid out: start, dt, steps, sampling, compared part."""
    d = scene.driver
    pos = np.asarray(d.positions, dtype=float)
    speed = d.speed
    if d.kind == "R":
        span = float(np.ptp(pos)) if pos.size > 1 else 360.0
        full = span >= 360.0 - 1e-9
        period = 2.0 * math.pi / abs(speed)
        if full:
            start = float(pos[0])
            duration = revolutions * period
        else:
            start = float(pos.min() if speed > 0 else pos.max())
            duration = radian_value(span) / abs(speed)
        unit = period
    else:
        span = float(np.ptp(pos))
        if span <= 0.0:
            raise SimulationError("a sliding driver's sweep has no length: give start < stop "
                                  "(or several positions)")
        full = False
        start = float(pos.min() if speed > 0 else pos.max())
        duration = span / abs(speed)
        unit = duration           # a "revolution" of a sliding driver: its sweep
    if not math.isfinite(revolutions) or revolutions <= 0.0:
        raise SimulationError(f"revolutions = {revolutions!r}: give a positive number")
    if revolutions < 1.0 + 1e-12 and full:
        raise SimulationError(f"revolutions = {revolutions:g}: the first revolution is left "
                              "out of the errors; give more than 1 (default 2)")
    if dt is None:
        n = DEFAULT_STEPS_PER_REVOLUTION if steps_per_revolution is None \
            else int(steps_per_revolution)
        if n < 10:
            raise SimulationError(f"steps per revolution = {n}: give at least 10")
        dt = unit / n
    elif steps_per_revolution is not None:
        raise SimulationError("give dt or steps per revolution, not both")
    if not (dt > 0.0 and math.isfinite(dt)):
        raise SimulationError(f"dt = {dt!r}: give a positive time step in s")
    steps = int(round(duration / dt))
    if steps < 2:
        raise SimulationError(f"dt = {dt:g} s is longer than the run ({duration:g} s)")
    if steps > MAX_STEPS:
        raise SimulationError(f"dt = {dt:g} s makes {steps:_} steps (at most {MAX_STEPS:_}); "
                              "give a larger dt or fewer revolutions")
    per_unit = unit / dt
    every = max(1, int(round(per_unit / max(1, samples_per_revolution))))
    samples = steps // every + 1        # the peak memory known before it is spent: the
    check_memory(RECORD_FACTOR * solve_bytes(scene, samples),   # record and its solve
                 f"the cross-check's {samples:,} samples", "give fewer --samples per "
                 "revolution or fewer --revolutions")
    compare_from = unit if full else SETTLE_FRACTION * duration
    return {"start": start, "dt": float(dt), "steps": steps, "every": every, "full": full,
            "unit": unit, "duration": duration, "compare_from": compare_from,
            "steps_per_revolution": per_unit}


def crosscheck(scene: Any, *, dt: float | None = None, steps_per_revolution: int | None = None,
               iterations: int | None = None, revolutions: float = 2.0,
               samples_per_revolution: int = 360, error_bias: float = 0.0,
               fast: bool | None = None, ballast: bool = True,
               keep_lower: bool = True) -> CrossCheck:
    """Simulate a scene in pymunk and compare the reactions with kinetostatics.

    Parameters
    ----------
    scene : path, TOML text, dict or Scene
        A mechanism scene whose driver turns (or slides) at constant speed.
    dt : float, optional
        Time step (s). Default: a revolution (a sliding driver's sweep) in
        ``steps_per_revolution`` steps.
    steps_per_revolution : int, optional
        Default: chosen for the scene (:func:`~kinetostatics.simulation.first_guess_steps`
        from its fastest body and smallest link, then, if the run misses
        ``TARGET_ERROR``, once more from the dt^2 law); the settings carry
        ``steps_rule`` and ``steps_tried``.
    iterations : int, optional
        Solver iterations. Default: chosen by :func:`converged_iterations` (30, or
        doubled until doubling again changes no reading by more than a quarter of the
        error; a diverged count is never chosen).
    revolutions : float
        Driver turns simulated when the sweep is a full turn (default 2; the first is
        left out of the errors). A shorter sweep is simulated once.
    samples_per_revolution : int
        Readings per revolution (default 360).
    error_bias : float
        Joint ``error_bias`` (default 0; pymunk's default gives errors near 1e-3).
    fast : bool, optional
        Let the stepping loop call Chipmunk directly (see :func:`simulation.run`).
    ballast : bool
        Where a run diverges with the driver's constraint solved last, run it once more
        with the driver's side heavy for the solver, the extra mass cancelled by a force
        before every step (:mod:`~kinetostatics.simulation.ballast`), before solving
        the driver's constraint first (default True: the shaper then settles at 60
        iterations instead of 180 to 480). A run that converges without it is the run
        it was before. False: no ballast (the settings before it).
    keep_lower : bool
        With automatic iterations, where doubling the count changed the readings by
        less than ``SETTLED_CHANGE``, keep the lower count if its error is already within
        ``LAG_TARGET`` in the same solver order (default; :func:`converged_iterations`).
        False: the doubled count, as before (with ``ballast=False``: the previous
        default settings, which ``crosscheck_speed`` times as its baseline).

    Returns
    -------
    CrossCheck

    Raises
    ------
    SimulationDiverged
        The run blew up (and, with automatic iterations, every count tried did).
    SimulationError
        A driver with acceleration, joint friction, a massless body, bad settings.

    Examples
    --------
    >>> import kinetostatics as ks
    >>> cc = crosscheck(ks.example("four_bar"), steps_per_revolution=4000, iterations=10)
    >>> cc.max_error < 1e-5
    True
    """
    sc = rebuildable_scene(scene)
    check_scene(sc)
    auto = dt is None and steps_per_revolution is None

    def attempt(n: int | None) -> CrossCheck:
        p = plan(sc, dt=dt, steps_per_revolution=n, revolutions=revolutions,
                 samples_per_revolution=samples_per_revolution)
        if iterations is None:
            return converged_iterations(sc, p, error_bias=error_bias, fast=fast,
                                        ballast=ballast, keep_lower=keep_lower)
        return _crosscheck(sc, p, int(iterations), error_bias, fast, ballast)

    if not auto:
        return attempt(steps_per_revolution)
    n0 = first_guess_steps(sc, MAX_AUTO_STEPS)
    cc = attempt(n0)
    tried = [n0]
    if cc.max_error > TARGET_ERROR:
        # the dt^2 law: aim at half the target; but where the error is already within
        # ACCEPTABLE_ERROR, not beyond the work budget (the cost grows as steps x
        # (iterations + a step's own work)). The rule counts work, never the wall time:
        # the same scene gets the same settings on a quiet machine and on a busy one.
        want = n0 * math.sqrt(cc.max_error / (0.5 * TARGET_ERROR))
        if cc.max_error <= ACCEPTABLE_ERROR:
            want = min(want, WORK_BUDGET / (cc.settings["iterations"] + STEP_WORK))
        n1 = int(min(MAX_AUTO_STEPS, 100 * math.ceil(want / 100.0)))
        if n1 > 1.1 * n0:
            tried.append(n1)
            try:
                finer = attempt(n1)
            except SimulationDiverged as exc:
                cc.notes.append(f"{n1} steps per revolution diverged ({exc}); kept {n0}")
            else:
                # the finer run is the better-converged one, kept whatever it shows: a
                # cross-check never chooses by agreement with what it checks
                if finer.max_error > cc.max_error:
                    finer.notes.append(
                        f"refining from {n0} to {n1} steps per revolution made the "
                        f"agreement worse ({cc.max_error:.2g} -> {finer.max_error:.2g}): "
                        "the simulation converges away from kinetostatics, the sign of a "
                        "real discrepancy (or of a solver that has not settled)")
                cc = finer
    cc.settings["steps_tried"] = tried
    cc.settings["steps_rule"] = ("auto: first guess from the fastest body and the smallest "
                                 "link, then the dt^2 law towards the target error")
    _budget_note(cc)
    return cc


TARGET_ERROR = 1e-5
"""The default settings aim at this largest relative error."""

BUDGET = 0.05
"""... within this wall time per simulated revolution (s): reported in the notes, never
used to choose settings."""

WORK_BUDGET = 400_000
"""Steps x (solver iterations + ``STEP_WORK``) per simulated revolution that the
automatic rule spends on refining a run already within ``ACCEPTABLE_ERROR``: about
``BUDGET`` on this project's 2-core machine (measured quiet: 1.0e-7 s per
step-iteration for the four-bar, 1.4e-7 for the shaper, at 30 to 180 iterations)."""

STEP_WORK = 40
"""A step's own work (the loads, the ballast, the readings, Chipmunk's fixed part), in
solver iterations: measured in one process, 31 to 60 (about 5 microseconds a step
against 0.12 per iteration; the four-bar 35, the slider-crank 31, the slotted lever with
its ballast 60, the shaper with its ballast about 45). It counts where few iterations
suffice: the shaper at 60 with the ballast refines from 3600 to 4000 steps per
revolution (9.5e-6), not to 5600 (4.8e-6), at 0.55 of the previous defaults' time
instead of 0.8 (docs/simulation.md, "Slow chains")."""

ACCEPTABLE_ERROR = 1e-4
"""A first run within this error is refined towards ``TARGET_ERROR`` only as far as the
time budget allows (a larger error is refined whatever it costs)."""


def _seconds_per_unit(cc: CrossCheck) -> float:
    s = cc.settings
    return s["seconds_per_revolution"] or s["seconds_per_sweep"]


def _budget_note(cc: CrossCheck) -> None:
    """Say why the default settings missed the target error or the time budget."""
    s = cc.settings
    per = _seconds_per_unit(cc)
    unit = "revolution" if s["seconds_per_revolution"] is not None else "sweep"
    missed = []
    if cc.max_error > TARGET_ERROR:
        missed.append(f"error {cc.max_error:.2g} > {TARGET_ERROR:g}")
    if per > BUDGET:
        missed.append(f"{1e3 * per:.0f} ms > {1e3 * BUDGET:.0f} ms per simulated {unit}")
    if not missed:
        return
    why = (f"the solver needed {s['iterations']} iterations per step to settle (Gauss-Seidel "
           "converges slowly along a chain whose bodies differ much in mass or inertia, "
           "such as a heavy ram driven through a slotted lever), and finer steps need as "
           "many or more" if s["iterations"] > 60 else
           "the error falls as dt^2 and the wall time grows as 1 / dt: the steps that reach "
           "the error cost more than the budget on this machine (its load counts too), so "
           f"the steps stopped at {s['steps_per_revolution']} per {unit}")
    cc.notes.append(f"the default settings missed the target ({'; '.join(missed)}): {why}")


AUTO_ITERATIONS = (30, 60, 120, 240, 480, 960)
"""Iteration counts tried, in turn, when none is given."""

SETTLED = 0.25
"""Doubling the iterations changes no reading by more than this fraction of the error:
the count is settled."""

SETTLED_CHANGE = ACCEPTABLE_ERROR
"""... or, failing that, doubling changes no reading by more than this fraction of its
scale: the doubled run is kept. Where Gauss-Seidel converges slowly the readings lag
the exact solution by an amount that falls as 1 / iterations (the shaper at 3600 steps:
1.1e-4, 5.4e-5, 2.8e-5 at 120, 240, 480), so a doubling changes them by about the
doubled run's own lag, and a change below a quarter of the error would need ever more
iterations for little gain: the doubled run's lag is then within the acceptable
error, and more iterations would cost more than they bring."""


def converged_iterations(sc: Scene, p: dict, *, error_bias: float = 0.0,
                         fast: bool | None = None, ballast: bool = True,
                         keep_lower: bool = True) -> CrossCheck:
    """Run with 30, 60, 120... iterations until doubling them changes no reading by more
    than ``SETTLED`` (a quarter) of the error against kinetostatics, and return the run
    before the last: the iterations then add little to the error it reports; or until
    doubling changes no reading by more than ``SETTLED_CHANGE`` of its scale, and return
    the doubled run (its lag is about that change). Measured on the slotted crank at
    3600 steps: 60, 120, 240 and 480 iterations give 5.3e-5, 5.0e-5, 4.9e-5 and 4.8e-5,
    each doubling changing the readings by 0.41, 0.21 and 0.01 of the error.

    Gauss-Seidel iterations converge slowly along a chain whose bodies differ much in
    mass or inertia (the shaper's 8 kg ram driven through a slotted lever: 480; with
    the ram ten times lighter, 120): such scenes need hundreds, a four-bar about 10.
    With ``error_bias = 0`` too few iterations make the run diverge
    (:class:`SimulationDiverged`): such a count is passed over, never chosen.
    The returned settings carry ``iterations_tried`` and ``iterations_diverged``.

    Raises
    ------
    SimulationDiverged
        Every count tried diverged (the last one's error).
    """
    prev = None
    tried, blown = [], []
    last_exc = None
    for n in AUTO_ITERATIONS:
        tried.append(n)
        try:
            cc = _crosscheck(sc, p, n, error_bias, fast, ballast)
        except SimulationDiverged as exc:
            blown.append(n)
            last_exc = exc
            prev = None              # two converged counts in a row are compared
            continue
        change = math.inf if prev is None else _reading_change(prev, cc)
        if change <= max(SETTLED * cc.max_error, 1e-9) or change <= SETTLED_CHANGE:
            keep, rule = prev, "auto: doubling changes no reading by more than a quarter " \
                "of the error"
            if change > max(SETTLED * cc.max_error, 1e-9):
                keep = _lag_bounded(sc, p, prev, cc, change, tried, blown, error_bias, fast,
                                    ballast, keep_lower)
                rule = (f"auto: doubling {prev.settings['iterations']} changed the readings "
                        f"by {change:.2g} of their scale (the solver's lag, falling as 1 / "
                        f"iterations); kept {keep.settings['iterations']}, whose lag is "
                        f"within {LAG_TARGET:g}")
            keep.settings["iterations_tried"] = tried
            keep.settings["iterations_diverged"] = blown
            keep.settings["iterations_rule"] = rule
            return keep
        prev = cc
    if prev is None:
        raise last_exc
    prev.settings["iterations_tried"] = tried
    prev.settings["iterations_diverged"] = blown
    prev.notes.append(f"the readings still changed between {tried[-2]} and {tried[-1]} "
                      "iterations: the solver may not have converged; try a larger dt or "
                      "more iterations")
    return prev


LAG_TARGET = 0.75 * ACCEPTABLE_ERROR
"""Where the readings lag (``SETTLED_CHANGE``), the count is the one whose lag this
estimate puts at this fraction of a reading's scale."""


def _lag_bounded(sc: Scene, p: dict, low: CrossCheck, high: CrossCheck, change: float,
                 tried: list, blown: list, error_bias: float,
                 fast: bool | None, ballast: bool = True,
                 keep_lower: bool = True) -> CrossCheck:
    """Between a count and its double, whose readings differ by ``change`` (the solver's
    lag), the count whose error the two runs put at ``LAG_TARGET``: the error taken as
    a + b / iterations through the two runs' errors (the lag falls as 1 / iterations).
    It is run and kept if it converges within ``ACCEPTABLE_ERROR``; else the doubled
    run is (also where that count is not above the lower one: keeping the lower count
    there made the slotted lever trade 60 iterations with the driver last for 30 with
    it first, and finer steps to make up for it). Measured on the shaper at 3600 steps:
    120 and 240 iterations give 1.07e-4 and 5.4e-5; the count between them, 180, gives
    7.1e-5 at three quarters of the doubled count's cost.

    With ``keep_lower``, the lower count is kept where its own error is already within
    ``LAG_TARGET`` and both runs solved the constraints in the same order, with or both
    without the ballast (the doubling bought nothing the target asks for, and the
    steps rule may spend the work on finer steps instead; measured: the slotted crank
    (TRT) at 3600 steps, 60 and 120 iterations, 5.3e-5 and 5.0e-5)."""
    k, k2 = low.settings["iterations"], high.settings["iterations"]
    if keep_lower and low.max_error <= LAG_TARGET and all(
            low.settings.get(q) == high.settings.get(q) for q in ("solver_order", "ballast")):
        return low
    b = k * k2 / (k2 - k) * (low.max_error - high.max_error)
    a = high.max_error - b / k2
    if not (b > 0.0 and a < LAG_TARGET and change > 0.0):
        return high
    m = 10 * math.ceil(b / (LAG_TARGET - a) / 10.0)
    if not k < m < k2:
        return high
    tried.append(m)
    try:
        mid = _crosscheck(sc, p, m, error_bias, fast, ballast)
    except SimulationDiverged:
        blown.append(m)
        return high
    return mid if mid.max_error <= ACCEPTABLE_ERROR else high


def _reading_change(a: CrossCheck, b: CrossCheck) -> float:
    """Largest change of a reading between two runs, relative to the quantity's scale
    (inf when they cannot be compared)."""
    if not (math.isfinite(a.max_error) and math.isfinite(b.max_error)):
        return math.inf
    ra, rb = a.rows, b.rows
    if len(ra) != len(rb):
        return math.inf
    used = ra.used.to_numpy() & rb.used.to_numpy()
    worst = 0.0
    for q in a.errors:
        m = (ra.quantity == q).to_numpy() & used
        if not m.any():
            continue
        scale = float(np.max(np.abs(ra.computed.to_numpy()[m])))
        if scale > 0.0:
            d = np.abs(ra.simulated.to_numpy()[m] - rb.simulated.to_numpy()[m])
            worst = max(worst, float(np.max(d)) / scale)
    return worst


def _crosscheck(sc: Scene, p: dict, iterations: int, error_bias: float,
                fast: bool | None, ballast: bool = True) -> CrossCheck:
    model, rec = _stepped(sc, p, iterations, error_bias, fast, ballast)  # or SimulationDiverged
    ref = reference_solution(sc, rec.position)
    cc = compare(sc, model, rec, ref, compare_from=p["compare_from"])
    revs = p["duration"] / p["unit"]
    n = p["steps_per_revolution"]
    cc.settings.update({
        "dt": p["dt"], "iterations": int(iterations), "error_bias": float(error_bias),
        "max_bias": "inf",
        "steps_per_revolution": int(round(n)) if abs(n - round(n)) < 1e-6 * n else n,
        "steps": p["steps"], "sample_every": p["every"],
        "revolutions": revs if sc.driver.kind == "R" else None,
        "sweeps": revs if sc.driver.kind == "T" else None,
        "seconds_per_revolution": rec.wall / revs if sc.driver.kind == "R" else None,
        "seconds_per_sweep": rec.wall / revs if sc.driver.kind == "T" else None,
        "wall": rec.wall, "full_turn": p["full"], "pymunk": PYMUNK_VERSION,
        "fast_path": rec.fast, "drift": rec.drift, "drift_bound": drift_bound(model),
        "solver_order": "driver first" if model.driver_first else "scene, driver last",
        "ballast": {k: list(v) for k, v in model.ballast.items()},
    })
    if model.driver_first:
        cc.notes.append(f"with the driver's constraint solved last the run diverged at "
                        f"{iterations} iterations; it was solved first (the driver's speed "
                        "is then held to the solver's residual)")
    if model.ballast:
        cc.notes.append(f"without the ballast the run diverged at {iterations} iterations; "
                        "it was run with it")
    return cc


def _stepped(sc: Scene, p: dict, iterations: int, error_bias: float, fast: bool | None,
             ballast: bool = True):
    """Build and run the model with the driver's constraint solved last (the driver's
    speed exact at every step); if that diverges and ``ballast`` is allowed, once more
    with the ballast (:mod:`~kinetostatics.simulation.ballast`, the driver's side heavy
    for the solver); if that diverges too, with the driver's constraint solved first
    and no ballast (:func:`~kinetostatics.simulation.model.solver_order`); if every
    attempt diverges, the first run's error is raised. A scene that runs without the
    ballast is simulated exactly as before it."""
    attempts = [{"driver_first": False, "ballast": False}]
    if ballast:
        attempts.append({"driver_first": False, "ballast": True})
    attempts.append({"driver_first": True, "ballast": False})
    first = None
    for how in attempts:
        try:
            model = build_space(sc, dt=p["dt"], iterations=iterations, start=p["start"],
                                error_bias=error_bias, **how)
            return model, run(model, p["steps"], p["every"], fast=fast)
        except SimulationDiverged as exc:
            first = first or exc
    raise first


def _crosscheck_summary(item: tuple) -> dict[str, Any]:
    """One cross-check of a batch, summarised (plain data in, plain data out)."""
    raw, settings = item
    return crosscheck(raw, **settings).summary()


def crosscheck_many(scenes: Iterable[Any], *, executor: Executor | str | None = None,
                    **settings: Any) -> list[dict[str, Any]]:
    """Cross-check many scenes (bundled cases, an exercise's variants...) as a batch.

    Parameters
    ----------
    scenes : iterable of path, TOML text, dict or Scene
        The scenes; each is read here and sent to the workers as its TOML dict (a
        worker on another machine needs no file).
    executor : Executor, ``"serial"`` or None
        As in :func:`study` (default: processes, one per core).
    **settings
        Keywords of :func:`crosscheck` (``steps_per_revolution``, ``iterations``...),
        the same for every scene.

    Returns
    -------
    list of dict
        :meth:`CrossCheck.summary` of each scene, in the order given (``title``,
        ``max_error``, ``errors``, ``seconds_per_revolution``...).

    Examples
    --------
    >>> import kinetostatics as ks
    >>> out = crosscheck_many([ks.example("four_bar"), ks.example("slider_crank")],
    ...                       steps_per_revolution=2000, iterations=30,
    ...                       samples_per_revolution=45, executor="serial")
    >>> [s["max_error"] < 1e-4 for s in out]
    [True, True]
    """
    bad = set(settings) - set(inspect.signature(crosscheck).parameters) - {"scene"}
    if bad or "scene" in settings:
        raise SimulationError(f"crosscheck_many: unknown setting(s) "
                              f"{', '.join(sorted(bad | ({'scene'} & set(settings))))}; "
                              "give keywords of crosscheck()")
    items = [(rebuildable_scene(s).raw, dict(settings)) for s in scenes]
    return run_batch(_crosscheck_summary, items, executor=executor)
