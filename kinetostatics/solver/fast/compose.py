"""The compiled kernels composed over blocks of rows, and their arrays wrapped in the
solver's objects (no numba here: the kernels module is passed in).

Per block of rows: the driver's motion, each dyad's motion in solving order, each body's
load resultants, each dyad's reactions in reverse order, the driver's Me/Fe (the numpy
path's :func:`~kinetostatics.solver.kinematics.solve_kinematics` then
:func:`~kinetostatics.solver.reactions.solve_reactions`, row by row). A long sweep keeps
only what the driver table and the dead points need, block by block in scratch arrays
(:class:`~kinetostatics.solver.blocks.Kept`); the full solve writes arrays over the
whole sweep, wrapped without copies in the :class:`BodyMotion`, :class:`DyadMotion` and
:class:`JointReaction` objects every table reads.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...model.scene import GROUND, Scene
from ..blocks import BLOCK_ROWS, Kept
from ..closure import Param
from ..driver import BodyMotion, ground_motion
from ..kinematics import SINGULAR_WARN, DyadMotion, Kinematics
from ..loads import RESIST_STILL
from ..reactions import DriverReaction, record_reaction
from ..solved import Solved
from . import layout as L
from .geometry import (
    body_loads_geometry,
    driver_geometry,
    dyad_geometry,
    swept_loads_geometry,
)


class Refused(Exception):
    """A kernel wrote a value that is not finite, or met a row the numpy path refuses:
    the sweep is solved on the numpy path, whose message names the rows."""


class Plan:
    """The kernels and their geometry for one scene (or stack) and structure, each dyad
    with its assembly ``ks`` (numbers, or arrays over a stack's rows)."""

    def __init__(self, kernels, scene: Scene, structure, ks):
        self.k = kernels
        self.scene, self.structure = scene, structure
        drv = scene.driver
        self.crank = drv.kind == "R"
        self.speed, self.accel = float(drv.speed), float(drv.acceleration)
        self.driver = driver_geometry(scene)
        self.dyads = [(*dyad_geometry(scene, d, k), d)
                      for d, k in zip(structure.dyads, ks, strict=True)]
        self.bodies = list(scene.bodies)
        self.loads = {b: body_loads_geometry(scene, b) for b in self.bodies}
        self.swept = {b: sw for b in self.bodies
                      if (sw := swept_loads_geometry(scene, b))[2]}
        self.tables()

    def check_swept(self) -> None:
        """Refuse (:class:`Refused`) a sweep whose top speed (power) of a ``resist``
        (``when = "resisting"``) load lifts its still threshold over a row the kernel took
        as moving (the numpy path tells those rows from the whole sweep)."""
        for b, (_, _, floors) in self.swept.items():
            for (top, least), floor in zip(self.stats[b], floors, strict=True):
                if not least > RESIST_STILL * max(top, floor):
                    raise Refused("swept load")

    def tables(self) -> None:
        """The structure as :func:`~kinetostatics.solver.fast.tiles.sweep` reads it: each
        dyad's kind and bodies as indices of the stacked motions (the ground 0), the
        geometry as tuples of arrays (each with a stand-in, so that none is empty)."""
        index = {b: i for i, b in enumerate((GROUND, *self.bodies))}
        self.index = index
        ops = [(L.KINDS[d.kind], index[d.outer[0].other(d.bodies[0])],
                index[d.outer[1].other(d.bodies[1])], index[d.bodies[0]], index[d.bodies[1]])
               for _, _, d in self.dyads]
        self.ops = np.array(ops, dtype=np.int64).reshape(len(ops), self.k.OPS)
        stand_in = np.zeros((L.PARAM, 1))
        self.gd = (*(g for g, _, _ in self.dyads), stand_in)
        self.gds = np.array([gs for _, gs, _ in self.dyads] + [0], dtype=np.int64)
        loads = [(stand_in, 0, 0)] + [self.loads[b] for b in self.bodies]
        self.gl = tuple(g for g, _, _ in loads)
        self.gls = np.array([gs for _, gs, _ in loads], dtype=np.int64)
        self.npoint = np.array([k for _, _, k in loads], dtype=np.int64)
        swept = [self.swept.get(b, (stand_in, 0, [])) for b in (GROUND, *self.bodies)]
        self.gsw = tuple(g for g, _, _ in swept)
        self.gsws = np.array([gs for _, gs, _ in swept], dtype=np.int64)
        self.nload = np.array([len(f) for _, _, f in swept], dtype=np.int64)
        stats = np.zeros((len(swept), max(1, *self.nload), 2))
        stats[:, :, 1] = np.inf
        self.stats_all = stats
        self.stats = {b: stats[index[b], :len(f)] for b, (_, _, f) in self.swept.items()}

    def buffers(self, width: int) -> dict:
        """Arrays for ``width`` rows: every body's motion and load resultants, each dyad's
        data and reactions, the driver's reaction, each stacked (its rows padded,
        :func:`~kinetostatics.solver.fast.layout.padded_width`; the ground's motion
        constant, what a kernel may leave unwritten zeroed)."""
        stride = L.padded_width(width)
        nb, nd = len(self.bodies) + 1, len(self.dyads)
        # (np.empty: memory a freed slab leaves is reused without faulting in fresh
        # zeroed pages)
        m = np.empty((nb, L.MOTION, stride))
        m[0] = 0.0
        m[0, L.C] = 1.0
        out = {"m": m, "a": np.empty((nb, 3, stride)),
               "d": np.zeros((max(nd, 1), L.DYAD_OUT, stride)),
               "r": np.zeros((max(nd, 1), L.REACTIONS, stride)),
               "drv": np.zeros((7, stride)), "u": np.zeros(stride, dtype=bool)}
        out["a"][0] = 0.0
        return out

    def run(self, x: np.ndarray, lo: int, hi: int, buf: dict, lean=None) -> None:
        """Rows ``lo`` to ``hi`` (``x``: the driver's angles in rad, or its positions) in
        one compiled call: into ``buf`` at ``i``, or (``lean``: the arrays Me/Fe, the
        undefined rows and the closeness kept, at ``i``) through ``buf``, one tile's
        scratch. A crank's cos and sin are numpy's, in a pass of their own. Raises
        :class:`Refused`."""
        m = buf["m"]
        drv = self.index[self.scene.driver.body]
        cs = sn = x[:0]
        if self.crank and lean is None:
            np.cos(x[lo:hi], out=m[drv, L.C, lo:hi])
            np.sin(x[lo:hi], out=m[drv, L.S, lo:hi])
        elif self.crank:
            cs, sn = np.cos(x[lo:hi]), np.sin(x[lo:hi])
        drive, kept_u, close = lean if lean is not None else (x[:0], buf["u"][:0], buf["d"][0])
        g, gs = self.driver
        bad = self.k.sweep(lo, hi, lean is not None, x, cs, sn, self.crank, g, gs, self.speed,
                           self.accel, drv, self.ops, self.gd, self.gds, self.gl, self.gls,
                           self.npoint, self.gsw, self.gsws, self.nload, self.stats_all, m,
                           buf["a"], buf["d"], buf["r"], buf["drv"], buf["u"], drive, kept_u,
                           close)
        if bad:
            raise Refused(bad)


def driver_input(scene: Scene) -> np.ndarray:
    """What the driver kernel reads per row: a crank's angles (rad), a slider's positions."""
    drv = scene.driver
    return drv.angles if drv.kind == "R" else np.asarray(drv.positions, dtype=float)


def solve_full(plan: Plan, positions: np.ndarray) -> Solved:
    """The whole sweep's Solved (every table's arrays), in one compiled call into arrays
    over the whole sweep."""
    n = positions.size
    buf = plan.buffers(n)
    plan.run(driver_input(plan.scene), 0, n, buf)
    plan.check_swept()
    return _solution(plan, positions, _cut(plan, buf, n))


def _cut(plan: Plan, buf: dict, n: int) -> dict:
    """The buffers' first ``n`` columns by body and by dyad (views: the rows are padded)."""
    names = (GROUND, *plan.bodies)
    nd = len(plan.dyads)
    return {"m": {b: buf["m"][i, :, :n] for i, b in enumerate(names)},
            "a": {b: buf["a"][i, :, :n] for i, b in enumerate(names)},
            "d": [buf["d"][q, :, :n] for q in range(nd)],
            "r": [buf["r"][q, :, :n] for q in range(nd)],
            "drv": buf["drv"][:, :n], "u": buf["u"][:n]}


def solve_lean(plan: Plan, positions: np.ndarray, block: int = BLOCK_ROWS) -> Kept:
    """A long sweep's :class:`~kinetostatics.solver.blocks.Kept`: Me/Fe and each dyad's
    closeness to a dead centre, the rest of each tile in scratch arrays (one compiled
    call a block of rows: a crank's cos and sin are worked out a block at a time)."""
    n = positions.size
    x = driver_input(plan.scene)
    buf = plan.buffers(plan.k.TILE)
    drive = np.empty(n)
    undefined = np.zeros(n, dtype=bool)
    close = np.empty((max(len(plan.dyads), 1), n))
    for lo in range(0, n, block):
        plan.run(x, lo, min(lo + block, n), buf, (drive, undefined, close))
    plan.check_swept()
    kind = plan.scene.driver.kind
    close = list(close[:len(plan.dyads)])
    singular = [~(c > SINGULAR_WARN**2) for c in close]
    return Kept(plan.structure, DriverReaction(kind, drive), undefined, close, singular)


def _param(scene: Scene, dyad, i: int, known: BodyMotion, m: np.ndarray, d: np.ndarray
           ) -> Param:
    joint, name = dyad.outer[i], dyad.bodies[i]
    b = 10 + 4 * i
    if joint.kind == "R":
        local = scene.bodies[name].local(joint.point_on(name))
        return Param("rot", known, local, d[b], d[b + 1], None, None, None, None)
    return Param("trans", known, c=m[L.C], s=m[L.S], ux=d[b], uy=d[b + 1], bx=d[b + 2],
                 by=d[b + 3])


def _solution(plan: Plan, positions: np.ndarray, buf: dict) -> Solved:
    """The Solved over the rows of ``buf`` (arrays over the whole sweep), every array a
    view of the kernels' output."""
    scene, n = plan.scene, positions.size
    m = buf["m"]
    drv = scene.driver
    bodies = {GROUND: ground_motion(), drv.body: BodyMotion(drv.angles if drv.kind == "R"
                                                            else None, *m[drv.body])}
    dyads = []
    for (g, gs, dyad), d in zip(plan.dyads, buf["d"], strict=True):
        for b in dyad.bodies:
            bodies[b] = BodyMotion(None, *m[b])
        pr = tuple(_param(scene, dyad, i, bodies[dyad.outer[i].other(dyad.bodies[i])],
                          m[dyad.bodies[i]], d) for i in range(2))
        inner = dyad.inner
        q = (tuple(g[L.Q1X:L.Q1Y + 1, 0]), tuple(g[L.Q2X:L.Q2Y + 1, 0])) if not gs else None
        if inner.kind == "R" and q is None:
            q = tuple(scene.bodies[b].local(inner.point_on(b)) for b in dyad.bodies)
        k = int(g[L.ASSEMBLY, 0]) if not gs else g[L.ASSEMBLY]
        dyads.append(DyadMotion(
            dyad, pr, k, d[L.XX], d[L.XY], (d[L.C1X], d[L.C1Y]), (d[L.C2X], d[L.C2Y]),
            d[L.DET], n, singular=~(d[L.CL2] > SINGULAR_WARN**2), closeness2=d[L.CL2],
            inner_local=q if inner.kind == "R" else None,
            slider_first=inner.kind == "T" and inner.slider == dyad.bodies[0],
            nx=d[L.NX] if inner.kind == "T" else None,
            ny=d[L.NY] if inner.kind == "T" else None))
    structure = plan.structure
    kin = Kinematics(scene, structure, positions, bodies, dyads)
    reactions = _reactions(plan, buf)
    r = buf["drv"]
    # (Me/Fe copied out: a stacked run's scenes keep it, not the slab it lies in)
    sol = Solved(scene, structure, kin, None, reactions,
                 DriverReaction(drv.kind, r[0].copy()), buf["u"])
    sol.path = "fast"
    return sol


def _reactions(plan: Plan, buf: dict) -> dict:
    """The joint reactions in the numpy path's order (dyads last to first, each its inner
    joint then its outer ones; the driver's joint last)."""
    scene, a = plan.scene, buf["a"]
    out: dict = {}
    for (_, _, dyad), d, r in zip(plan.dyads[::-1], buf["d"][::-1], buf["r"][::-1],
                                     strict=True):
        inner = dyad.inner
        if inner.kind == "R":
            record_reaction(out, inner, dyad.bodies[1], r[L.R_FX], r[L.R_FY], d[L.XX], d[L.XY])
        else:
            record_reaction(out, inner, inner.slider, r[L.R_FX], r[L.R_FY], d[L.XX], d[L.XY],
                    r[L.R_N], r[L.R_M])
        for i, (name, joint) in enumerate(zip(dyad.bodies, dyad.outer, strict=True)):
            if joint.kind == "R":
                b = 10 + 4 * i
                record_reaction(out, joint, name, a[name][0], a[name][1], d[b], d[b + 1], sign=-1.0)
                continue
            o = 4 + 6 * i
            record_reaction(out, joint, name, r[o + L.R_FX], r[o + L.R_FY], r[o + L.R_SX],
                    r[o + L.R_SY], r[o + L.R_N], r[o + L.R_M])
    drv = scene.driver
    joint = scene.joints[drv.joint]
    ad, r = a[drv.body], buf["drv"]
    if drv.kind == "R":
        px, py = scene.ground[joint.point_on(GROUND)]
        record_reaction(out, joint, drv.body, ad[0], ad[1], px, py, sign=-1.0)
    else:
        record_reaction(out, joint, drv.body, r[5], r[6], r[3], r[4], r[1], r[2])
    return out


def with_assembly(structure, ks) -> object:
    """The structure with each dyad's assembly (numbers)."""
    return replace(structure, assembly=tuple(int(k) for k in ks))
