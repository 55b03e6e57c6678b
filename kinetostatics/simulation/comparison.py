"""The pymunk cross-check: simulated reactions against kinetostatics, and its cost.

:func:`crosscheck` runs a scene's mechanism in pymunk (:mod:`kinetostatics.simulation`)
at the driver's constant speed and compares, at the simulated driver positions, the
magnitude of the reaction in every joint, the couple of every locked prismatic joint
and the driving moment (force) with :func:`kinetostatics.solve` evaluated exactly at
those positions. :func:`study` sweeps the time step and the solver iterations and
reports the wall time per simulated revolution against the error, with the observed
order of convergence; :func:`crosscheck_many` cross-checks many scenes (the bundled
cases, an exercise's variants). Both are batches of top-level work items on plain data
(:func:`kinetostatics.simulation.run_batch`): by default one process per core, or any
``concurrent.futures.Executor`` (a dask.distributed ``Client.get_executor()``). The
pictures (:func:`plot_comparison`, :func:`plot_study`) return matplotlib Figures.

Error of a quantity: the largest |simulated - computed| over the compared rows,
divided by the largest |computed| there. Compared rows: after the first revolution
(a full turn is simulated ``revolutions`` times), or, for a sweep shorter than a
turn (and for a sliding driver), the sweep after its first 1 %; rows that
kinetostatics flags ``singular`` or ``undefined_load``, or where a ``resist`` point is
nearly still in the simulation, are left out.
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Iterable
from concurrent.futures import Executor
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from ..model.scene import Scene, load_scene
from .engine import (
    DEFAULT_STEPS_PER_REVOLUTION,
    PYMUNK_VERSION,
    SimRecord,
    SimulationError,
    build_space,
    mechanism_size,
    reference_solution,
    run,
    run_batch,
)

MAX_STEPS = 50_000_000
"""A run longer than this is refused (minutes of wall time)."""

SETTLE_FRACTION = 0.01
"""A sweep shorter than a turn: its first 1 % is left out of the errors."""

STUDY_STEPS = (500, 1000, 2000, 4000, 8000, 16000, 32000)
"""Default steps per revolution of the study."""

STUDY_ITERATIONS = (10, 30)
"""Default solver iterations of the study."""

ZERO_COUPLE = 1e-9
"""A prismatic joint's couple below this times max|F| x the mechanism's size counts as
zero in kinetostatics (it is compared on that scale, not on its own)."""

ORDER_FLOOR = 1e-6
"""The convergence order is fitted on errors above this (rounding takes over near 1e-7)."""


@dataclass
class CrossCheck:
    """A simulated run compared with kinetostatics.

    Attributes
    ----------
    scene : Scene
    record : SimRecord
        The simulation's readings.
    reference : Solution
        Kinetostatics at the simulated driver positions (its first row, the scene's
        first position, is dropped from every comparison).
    rows : pandas.DataFrame
        Long table ``position, time, quantity, simulated, computed, used``: one row per
        sample and quantity (``F[joint]``: magnitudes from the public impulses;
        ``M[joint]``: the signed couple of a prismatic joint, where kinetostatics does
        not find it zero; ``Me`` or ``Fe``: signed).
    errors : dict
        Quantity -> relative error over the compared rows.
    vector_errors : dict
        The same for the signed values derived from the momentum balance
        (``Fx[j]``, ``Fy[j]``, ``N[j]``, ``M[j]``).
    settings : dict
        dt, iterations, error_bias, steps per revolution, revolutions, samples.
    notes : list of str
        What the reader should know (translating bodies, couples that are zero, mass
        models, rows left out...).
    """

    scene: Scene
    record: SimRecord
    reference: Any
    rows: pd.DataFrame
    errors: dict[str, float]
    vector_errors: dict[str, float]
    settings: dict[str, Any]
    notes: list[str] = field(default_factory=list)

    @property
    def max_error(self) -> float:
        """The largest error over all joints (|F|, M) and the driving moment (force)."""
        return max(self.errors.values()) if self.errors else float("nan")

    @property
    def seconds_per_revolution(self) -> float | None:
        """Wall time per simulated driver revolution (None for a sliding driver)."""
        return self.settings["seconds_per_revolution"]

    def error_table(self) -> pd.DataFrame:
        """Per quantity: ``quantity, unit, scale`` (largest |computed|), ``max_abs_error``,
        ``error`` (relative) and ``position`` of the worst row."""
        out = []
        for q, g in self.rows[self.rows.used].groupby("quantity", sort=False):
            d = np.abs(g.simulated.to_numpy() - g.computed.to_numpy())
            i = int(np.argmax(d))
            out.append({"quantity": q, "unit": _unit(q, self.scene),
                        "scale": float(np.abs(g.computed).max()),
                        "max_abs_error": float(d[i]), "error": self.errors[q],
                        "position": float(g.position.to_numpy()[i])})
        return pd.DataFrame(out)

    def wide(self) -> pd.DataFrame:
        """One row per sample: ``position``, ``time`` and ``<quantity> sim`` /
        ``<quantity> ks`` columns, ``used``."""
        r = self.rows
        first = r[r.quantity == r.quantity.iloc[0]]
        out = pd.DataFrame({"position": first.position.to_numpy(),
                            "time": first.time.to_numpy()})
        for q, g in r.groupby("quantity", sort=False):
            out[f"{q} sim"] = g.simulated.to_numpy()
            out[f"{q} ks"] = g.computed.to_numpy()
        out["used"] = first.used.to_numpy()
        return out

    def summary(self) -> dict[str, Any]:
        """A JSON-ready dict: the settings, ``seconds_per_revolution``, ``max_error``,
        ``errors`` per quantity, ``vector_errors``, ``vector_check``, notes."""
        worst = max(self.errors, key=self.errors.get) if self.errors else None
        s = dict(self.settings)
        s.update({
            "title": self.scene.title,
            "max_error": self.max_error,
            "worst": worst,
            "errors": dict(self.errors),
            "vector_errors": dict(self.vector_errors),
            "vector_check": self.record.vector_check,
            "rows": int(self.rows.position.nunique()),
            "rows_compared": int(self.rows[self.rows.used].position.nunique()),
            "notes": list(self.notes),
        })
        return s


def _unit(q: str, scene: Scene) -> str:
    if q.startswith("M[") or q == "Me":
        return "N m"
    return "N"


def _dict_scene(scene: Any) -> Scene:
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
            duration = math.radians(span) / abs(speed)
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
    compare_from = unit if full else SETTLE_FRACTION * duration
    return {"start": start, "dt": float(dt), "steps": steps, "every": every, "full": full,
            "unit": unit, "duration": duration, "compare_from": compare_from,
            "steps_per_revolution": per_unit}


def crosscheck(scene: Any, *, dt: float | None = None, steps_per_revolution: int | None = None,
               iterations: int | None = None, revolutions: float = 2.0,
               samples_per_revolution: int = 360, error_bias: float = 0.0,
               fast: bool | None = None) -> CrossCheck:
    """Simulate a scene in pymunk and compare the reactions with kinetostatics.

    Parameters
    ----------
    scene : path, TOML text, dict or Scene
        A mechanism scene whose driver turns (or slides) at constant speed.
    dt : float, optional
        Time step (s). Default: a revolution (a sliding driver's sweep) in
        ``steps_per_revolution`` steps.
    steps_per_revolution : int, optional
        Default 3600 (``simulation.DEFAULT_STEPS_PER_REVOLUTION``).
    iterations : int, optional
        Solver iterations. Default: chosen by :func:`converged_iterations` (30, or
        doubled until doubling again changes no reading by more than a tenth of the
        error).
    revolutions : float
        Driver turns simulated when the sweep is a full turn (default 2; the first is
        left out of the errors). A shorter sweep is simulated once.
    samples_per_revolution : int
        Readings per revolution (default 360).
    error_bias : float
        Joint ``error_bias`` (default 0; pymunk's default gives errors near 1e-3).
    fast : bool, optional
        Let the stepping loop call Chipmunk directly (see :func:`simulation.run`).

    Returns
    -------
    CrossCheck

    Raises
    ------
    SimulationError
        A driver with acceleration, a massless body, bad settings.

    Examples
    --------
    >>> import kinetostatics as ks
    >>> cc = crosscheck(ks.example("four_bar"), steps_per_revolution=4000, iterations=10)
    >>> cc.max_error < 1e-5
    True
    """
    sc = _dict_scene(scene)
    if sc.driver.acceleration != 0.0:
        raise SimulationError(
            f"driver.acceleration = {sc.driver.acceleration:g}: this scene's rows are "
            "snapshots, not a motion; the cross-check needs a constant-speed driver "
            "(acceleration = 0)")
    p = plan(sc, dt=dt, steps_per_revolution=steps_per_revolution, revolutions=revolutions,
             samples_per_revolution=samples_per_revolution)
    if iterations is None:
        return converged_iterations(sc, p, error_bias=error_bias, fast=fast)
    return _crosscheck(sc, p, int(iterations), error_bias, fast)


AUTO_ITERATIONS = (30, 60, 120, 240, 480, 960)
"""Iteration counts tried, in turn, when none is given."""


def converged_iterations(sc: Scene, p: dict, *, error_bias: float = 0.0,
                         fast: bool | None = None) -> CrossCheck:
    """Run with 30, 60, 120... iterations until doubling them changes no reading by more
    than a tenth of the error against kinetostatics; return the run before the last.

    Gauss-Seidel iterations converge slowly where light bodies sit between heavy ones
    (a sliding block between a crank and a slotted lever): such scenes need hundreds,
    a four-bar about 10. The returned settings carry ``iterations_tried``.
    """
    prev = None
    tried = []
    for n in AUTO_ITERATIONS:
        cc = _crosscheck(sc, p, n, error_bias, fast)
        tried.append(n)
        if prev is not None and _same_readings(prev, cc):
            prev.settings["iterations_tried"] = tried
            prev.settings["iterations_rule"] = "auto: doubling changes no reading by more " \
                "than a tenth of the error"
            return prev
        prev = cc
    prev.settings["iterations_tried"] = tried
    prev.notes.append(f"the readings still changed between {tried[-2]} and {tried[-1]} "
                      "iterations: the solver may not have converged; try a larger dt or "
                      "more iterations")
    return prev


def _same_readings(a: CrossCheck, b: CrossCheck) -> bool:
    if not (math.isfinite(a.max_error) and math.isfinite(b.max_error)):
        return False
    ra, rb = a.rows, b.rows
    if len(ra) != len(rb):
        return False
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
    return worst <= max(0.1 * b.max_error, 1e-9)


def _crosscheck(sc: Scene, p: dict, iterations: int, error_bias: float,
                fast: bool | None) -> CrossCheck:
    model = build_space(sc, dt=p["dt"], iterations=iterations, start=p["start"],
                        error_bias=error_bias)
    rec = run(model, p["steps"], p["every"], fast=fast)
    ref = reference_solution(sc, rec.position)
    cc = compare(sc, model, rec, ref, compare_from=p["compare_from"])
    revs = p["duration"] / p["unit"]
    cc.settings.update({
        "dt": p["dt"], "iterations": int(iterations), "error_bias": float(error_bias),
        "max_bias": "inf", "steps_per_revolution": p["steps_per_revolution"],
        "steps": p["steps"], "sample_every": p["every"],
        "revolutions": revs if sc.driver.kind == "R" else None,
        "sweeps": revs if sc.driver.kind == "T" else None,
        "seconds_per_revolution": rec.wall / revs if sc.driver.kind == "R" else None,
        "seconds_per_sweep": rec.wall / revs if sc.driver.kind == "T" else None,
        "wall": rec.wall, "full_turn": p["full"], "pymunk": PYMUNK_VERSION,
        "fast_path": rec.fast, "drift": rec.drift,
    })
    return cc


def compare(sc: Scene, model, rec: SimRecord, ref, *, compare_from: float) -> CrossCheck:
    """Build the comparison tables of a run (see :func:`crosscheck`)."""
    n = rec.time.size
    used = rec.time > compare_from * (1.0 + 1e-12)
    flagged = np.asarray(ref.singular[1:], dtype=bool) | \
        np.asarray(ref.undefined_load[1:], dtype=bool) | rec.resist_unsure
    used &= ~flagged
    react = ref.reactions
    parts = []
    errors: dict[str, float] = {}
    verr: dict[str, float] = {}
    notes: list[str] = []

    def err(sim, ks_) -> float:
        if not used.any():
            return float("nan")
        scale = float(np.max(np.abs(ks_[used])))
        d = float(np.max(np.abs(sim[used] - ks_[used])))
        return d / scale if scale > 0.0 else (0.0 if d == 0.0 else float("inf"))

    def add(q, sim, ks_, into=errors, table=True):
        into[q] = err(sim, ks_)
        if table:
            parts.append(pd.DataFrame({"position": rec.position, "time": rec.time,
                                       "quantity": q, "simulated": sim, "computed": ks_,
                                       "used": used}))

    zero: dict[str, float] = {}
    for name, j in sc.joints.items():
        r = react[react.joint == name]
        F = r.F.to_numpy()[1:]
        add(f"F[{name}]", rec.impulse[name], F)
        fx, fy = rec.signed[name]
        add(f"Fx[{name}]", fx, r.Fx.to_numpy()[1:], verr, False)
        add(f"Fy[{name}]", fy, r.Fy.to_numpy()[1:], verr, False)
        if j.kind == "T":
            N, M = r.N.to_numpy()[1:], r.M.to_numpy()[1:]
            add(f"N[{name}]", rec.signed[f"{name}:N"], N, verr, False)
            Ms = rec.signed[f"{name}:M"]
            # a couple that kinetostatics finds zero (to rounding) has no scale of its
            # own: measure it against the joint's force times the mechanism's size
            top = float(np.max(np.abs(M[used]))) if used.any() else 0.0
            big = float(np.max(F[used])) * mechanism_size(sc) if used.any() else 0.0
            if top <= ZERO_COUPLE * big:
                zero[f"M[{name}]"] = (float(np.max(np.abs(Ms[used] - M[used]))) / big
                                      if big > 0.0 else 0.0)
                notes.append(f"prismatic joint {name!r}: kinetostatics gives M = 0; the "
                             f"simulated couple is at most {zero[f'M[{name}]']:.1e} of "
                             "max|F| x the mechanism's size (in vector_errors)")
            else:
                add(f"M[{name}]", Ms, M)
    verr.update(zero)
    q = "Me" if sc.driver.kind == "R" else "Fe"
    drive = np.asarray(ref.Me, dtype=float)[1:]
    add(q, rec.signed["driver"], drive)
    add(f"|{q}|", rec.impulse["driver"], np.abs(drive), verr, False)
    notes.extend(model.notes)
    if model.translating:
        notes.append("bodies that only translate, built with an infinite moment of inertia: "
                     + ", ".join(sorted(model.translating)))
    for name, b in sc.bodies.items():
        if b.mass_model is not None:
            notes.append(f"body {name!r} has a {b.mass_model.kind} mass model: kinetostatics "
                         "uses it, the simulation uses the body's exact mass and inertia")
    if any(j.friction is not None for j in sc.joints.values()):
        notes.append("joint friction is ignored by kinetostatics.solve and by the simulation")
    skipped = int(np.count_nonzero(flagged))
    if skipped:
        notes.append(f"{skipped} of {n} rows flagged singular / undefined_load / resist point "
                     "nearly still: left out of the errors")
    rows = pd.concat(parts, ignore_index=True)
    return CrossCheck(sc, rec, ref, rows, errors, verr, {}, notes)


# ----------------------------------------------------------------------------- study
@dataclass
class Study:
    """Speed against error over time steps and iteration counts.

    Attributes
    ----------
    table : pandas.DataFrame
        ``case, dt, steps_per_revolution, iterations, ms_per_revolution, max_error,
        order`` (``order``: the local order log(e1 / e2) / log(dt1 / dt2) against the
        previous, larger step with the same iterations).
    order : dict
        Iterations -> the order fitted (least squares in log-log) on the errors above
        1e-6, or None with fewer than two such points.
    """

    table: pd.DataFrame
    order: dict[int, float | None]

    def best(self, threshold: float) -> dict[str, Any] | None:
        """The cheapest run (ms per revolution) whose error is at most ``threshold``."""
        ok = self.table[self.table.max_error <= threshold]
        if ok.empty:
            return None
        return ok.sort_values("ms_per_revolution").iloc[0].to_dict()

    def summary(self) -> dict[str, Any]:
        """JSON-ready: the rows, the fitted orders and the cheapest runs at 1e-5 and 1e-6."""
        return {"rows": self.table.to_dict(orient="records"),
                "order": {str(k): v for k, v in self.order.items()},
                "best_1e-5": self.best(1e-5), "best_1e-6": self.best(1e-6)}


def study(scene: Any, *, steps: tuple[int, ...] | None = None,
          dts: tuple[float, ...] | None = None,
          iterations: tuple[int, ...] = STUDY_ITERATIONS, revolutions: float = 2.0,
          samples_per_revolution: int = 360, repeats: int = 1, case: str | None = None,
          fast: bool | None = None, executor: Executor | str | None = None) -> Study:
    """Sweep the time step and the iterations; wall time per revolution against error.

    Parameters
    ----------
    scene : path, TOML text, dict or Scene
    steps : tuple of int, optional
        Steps per revolution to try (default ``STUDY_STEPS``); or give ``dts``.
    dts : tuple of float, optional
        Time steps (s) to try instead.
    iterations : tuple of int
        Solver iterations to try (default 10 and 30).
    revolutions, samples_per_revolution, fast
        As in :func:`crosscheck`.
    repeats : int
        Runs per setting; the wall time is the smallest (the least disturbed).
    case : str, optional
        Label of the ``case`` column (default the scene's title).
    executor : Executor, ``"serial"`` or None
        Runs the settings (times the repeats) as a batch
        (:func:`kinetostatics.simulation.run_batch`): None, processes (one per core);
        ``"serial"``, one after another in this process; or any
        ``concurrent.futures.Executor`` (a dask ``Client.get_executor()``). Each run
        times its own stepping loop in its worker, so the wall times stay per run; but
        runs side by side share the machine (memory, caches, clock boost: on a 2-core
        machine two at once were measured up to about 10 % slower each), so tables of
        wall time are best made ``"serial"``. The errors do not depend on it.

    Returns
    -------
    Study
    """
    sc = _dict_scene(scene)
    if steps is not None and dts is not None:
        raise SimulationError("give steps per revolution or dts, not both")
    grid = [("dt", float(x)) for x in dts] if dts is not None else \
        [("steps", int(x)) for x in (steps or STUDY_STEPS)]
    n_rep = max(1, int(repeats))
    keys = [(int(it), kind, val) for it in iterations for kind, val in grid]
    settings = {"revolutions": revolutions, "samples_per_revolution": samples_per_revolution,
                "fast": fast}
    items = [(sc.raw, kind, val, it, settings) for it, kind, val in keys
             for _ in range(n_rep)]
    done = run_batch(_study_run, items, executor=executor)
    rows = []
    for i, (it, _kind, _val) in enumerate(keys):
        best = min(done[i * n_rep:(i + 1) * n_rep], key=lambda r: r["wall"])
        err = best["max_error"]
        rows.append({"case": case or sc.title, "dt": best["dt"],
                     "steps_per_revolution": best["steps_per_revolution"],
                     "iterations": it, "ms_per_revolution": 1e3 * best["wall"],
                     "max_error": err if math.isfinite(err) else float("inf")})
    table = pd.DataFrame(rows)
    table["order"] = np.nan
    order: dict[int, float | None] = {}
    for it, g in table.groupby("iterations"):
        g = g.sort_values("dt", ascending=False)
        e, h = g.max_error.to_numpy(), g.dt.to_numpy()
        with np.errstate(divide="ignore", invalid="ignore"):
            local = np.log(e[:-1] / e[1:]) / np.log(h[:-1] / h[1:])
        table.loc[g.index[1:], "order"] = local
        fit = (e > ORDER_FLOOR) & np.isfinite(e) & (e < 1.0)
        order[int(it)] = float(np.polyfit(np.log(h[fit]), np.log(e[fit]), 1)[0]) \
            if fit.sum() >= 2 else None
    return Study(table, order)


def _study_run(item: tuple) -> dict[str, Any]:
    """One run of a study (a batch work item: plain data in, plain data out)."""
    raw, kind, val, it, settings = item
    try:
        cc = crosscheck(raw, dt=val if kind == "dt" else None,
                        steps_per_revolution=val if kind == "steps" else None,
                        iterations=it, **settings)
    except (FloatingPointError, np.linalg.LinAlgError) as exc:   # diverged
        raise SimulationError(f"iterations {it}, {kind} {val}: {exc}") from exc
    s = cc.settings
    wall = s["seconds_per_revolution"] or s["seconds_per_sweep"]
    return {"dt": s["dt"], "steps_per_revolution": s["steps_per_revolution"],
            "wall": float(wall), "max_error": float(cc.max_error)}


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
    items = [(_dict_scene(s).raw, dict(settings)) for s in scenes]
    return run_batch(_crosscheck_summary, items, executor=executor)


# ----------------------------------------------------------------------------- plots
def plot_comparison(cc: CrossCheck, quantities: list[str] | None = None, *, every: int = 1):
    """Simulated against computed values over the driver's positions, one panel each.

    Parameters
    ----------
    cc : CrossCheck
    quantities : list of str, optional
        Which (default every joint's ``F[...]``, the locked couples and ``Me``/``Fe``).
    every : int
        Plot every n-th simulated sample as a marker.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure
    qs = quantities or list(dict.fromkeys(cc.rows.quantity))
    ncol = min(3, len(qs))
    nrow = -(-len(qs) // ncol)
    fig = Figure(figsize=(4.2 * ncol, 3.0 * nrow), layout="constrained")
    axes = fig.subplots(nrow, ncol, squeeze=False).ravel()
    xlab = "driver angle (deg)" if cc.scene.driver.kind == "R" else "driver position (m)"
    for ax, q in zip(axes, qs, strict=False):
        g = cc.rows[cc.rows.quantity == q]
        ax.plot(g.position, g.computed, "-", lw=1.2, color="C0", label="kinetostatics")
        s = g.iloc[::max(1, every)]
        ax.plot(s.position, s.simulated, ".", ms=3, color="C1", label="pymunk")
        e = cc.errors.get(q, float("nan"))
        ax.set_title(f"{q}: error {e:.1e}", fontsize=9)
        ax.set_xlabel(xlab)
        ax.set_ylabel(f"{q} ({_unit(q, cc.scene)})")
        ax.grid(alpha=0.3)
    for ax in axes[len(qs):]:
        ax.set_visible(False)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"{cc.scene.title}: pymunk (dt = {cc.settings.get('dt', 0):.3g} s, "
                 f"{cc.settings.get('iterations')} iterations) against kinetostatics",
                 fontsize=10)
    return fig


def plot_study(table: pd.DataFrame | Study):
    """Log-log pictures of a study: error against wall time per revolution, and error
    against dt with a dt^2 guide.

    Parameters
    ----------
    table : pandas.DataFrame or Study
        Rows as in :attr:`Study.table` (several cases may be concatenated).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure
    t = table.table if isinstance(table, Study) else table
    fig = Figure(figsize=(10, 4), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    for i, ((case, it), g) in enumerate(t.groupby(["case", "iterations"], sort=False)):
        g = g.sort_values("dt")
        style = dict(marker="o", ms=4, color=f"C{i % 10}", label=f"{case}, {it} it.")
        ax1.loglog(g.ms_per_revolution, g.max_error, **style)
        ax2.loglog(g.dt, g.max_error, **style)
    for thr, ms in ((1e-5, 20.0), (1e-6, 60.0)):
        ax1.plot([ms], [thr], marker="*", ms=12, color="k", ls="none")
    ax1.axhline(1e-5, color="0.6", lw=0.8, ls="--")
    ax1.axhline(1e-6, color="0.6", lw=0.8, ls="--")
    ax1.set_xlabel("wall time per simulated revolution (ms)")
    ax1.set_ylabel("max relative error")
    ax1.set_title("cost against error (stars: the targets)", fontsize=10)
    if len(t):
        h = np.array([t.dt.min(), t.dt.max()])
        e0 = float(t.max_error[t.dt == t.dt.max()].min())
        ax2.loglog(h, e0 * (h / h[1]) ** 2, "k--", lw=0.8, label="slope 2")
    ax2.set_xlabel("dt (s)")
    ax2.set_ylabel("max relative error")
    ax2.set_title("convergence", fontsize=10)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3, which="both")
    ax2.legend(fontsize=7)
    return fig
