"""A population of designs judged at once: one stacked solve, feasibility, the
objectives and the constraints: :func:`evaluate`.

Feasibility is never a penalty nor a partial answer. A design is feasible when its
whole sweep is solved and vouched for: the solver assembles it at every row (else it
refuses the design, naming the rows), no row lies near a dead centre (``singular``:
the sine of a transmission angle below 1e-3), and the solver's own between-row checks
find no dead point and no gap between two rows (``dead_points_between_rows``: a change
of assembly branch or a change point passed; ``unassembled_between_rows``). With
``full_turn`` and a sweep shorter than a turn, the design's whole turn is checked the
same way. A design that is not feasible has no objectives (NaN) and the reason is kept.

Two roads give the same numbers: from stacked arrays alone, the screen, the solve and
every quantity in one pass per run (:mod:`~kinetostatics.design.stacked`, no Scene per
design), where the variables allow; else one Solution per design
(:func:`evaluate_scenes`: each design's Scene, the screen
(:mod:`~kinetostatics.design.screen`), then :func:`~kinetostatics.solve_many`).
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from concurrent.futures import Executor
from dataclasses import dataclass
from functools import partial

import numpy as np

from ..results.solving import solve_outcomes
from ..solver.fast import path_setting, wanted
from .screen import loaded
from .section import DesignSpec
from .stacked import REASONS, judge_stacked

NOT_FINITE = "an objective is not finite"

# the stacked solve keeps every run's arrays: each design's kinematics are read (the
# feasibility, the transmission angle), which a lean solve would solve again (measured for
# 1000 four-bars of 361 rows: about 0.1 s a generation less)
LEAN = False


@dataclass
class Evaluation:
    """The judgement of a population.

    Attributes
    ----------
    values : ndarray (n, objectives)
        Each objective's value (SI or deg, a maximised one as its value); NaN where the
        design is not solved.
    limits : ndarray (n, constraints)
        Each constrained quantity's value (NaN where the design is not solved).
    solved : ndarray of bool
        Solved and vouched for over the whole sweep (and turn).
    feasible : ndarray of bool
        Solved and every constraint kept.
    reasons : list of str or None
        Why each design is infeasible (None for a feasible one).
    """

    values: np.ndarray
    limits: np.ndarray
    solved: np.ndarray
    feasible: np.ndarray
    reasons: list[str | None]

    @staticmethod
    def concat(parts: Sequence[Evaluation]) -> Evaluation:
        return Evaluation(np.concatenate([p.values for p in parts]),
                          np.concatenate([p.limits for p in parts]),
                          np.concatenate([p.solved for p in parts]),
                          np.concatenate([p.feasible for p in parts]),
                          [r for p in parts for r in p.reasons])


def evaluate(spec: DesignSpec, X: np.ndarray, executor: Executor | None = None,
             parts: int = 1) -> Evaluation:
    """Judge the designs ``X`` (one row per design, the variables in the section's
    order): one :func:`~kinetostatics.results.solving.solve_outcomes` call (the stacked
    solve of :func:`~kinetostatics.solve_many`, each design's outcome its Solution or
    the error ``solve`` raises for it) for the whole population, or, through
    ``executor``, one per part of ``parts`` (the numbers are the same: each design's
    are those ``solve`` gives it alone)."""
    X = np.asarray(X, dtype=float)
    if executor is None or parts < 2 or len(X) < 2 * parts:
        return evaluate_rows(spec, X)
    bounds = np.linspace(0, len(X), parts + 1).astype(int)
    chunks = [X[a:b] for a, b in zip(bounds[:-1], bounds[1:], strict=True)]
    return Evaluation.concat(list(executor.map(partial(evaluate_rows, spec), chunks)))


def evaluate_rows(spec: DesignSpec, X: np.ndarray) -> Evaluation:
    """:func:`evaluate` in this process (a top-level function: an executor's task): the
    population judged from stacked arrays (:func:`~kinetostatics.design.stacked.
    judge_stacked`, no Scene per design) where it can be, else, and for the designs it
    leaves (a number not finite), one Solution per design (:func:`evaluate_scenes`).
    On the compiled path, when asked for (:func:`_compiled`), every design is judged from
    the Solution :func:`~kinetostatics.solve_many` gives it, as ``solve`` there solves it."""
    X = np.asarray(X, dtype=float)
    plan = spec.stack_plan
    if plan is None or len(X) < 2 or _compiled(len(X) * plan.base.driver.positions.size):
        return evaluate_scenes(spec, X)
    ev = _evaluate_stacked(spec, plan, X)
    return evaluate_scenes(spec, X) if ev is None else ev


def _compiled(rows: int) -> bool:
    """Whether the designs are judged on the compiled path: only when it is asked for
    (``KINETOSTATICS_PATH=fast`` or ``use("fast")``). Under ``auto`` the stacked judge
    stays (numpy's numbers): judging one Solution per design from the compiled
    ``solve_many`` took 84 s of CPU against 19 s for ``design four_bar_design
    --population 1000 --generations 100`` (docs/design.md, 2026-11-29)."""
    return path_setting() == "fast" and wanted(rows) is not None


def _evaluate_stacked(spec: DesignSpec, plan, X: np.ndarray) -> Evaluation | None:
    """:func:`evaluate_rows` by :func:`~kinetostatics.design.stacked.judge_stacked` (and,
    with ``full_turn`` over a partial sweep, the whole turn's too); None when the
    population cannot be stacked."""
    V = spec.set_values(X)
    quantities = list({q.name: q for q in [c.quantity for c in spec.constraints]
                       + [o.quantity for o in spec.objectives]}.values())
    main = judge_stacked(plan, V, quantities)
    turn = None
    if main is not None and spec.turn_plan is not None:
        turn = judge_stacked(spec.turn_plan, V, [])
    if main is None or (spec.turn_plan is not None and turn is None):
        return None
    again = main.again | (turn.again if turn is not None else False)
    code = np.where(again, 0, main.why)
    turned = (code == 0) & ~again & (turn.why != 0 if turn is not None else False)
    solved = (code == 0) & ~turned & ~again
    values = np.full((len(X), len(spec.objectives)), np.nan)
    limits = np.full((len(X), len(spec.constraints)), np.nan)
    for k, o in enumerate(spec.objectives):
        values[solved, k] = main.quantities[o.quantity.name][solved]
    for k, c in enumerate(spec.constraints):
        limits[solved, k] = main.quantities[c.quantity.name][solved]
    reasons = [REASONS[c] for c in code.tolist()]
    for i in np.flatnonzero(turned).tolist():
        reasons[i] = f"full_turn: {REASONS[turn.why[i]]}"
    broken = _broken(spec, values, limits, solved)
    for i in np.flatnonzero(broken >= 0).tolist():
        b = int(broken[i])
        reasons[i] = f"{spec.constraints[b].text} not kept" if b < len(spec.constraints) \
            else NOT_FINITE
    feasible = solved & (broken < 0)
    ev = Evaluation(values, limits, solved, feasible, reasons)
    redo = np.flatnonzero(again)
    if redo.size:
        _put(ev, redo, evaluate_scenes(spec, X[redo]))
    return ev


def _broken(spec: DesignSpec, values: np.ndarray, limits: np.ndarray, solved: np.ndarray
            ) -> np.ndarray:
    """Per design solved, the first constraint it breaks (its index; the number of
    constraints: a quantity not finite), else -1 (as :func:`_judged`, every design at
    once: the same arithmetic, elementwise)."""
    out = np.full(len(solved), -1)
    bad = solved & ~(np.isfinite(values).all(axis=1) & np.isfinite(limits).all(axis=1))
    out[bad] = len(spec.constraints)
    for k in reversed(range(len(spec.constraints))):    # (the first broken one last)
        with np.errstate(invalid="ignore"):
            hit = solved & ~bad & (spec.constraints[k].excess(limits[:, k]) > 0)
        out[hit] = k
    return out


def _put(ev: Evaluation, rows: np.ndarray, part: Evaluation) -> None:
    """Part's designs into ``ev`` at ``rows``."""
    ev.values[rows], ev.limits[rows] = part.values, part.limits
    ev.solved[rows], ev.feasible[rows] = part.solved, part.feasible
    for i, r in zip(rows.tolist(), part.reasons, strict=True):
        ev.reasons[i] = r


def evaluate_scenes(spec: DesignSpec, X: np.ndarray) -> Evaluation:
    """The designs ``X`` judged one Solution each: the designs the screen
    (:func:`~kinetostatics.design.screen.screen`) sets aside are not solved; the others
    are, in one call."""
    n = len(X)
    made = [spec.design_scene(x) for x in X]
    turns = [spec.turn_dict(d) for d, _ in made]
    dicts = [s for _, s in made] + [t for t in turns if t is not None]
    scenes, why = loaded(dicts)
    go = [i for i, (s, w) in enumerate(zip(scenes, why, strict=True))
          if w is None and not isinstance(s, Exception)]
    outcomes: list = [w if w is not None else s for s, w in zip(scenes, why, strict=True)]
    for i, sol in zip(go, solve_outcomes([scenes[i] for i in go], lean=LEAN), strict=True):
        outcomes[i] = sol
    turn_of = iter(range(n, len(dicts)))
    values = np.full((n, len(spec.objectives)), np.nan)
    limits = np.full((n, len(spec.constraints)), np.nan)
    feasible = np.zeros(n, dtype=bool)
    solved = np.zeros(n, dtype=bool)
    reasons: list[str | None] = [None] * n
    for i, turn in enumerate(turns):
        t = None if turn is None else next(turn_of)
        why_i = unvouched(outcomes[i])
        if why_i is None and t is not None:
            why_t = unvouched(outcomes[t])
            why_i = None if why_t is None else f"full_turn: {why_t}"
        if why_i is None:
            solved[i] = True
            why_i = _judge(spec, outcomes[i], i, values, limits)
        reasons[i] = why_i
        feasible[i] = why_i is None
    return Evaluation(values, limits, solved, feasible, reasons)


def _judge(spec: DesignSpec, sol, i: int, values: np.ndarray, limits: np.ndarray
           ) -> str | None:
    """Fill row ``i`` of the values and limits of a solved design; the first broken
    constraint, or None."""
    known: dict[str, float] = {}       # (a quantity both constrained and an objective: once)
    for q in [c.quantity for c in spec.constraints] + [o.quantity for o in spec.objectives]:
        if q.name not in known:
            known[q.name] = q.of(sol)
    return _judged(spec, known, i, values, limits)


def _judged(spec: DesignSpec, known: dict, i: int, values: np.ndarray, limits: np.ndarray
            ) -> str | None:
    """Fill row ``i`` of the values and limits from the design's quantities by name
    (``known``); the first broken constraint, or None."""
    for k, c in enumerate(spec.constraints):
        limits[i, k] = known[c.quantity.name]
    for k, o in enumerate(spec.objectives):
        values[i, k] = known[o.quantity.name]
    if not np.isfinite(values[i]).all() or not np.isfinite(limits[i]).all():
        return NOT_FINITE
    for k, c in enumerate(spec.constraints):
        if c.excess(limits[i, k]) > 0:
            return f"{c.text} not kept"
    return None


def unvouched(sol) -> str | None:
    """Why a solve's outcome (a Solution, the error the solver raised, or the screen's
    reason) cannot be vouched for over its whole sweep, or None."""
    if isinstance(sol, str):        # (set aside by the screen)
        return sol
    if isinstance(sol, Exception):
        return reason_of(sol)
    if len(sol.kin.between):
        return "a dead point between rows (a change of branch)"
    if len(sol.kin.unassembled):
        return "cannot be assembled between two rows"
    if sol.singular.any():
        return "passes a dead centre (a row with sin tau below 1e-3)"
    locked = sol.self_locking
    if locked is not None and locked.any():
        return "self-locking rows"
    return None


def reason_of(exc: Exception) -> str:
    """The gist of the solver's refusal, without its rows and numbers (to count the
    commonest reason): ``dyad RRR(coupler, rocker) cannot be assembled``."""
    text = re.split(r" at | by |: |; ", str(exc), maxsplit=1)[0]
    return text if text else type(exc).__name__


def excess(spec: DesignSpec, ev: Evaluation) -> np.ndarray:
    """The constraints as the search sees them (<= 0 kept): first, whether the design is
    solved and vouched for (0 or 1); then each constraint's relative excess (1 where the
    design is not solved)."""
    g = np.ones((len(ev.feasible), 1 + len(spec.constraints)))
    solved = ev.solved
    g[solved, 0] = 0.0
    for k, c in enumerate(spec.constraints):
        col = ev.limits[:, k]
        ok = solved & np.isfinite(col)
        g[ok, 1 + k] = c.excess(col[ok])      # (elementwise: each design's own number)
    g[~np.isfinite(g)] = 1.0
    return g


def minimised(spec: DesignSpec, values: np.ndarray, feasible: np.ndarray | None = None
              ) -> np.ndarray:
    """The objectives as the search minimises them (a maximised one negated); those of a
    design not ``feasible`` are +inf (never compared: its constraints rank it)."""
    sense = np.array([o.sense for o in spec.objectives], dtype=float)
    f = values * sense
    if feasible is not None:
        f[~feasible] = math.inf
    f[~np.isfinite(f)] = math.inf
    return f
