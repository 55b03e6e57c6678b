"""A stacked solve cut per scene (:func:`kinetostatics.solve_many`,
:mod:`~kinetostatics.solver.many`): each scene's :class:`CutSolved`, a view of its run's
Me/Fe and flags, whose kinematics and joint reactions are cut from its run solved again
(:class:`RunAgain`) when first read: the same rows and assemblies, so the same numbers
bit for bit.
"""

from __future__ import annotations

import threading
from dataclasses import replace
from functools import partial
from typing import Any, NamedTuple

import numpy as np

from . import blocks
from .driver import BodyMotion
from .kinematics import Kinematics
from .reactions import DriverReaction
from .solved import Solved
from .stack import Rows


def run_values(sol: Solved) -> tuple:
    """What the scenes of a run keep of its solve ``sol``: the driver's kind, Me/Fe and
    the undefined rows, each dyad's singular rows, each with whether it is an array over
    the run's rows (cut per scene) or a value they share."""
    n_run = sol.positions.size
    drive = np.asarray(sol.drive.value)
    undefined = np.asarray(sol.undefined_load)
    return (sol.drive.kind, drive, per_row(drive, n_run), undefined,
            per_row(undefined, n_run),
            [(f, per_row(f, n_run)) for f in (np.asarray(dm.singular) for dm in sol.kin.dyads)])


def cut_scenes(scenes: list, structure, ks: np.ndarray, starts: np.ndarray,
               counts: np.ndarray, bounds: np.ndarray, runs: list, dead: list) -> list:
    """Each scene's :class:`CutSolved` (``again`` None for a scene of a refused run),
    every field worked out for all the scenes at once and each made in C (measured
    2026-11-29, 1000 four-bars: 0.6 ms a call of solve_many making them one by one in
    Python): its rows in its run, its run's values and ``again`` (the run solved again
    when its kinematics are first read, :class:`RunAgain`), its dead points, and one
    Structure per assembly, shared."""
    run_of = np.repeat(np.arange(bounds.size - 1), np.diff(bounds))
    first = starts - starts[bounds[:-1]][run_of]
    # (each scene's first row in its run, an int: its slice made when read, not a
    # thousand slices that the garbage collector walks, measured 2026-11-30: 1000 of the
    # 4090 objects a call of solve_many left young)
    rows = first.tolist()
    # each scene's assembly as a number (bit d: dyad d's k is -1), its Structure shared
    code = ((ks < 0) << np.arange(ks.shape[0])[:, None]).sum(axis=0)
    table = np.empty(int(code.max()) + 1, dtype=object)
    for c in np.unique(code).tolist():
        table[c] = replace(structure, assembly=tuple(-1 if c >> d & 1 else 1
                                                     for d in range(ks.shape[0])))
    per_run = [np.empty(len(runs), dtype=object) for _ in range(3)]
    for r, got in enumerate(runs):
        for f, x in zip(per_run, (None, None, None) if got is None else got, strict=True):
            f[r] = x
    again, values, path = (f[run_of].tolist() for f in per_run)
    return list(map(partial(tuple.__new__, CutSolved),
                    zip(scenes, table[code].tolist(), again, rows, values, path, dead,
                        strict=True)))


class CutSolved(NamedTuple):
    """One scene's arrays cut from a stacked solve (a
    :class:`~kinetostatics.solver.solved.Deferred`): its scene and structure from the
    start; its ``Me``/``Fe`` and flags (views of its run's arrays) cut when first asked
    for, its kinematics and joint reactions when first asked for (the run solved again
    for all its scenes, :class:`RunAgain`); its loads are computed from its kinematics when
    asked for, as a solve's are. (A tuple: a stack's are made a thousand at a time in C,
    :func:`cut_scenes`.)"""

    scene: Any
    structure: Any
    again: RunAgain | None          # (None: its run refused; the scene is solved alone)
    first: int                  # (its first row in its run's arrays)
    run: tuple                  # (its run's values, :func:`run_values`)
    path: str | None = None     # (the compiled path's "fast"; None: the numpy path's)
    dead: tuple | None = None   # (between, ends, unassembled: once screened)

    @property
    def rows(self) -> slice:
        """Its rows in its run's arrays."""
        return slice(self.first, self.first + self.scene.driver.positions.size)

    @property
    def known(self) -> dict:
        return {"scene": self.scene, "structure": self.structure, "self_locking": None}

    @property
    def positions(self) -> np.ndarray:
        return self.scene.driver.positions

    def singular(self) -> np.ndarray:
        """As :attr:`Kinematics.singular`, from the run's flags (the driver table reads
        it: no need to solve the run again)."""
        rows, run = self.rows, self.run
        return blocks.singular_rows(rows.stop - rows.start,
                                    [f[rows] if cut else f for f, cut in run[5]], self.dead)

    def give(self, name: str, have=()) -> dict:
        """``drive`` or ``undefined_load``: both, views of the run's arrays (the same
        for every thread); ``kin`` or ``joint_reactions``: both, cut from the run solved
        again (with the views, if not held yet)."""
        out = {}
        if "drive" not in have or "undefined_load" not in have:
            rows = self.rows
            kind, drive, drive_rows, undefined, undefined_rows, _ = self.run
            out.update(drive=DriverReaction(kind, drive[rows] if drive_rows else drive),
                       undefined_load=undefined[rows] if undefined_rows else undefined)
        if name in ("kin", "joint_reactions"):
            kin, reactions = self.again.cutter()(self.scene, self.structure, self.rows,
                                                 self.dead)
            out.update(kin=kin, joint_reactions=reactions)
        return out

    def solved(self) -> Solved:
        got = self.give("kin")
        return Solved(self.scene, self.structure, got["kin"], None, got["joint_reactions"],
                      got["drive"], got["undefined_load"])

    def __reduce__(self):
        return _solved, (self.solved(),)


def _solved(solved: Solved) -> Solved:
    return solved


class RunAgain:
    """A run of stacked scenes whose solve was let go once its Me/Fe, flags and
    closeness to the dead centres were taken: solved again (``solve(*args)``, the same
    rows and assemblies, so the same numbers bit for bit) when the kinematics or joint
    reactions of one of its scenes are first read, and then cut for each of them."""

    def __init__(self, solve, args: tuple, cut=None):
        self.solve = solve
        self.args = args
        self.lock = threading.Lock()
        self.cut = cut          # (given: the run kept whole, never solved again)

    def cutter(self):
        """The run's :func:`splitter` (solving the run again, once)."""
        with self.lock:
            if self.cut is None:
                self.cut = splitter(self.solve(*self.args))
                self.solve = self.args = None       # (the stack: no longer needed)
            return self.cut


class _Template:
    """How to cut one object of the stacked solution: its attributes that hold an array
    over the rows (or tuples of them), and the rest, shared."""

    def __init__(self, obj, total: int):
        self.cls = type(obj)
        self.same = {}
        self.rows = []            # (name, array)
        self.parts = []           # (name, tuple of array-or-value, which are arrays)
        for k, v in obj.__dict__.items():
            if per_row(v, total):
                self.rows.append((k, np.asarray(v)))
            elif type(v) is tuple and any(per_row(x, total) for x in v):
                self.parts.append((k, tuple(np.asarray(x) if per_row(x, total) else x
                                            for x in v),
                                   tuple(per_row(x, total) for x in v)))
            else:
                self.same[k] = np.asarray(v) if type(v) is Rows else v

    def cut(self, rows: slice, **extra):
        new = object.__new__(self.cls)
        d = new.__dict__
        d.update(self.same)
        for k, a in self.rows:
            d[k] = a[rows]
        for k, vals, which in self.parts:
            d[k] = tuple([x[rows] if w else x for x, w in zip(vals, which, strict=True)])
        d.update(extra)
        return new


def per_row(v, total: int) -> bool:
    return isinstance(v, np.ndarray) and v.ndim == 1 and v.shape[0] == total


def splitter(sol: Solved):
    """A function (scene, structure, rows, dead points) -> that scene's kinematics and
    joint reactions, cutting the rows of every array of the stacked ``sol``."""
    total = sol.positions.size
    motions = []
    for name, m in sol.kin.bodies.items():
        values = [getattr(m, f) for f in ("_theta", *BodyMotion.FIELDS)]
        motions.append((name, [(np.asarray(v), True) if per_row(v, total) else (v, False)
                               for v in values]))
    known = {id(m): name for name, m in sol.kin.bodies.items()}
    dyads = [(_Template(dm, total), [(_Template(p, total), known[id(p.known)])
                                     for p in dm.params]) for dm in sol.kin.dyads]
    reactions = [(name, _Template(r, total)) for name, r in sol.joint_reactions.items()]

    def cut(scene, structure, rows: slice, dead: tuple) -> tuple:
        bodies = {name: BodyMotion(*[a[rows] if cut_it else a for a, cut_it in fs])
                  for name, fs in motions}
        n = rows.stop - rows.start
        dms = []
        for d, (t, params) in enumerate(dyads):
            pr = tuple([tp.cut(rows, known=bodies[b]) for tp, b in params])
            dms.append(t.cut(rows, dyad=structure.dyads[d], params=pr,
                             k=structure.assembly[d], n=n, _tau=None))
        kin = Kinematics(scene, structure, scene.driver.positions, bodies, dms)
        # the dead points between rows, and the intervals no motion crosses, found per
        # scene along increasing driver position exactly as solve finds them
        kin.between, kin.ends, kin.unassembled = dead
        return (kin,
                {name: t.cut(rows) for name, t in reactions})
    return cut
