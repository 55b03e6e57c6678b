"""A population judged from stacked arrays alone: :func:`judge_stacked`.

A design changes a few numbers of the scene (a ground point's or a body point's
coordinate, a centre of mass, a mass, an inertia: the paths
:func:`~kinetostatics.design.scenes.scene_maker` sets directly). The population's
numbers are laid straight into the stacked arrays of
:class:`~kinetostatics.solver.stack.Stacker` (no Scene per design: a Scene is made only
for a design written out), and each run of whole designs of about ``RUN_ROWS`` rows is
solved once, kinematics and loads, with ``strict = False`` and both measures of the
closeness to a dead centre (``screened``): the rows of a design that cannot close are
NaN there and touch no other row (every operation is elementwise). From that one pass:

- the screen (:mod:`~kinetostatics.design.screen`): a design that cannot close at its
  first row, nor at some row, or comes within ``SINGULAR_WARN`` of a dead centre as a
  probe measures it, is set aside with the screen's reason;
- for the others, what :func:`~kinetostatics.solve_many` gives them: their rows are the
  rows a strict solve of the stack of those designs alone gives (the same elementwise
  operations; its closeness, singular flags and refusals are the strict ones), the dead
  points between rows screened for all at once
  (:func:`~kinetostatics.solver.deadpoints.dead_points_stacked`), every number checked
  finite as the solve checks it;
- every objective and constraint, for all the run's designs at once
  (:meth:`~kinetostatics.design.vocabulary.Quantity.of_designs`).

A design whose numbers are not all finite (the solve would refuse it: its reason is the
solve's own) and a run the pass refuses are judged by
:func:`~kinetostatics.design.judging.evaluate_rows` as before; so is a population this
cannot stack (another path, ``[units]``, a mass model, joint friction, masses that the
solver's tests tell apart).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..model.scene import Scene
from ..results.solution import Solution
from ..solver.deadpoints import dead_points_stacked, kin_measure2
from ..solver.kinematics import SINGULAR_WARN, Kinematics, solve_kinematics
from ..solver.many import RUN_ROWS, run_bounds
from ..solver.pipeline import solve_rows
from ..solver.probes import probe_closeness
from ..solver.solved import Solved
from ..solver.stack import Stacker, assemblies, signature
from ..solver.structure import Structure, analyse
from .scenes import direct_places
from .screen import DEAD_CENTRE, NOT_AT_FIRST_ROW, NOT_OVER_SWEEP


@dataclass
class Plan:
    """How a population of ``base`` is stacked: the places of the paths a design sets
    (:func:`~kinetostatics.design.scenes.direct_places`), the points whose coordinates
    vary (for the scene's size) and the largest distance of the others."""

    base: Scene
    places: list
    varied: list            # (body or None for ground, point): their hypot per design
    fixed_size: float
    structure: Structure


def plan_of(base: Scene, raw: dict, paths: list) -> Plan | None:
    """The :class:`Plan` of a scene, or None when its designs cannot be stacked here."""
    places = direct_places(base, raw, paths)
    pos = base.driver.positions
    if places is None or signature(base) is None or pos.size < 1 \
            or not bool(np.all(pos[1:] > pos[:-1])):
        return None         # (a sweep that repeats a position: refused per design)
    if any(ld.resist is not None or ld.when == "resisting" for ld in base.loads):
        return None         # (a sweep's maxima: solved per design by solve_many)
    varied = sorted({(None if kind == "ground" else name, key if kind == "points" else name)
                     for kind, name, key, _ in places if kind in ("ground", "points")},
                    key=repr)
    sizes = [math.hypot(*p) for name, p in base.ground.items() if (None, name) not in varied]
    sizes += [math.hypot(*p) for b in base.bodies.values() for k, p in b.points.items()
              if (b.name, k) not in varied]
    return Plan(base, places, varied, max([1e-3] + sizes), analyse(base, assemble=False))


def _column(values: np.ndarray):
    """A number over the designs: the first design's when all have its bits (as
    :class:`~kinetostatics.solver.stack.Stacker` keeps it), else the array."""
    bits = values.view(np.int64)
    return float(values[0]) if (bits == bits[0]).all() else values


def stacker_of(plan: Plan, V: np.ndarray) -> Stacker | None:
    """The stacker of the designs whose set numbers are the columns of ``V`` (in the
    order of ``plan.places``), or None when the solver's tests on their masses differ
    (as :func:`~kinetostatics.solver.stack.signature` tells scenes apart)."""
    base = plan.base
    m = len(V)
    ground = {p: [np.full(m, v[0]), np.full(m, v[1])] for p, v in base.ground.items()}
    bodies = {name: [np.full(m, b.mass), np.full(m, b.inertia),
                     None if b.cog is None else [np.full(m, b.cog[0]), np.full(m, b.cog[1])],
                     {k: [np.full(m, p[0]), np.full(m, p[1])] for k, p in b.points.items()}]
              for name, b in base.bodies.items()}
    for col, (kind, name, key, i) in enumerate(plan.places):
        v = np.ascontiguousarray(V[:, col], dtype=float)
        if kind == "ground":
            ground[name][i] = v
        elif kind == "points":
            bodies[name][3][key][i] = v
        elif kind == "cog":
            bodies[name][2][i] = v
        else:
            slot = 0 if kind == "mass" else 1
            if len({(x == 0.0, x > 0.0) for x in v.tolist()}) > 1:
                return None
            bodies[name][slot] = v
    size = np.full(m, plan.fixed_size)
    for body, point in plan.varied:
        xy = ground[point] if body is None else bodies[body][3][point]
        h = np.array([math.hypot(x, y) for x, y in zip(xy[0].tolist(), xy[1].tolist(),
                                                        strict=True)])
        size = np.maximum(size, h)   # (max of floats, none NaN: Scene.size's own max)
    cols = {p: tuple(_column(c) for c in xy) for p, xy in ground.items()}
    bods = {name: (_column(mass), _column(inertia),
                   None if cog is None else tuple(_column(c) for c in cog),
                   {k: tuple(_column(c) for c in xy) for k, xy in pts.items()})
            for name, (mass, inertia, cog, pts) in bodies.items()}
    return Stacker.of_columns(base, m, cols, bods, _column(size))


@dataclass
class RunSolution:
    """A run of ``m`` stacked designs of ``n`` rows each at ``positions``: its
    :class:`~kinetostatics.results.Solution` (``sol``), what the quantities read."""

    sol: Solution
    m: int
    n: int
    positions: np.ndarray


BETWEEN = "a dead point between rows (a change of branch)"
UNASSEMBLED = "cannot be assembled between two rows"
PASSES = "passes a dead centre (a row with sin tau below 1e-3)"
# why a design is set aside or cannot be vouched for, by its code (0: vouched for), as
# the screen and :func:`~kinetostatics.design.judging.unvouched` say it
REASONS = (None, NOT_AT_FIRST_ROW, NOT_OVER_SWEEP, DEAD_CENTRE, BETWEEN, UNASSEMBLED, PASSES)


@dataclass
class Stacked:
    """Per design of a population: why it is set aside or cannot be vouched for (``why``,
    a code of :data:`REASONS`; 0 when vouched for), whether to judge it again one by one
    (``again``) and its quantities by name."""

    why: np.ndarray
    again: np.ndarray
    quantities: dict


def judge_stacked(plan: Plan, V: np.ndarray, quantities: list) -> Stacked | None:
    """The designs ``V`` solved and judged in stacked runs (see the module), or None when
    they cannot be stacked here."""
    stacker = stacker_of(plan, V)
    if stacker is None:
        return None
    m, n = len(V), plan.base.driver.positions.size
    structure = plan.structure
    try:        # (refused, solve_many solves each design alone: so does the caller)
        with np.errstate(all="ignore"):
            ks, ok = assemblies(stacker, structure)
    except Exception:
        return None
    counts = np.full(m, n)
    starts = np.arange(m) * n
    positions = np.tile(plan.base.driver.positions, m)
    bounds = run_bounds(starts, counts, RUN_ROWS)
    m2 = np.full(m * n, np.inf)
    passed = np.zeros(m, dtype=bool)
    reach = np.ones(m, dtype=bool)
    finite = np.ones(m, dtype=bool)
    flagged = np.zeros(m, dtype=bool)
    again = np.zeros(m, dtype=bool)
    values = {q.name: np.full(m, np.nan) for q in quantities}
    for lo, hi in zip(bounds[:-1].tolist(), bounds[1:].tolist(), strict=True):
        a, b = lo * n, hi * n
        st = replace(structure, assembly=tuple(np.repeat(k[lo:hi], n) for k in ks))
        sc = stacker.runs(lo, hi, counts[lo:hi], positions[a:b])
        try:
            with np.errstate(all="ignore"):
                kin = solve_kinematics(sc, st, strict=False, screened=True)
                sol = solve_rows(sc, st, kin)
        except Exception:
            again[lo:hi] = ok[lo:hi]
            continue
        rows = _RunRows(kin, sol, hi - lo, n)
        reach[lo:hi] = rows.reach()
        passed[lo:hi] = ok[lo:hi] & rows.clear()
        finite[lo:hi] = rows.finite()
        flagged[lo:hi] = rows.flagged()
        m2[a:b] = np.where(np.repeat(passed[lo:hi], n), rows.measure2(), np.inf)
        run = RunSolution(Solution.of(sol), hi - lo, n, plan.base.driver.positions)
        with np.errstate(all="ignore"):
            for q in quantities:
                values[q.name][lo:hi] = q.of_designs(run)
    try:
        dead = _dead_points(stacker, structure, ks, m2, positions, starts, counts)
    except Exception:       # (as solve_many: each design alone)
        return None
    again |= passed & ~finite
    between, unassembled, ends = (np.array([len(d[i]) for d in dead], dtype=bool)
                                  for i in (0, 2, 1))
    why = np.select([~ok, ~reach, ~passed, between, unassembled, flagged | ends],
                    [1, 2, 3, 4, 5, 6], 0)
    return Stacked(np.where(again, 0, why), again, values)


def _dead_points(stacker: Stacker, structure, ks: np.ndarray, m2: np.ndarray,
                 positions: np.ndarray, starts: np.ndarray, counts: np.ndarray) -> list:
    """The dead points between rows of every design (``m2`` inf where none is looked
    for), probed at once as :func:`~kinetostatics.solve_many` probes them."""
    def at(where: np.ndarray, who: np.ndarray) -> tuple:
        # (the closeness from the positions alone, as solve_many's probes: the same
        # numbers as the kinematics solved with strict = False)
        probe = replace(structure, assembly=tuple(k[who] for k in ks))
        return probe_closeness(stacker.scene(who, where), probe)
    return dead_points_stacked(m2, positions, starts, counts, at)


class _RunRows:
    """Per design of a run (``m`` designs of ``n`` rows), what its rows tell."""

    def __init__(self, kin: Kinematics, sol: Solved, m: int, n: int):
        self.kin, self.sol, self.m, self.n = kin, sol, m, n

    def _per(self, a, op) -> np.ndarray:
        if not (isinstance(a, np.ndarray) and a.shape == (self.m * self.n,)):
            a = np.broadcast_to(a, (self.m * self.n,))
        return op.reduce(a.reshape(self.m, self.n), axis=1)

    def reach(self) -> np.ndarray:
        """Every row closes (the probe's measure is a number)."""
        out = np.ones(self.m, dtype=bool)
        for dm in self.kin.dyads:
            out &= self._per(~np.isnan(dm.probe2), np.logical_and)
        return out

    def clear(self) -> np.ndarray:
        """Every row closes and stays clear of a dead centre as a probe measures it (the
        screen's test)."""
        out = np.ones(self.m, dtype=bool)
        for dm in self.kin.dyads:
            out &= self._per(dm.probe2 > SINGULAR_WARN**2, np.logical_and)
        return out

    def flagged(self) -> np.ndarray:
        """A row flagged singular by the strict measure."""
        out = np.zeros(self.m, dtype=bool)
        for dm in self.kin.dyads:
            out |= self._per(dm.singular, np.logical_or)
        return out

    def measure2(self) -> np.ndarray:
        """The strict closeness per row, the smallest over the dyads."""
        return kin_measure2(self.kin)

    def finite(self) -> np.ndarray:
        """Every number the solve checks finite is (its
        :func:`~kinetostatics.solver.pipeline` check, per design)."""
        sol = self.sol
        arrays = [getattr(b, f) for b in sol.kin.bodies.values()
                  for f in ("cos", "sin", "omega", "alpha", "ox", "oy", "vx", "vy", "ax", "ay")]
        arrays += [d.closeness2 for d in sol.kin.dyads]
        arrays.append(sol.drive.value)
        for r in sol.joint_reactions.values():
            arrays += [v for v in (r.fx, r.fy, r.N, r.M) if v is not None]
        total = np.zeros(self.m * self.n)
        with np.errstate(all="ignore"):
            for a in arrays:
                # every array added into one (a NaN or an infinity anywhere makes the
                # row's total non-finite), then one sum per design; a total that
                # overflows with every value finite also reads not finite: the design is
                # then judged again one by one, where the solve looks closer
                if isinstance(a, np.ndarray) and a.ndim:
                    total += a
                elif not math.isfinite(float(a)):
                    return np.zeros(self.m, dtype=bool)
            out = np.isfinite(np.add.reduce(total.reshape(self.m, self.n), axis=1))
        return out
