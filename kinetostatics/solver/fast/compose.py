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

import threading
from dataclasses import replace
from functools import cache

import numpy as np

from ...model.scene import GROUND, Scene
from ..blocks import Kept, singular_rows
from ..closure import Param
from ..deadpoints import SCAN_FIRST, SCREEN
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

# Rows per block: each kernel goes over a block of rows before the next one starts, so a
# block's arrays (some 90 rows of a four-bar's) stay in the processor's caches between
# kernels. Measured 2026-11-29 (four-bar, solve + driver table, processor time, the
# machine loaded): 2048 rows 0.58x / 0.74x the hand form at 2e5 / 1e6 positions, 4096
# rows 0.55x / 0.66x, the numpy path's 16 384 rows 0.61x / 0.77x
ROWS = 4096


class Refused(Exception):
    """A kernel wrote a value that is not finite, or met a row the numpy path refuses:
    the sweep is solved on the numpy path, whose message names the rows."""


ONE_SCENE = np.zeros(1, dtype=np.int64)     # each row's scene, for one scene: column 0


class Geometry:
    """What the kernels read of a scene (or a stack) and its structure, each dyad in its
    assembly ``ks``: the driver's geometry, each dyad's with the dyad, each body's load
    resultants and its ``resist`` or ``when = "resisting"`` loads (those of the bodies
    that have some). Nothing here changes as the kernels run (they read it only), so one
    scene's may serve each of its solves
    (:func:`~kinetostatics.solver.fast.solve.solve_compiled`)."""

    def __init__(self, scene: Scene, structure, ks):
        self.driver = driver_geometry(scene)
        self.dyads = [(*dyad_geometry(scene, d, k), d)
                      for d, k in zip(structure.dyads, ks, strict=True)]
        self.loads = {b: body_loads_geometry(scene, b) for b in scene.bodies}
        self.swept = {b: sw for b in scene.bodies
                      if (sw := swept_loads_geometry(scene, b))[2]}


def turn(k, angles: np.ndarray, cs: np.ndarray, sn: np.ndarray) -> None:
    """The compiled path's cos and sin of a crank's ``angles`` into ``cs``, ``sn`` (``k``:
    the kernels, :func:`~kinetostatics.solver.fast.trig_kernels.turn_rows`; the same
    doubles as the kernels that turn the angles themselves), the angles read-only (as a
    driver's: one compiled signature)."""
    if angles.flags.writeable:
        angles = angles.view()
        angles.flags.writeable = False
    k.turn_rows(angles, cs, sn)


class Plan:
    """The kernels and their geometry for one scene (or a stack) and structure, each
    dyad with its assembly ``ks`` (numbers, or arrays over a stack's scenes).

    A stack (``owner`` given: each row's scene, counted from 0) holds each number that
    differs from scene to scene as an array over its scenes
    (:meth:`~kinetostatics.solver.stack.Stacker.table`): the kernels' geometry is a
    column per scene, gathered per tile
    (:func:`~kinetostatics.solver.fast.jitbase.tile_geometry`)."""

    def __init__(self, kernels, scene: Scene, structure, ks, owner: np.ndarray | None = None,
                 geometry: Geometry | None = None):
        self.k = kernels
        self.scene, self.structure = scene, structure
        self.own = ONE_SCENE if owner is None else owner
        drv = scene.driver
        self.crank = drv.kind == "R"
        self.speed, self.accel = float(drv.speed), float(drv.acceleration)
        if geometry is None:
            geometry = Geometry(scene, structure, ks)
        self.driver, self.dyads, self.loads, self.swept = (
            geometry.driver, geometry.dyads, geometry.loads, geometry.swept)
        self.bodies = list(scene.bodies)
        # per load and scene (a stack's: each its own sweep's top), the top and least
        self.stats = fresh_stats(self.swept, 1 if owner is None else int(owner[-1]) + 1)

    def check_swept(self) -> None:
        """Refuse (:class:`Refused`) a sweep whose top speed (power) of a ``resist``
        (``when = "resisting"``) load lifts its still threshold over a row the kernel took
        as moving (:func:`check_stats`)."""
        check_stats(self.swept, self.stats)

    def buffers(self, width: int) -> dict:
        """Arrays for ``width`` rows: each body's motion and load resultants, each dyad's
        data and reactions, the driver's reaction (the ground's motion: constant): rows
        of one slab, its rows padded (:func:`~kinetostatics.solver.fast.layout.padded_width`)."""
        names = (GROUND, *self.bodies)
        nd = len(self.dyads)
        moving = (L.MOTION + 3) * len(names)
        # (np.empty: memory a freed slab leaves is reused without faulting in fresh
        # zeroed pages; only what a kernel may leave unwritten is zeroed: the rows after
        # the bodies', the dyads' and the driver's, in one pass)
        slab = np.empty((moving + (L.DYAD_OUT + L.REACTIONS) * nd + 7,
                         L.padded_width(width)))
        slab[moving:] = 0.0
        a0, d0 = L.MOTION * len(names), moving
        r0 = d0 + L.DYAD_OUT * nd
        out: dict = {
            "m": {b: slab[L.MOTION * i:L.MOTION * (i + 1)] for i, b in enumerate(names)},
            "a": {b: slab[a0 + 3 * i:a0 + 3 * (i + 1)] for i, b in enumerate(names)},
            "d": [slab[d0 + L.DYAD_OUT * i:d0 + L.DYAD_OUT * (i + 1)] for i in range(nd)],
            "r": [slab[r0 + L.REACTIONS * i:r0 + L.REACTIONS * (i + 1)] for i in range(nd)],
            "drv": slab[r0 + L.REACTIONS * nd:], "u": np.zeros(width, dtype=bool)}
        ground = out["m"][GROUND]
        ground[:] = 0.0
        ground[L.C] = 1.0
        return out

    def run(self, x: np.ndarray, lo: int, hi: int, off: int, buf: dict) -> None:
        """Rows ``lo`` to ``hi`` (``x``: the driver's angles in rad, or its positions),
        into ``buf`` at ``i - off``; raises :class:`Refused`."""
        k, m, a, own = self.k, buf["m"], buf["a"], self.own
        dname = self.scene.driver.body
        g, gs = self.driver
        if self.crank:      # (cos and sin in a pass of their own: the compiled path's)
            rows = slice(lo - off, hi - off)
            turn(k, x[lo:hi], m[dname][L.C, rows], m[dname][L.S, rows])
        motion = k.crank_motion if self.crank else k.slider_motion
        bad = motion(x, lo, hi, off, g, gs, own, self.speed, self.accel, m[dname])
        for (g, gs, dyad), d in zip(self.dyads, buf["d"], strict=True):
            (b1, b2), (j1, j2) = dyad.bodies, dyad.outer
            args = (lo, hi, off, g, gs, own, m[j1.other(b1)], m[j2.other(b2)], m[b1], m[b2], d)
            kernel = k.MOTION[dyad.kind]
            if dyad.kind == "RTR":      # the guide's cos and sin, then the rest
                kernel(0, *args)
            bad += kernel(1, *args)
        for b, (g, gs, npoint) in self.loads.items():
            bad += k.body_loads(lo, hi, off, g, gs, own, npoint, m[b], a[b])
        buf["u"][lo - off:hi - off] = False
        for b, (g, gs, floors) in self.swept.items():
            bad += k.swept_loads(lo, hi, off, g, gs, own, len(floors), m[b], a[b], buf["u"],
                                 self.stats[b])
        for (g, gs, dyad), d, r in zip(self.dyads[::-1], buf["d"][::-1],
                                             buf["r"][::-1], strict=True):
            (b1, b2), (j1, j2) = dyad.bodies, dyad.outer
            k1, k2 = j1.other(b1), j2.other(b2)
            bad += k.REACTIONS[dyad.kind](lo, hi, off, g, gs, own, m[b1], m[b2], m[k1], m[k2],
                                          d, a[b1], a[b2], a[k1], a[k2], r)
        g, gs = self.driver
        react = k.crank_reaction if self.crank else k.slider_reaction
        bad += react(lo, hi, off, g, gs, own, m[dname], a[dname], buf["drv"])
        if bad:
            raise Refused(bad)


def fresh_stats(swept: dict, scenes: int) -> dict:
    """Per body of ``swept`` loads, per load and scene the top (0 at first) and least
    (infinite at first) the kernels keep: a ``(loads, scenes, 2)`` array."""
    stats = {}
    for b, (_, _, floors) in swept.items():
        s = stats[b] = np.empty((len(floors), scenes, 2))
        s[..., 0] = 0.0
        s[..., 1] = np.inf
    return stats


def check_stats(swept: dict, stats: dict) -> None:
    """Refuse (:class:`Refused`) a sweep whose top speed (power) of a ``resist`` load
    (``stats``: :func:`fresh_stats`, as the kernels left them) lifts its still threshold
    over a row the kernel took as moving (the numpy path tells those rows from the whole
    sweep)."""
    for b, (_, _, floors) in swept.items():
        for st, floor in zip(stats[b], floors, strict=True):
            if type(floor) is float and st.shape[0] == 1:
                # (one scene's: as Python floats, no numpy calls; the peak as
                # np.maximum's, a NaN kept)
                top, least = st[0].tolist()
                peak = top if top >= floor or top != top else floor
                if not least > RESIST_STILL * peak:
                    raise Refused("swept load")
                continue
            top, least = st[:, 0], st[:, 1]
            if not (least > RESIST_STILL * np.maximum(top, floor)).all():
                raise Refused("swept load")


def driver_input(scene: Scene) -> np.ndarray:
    """What the driver kernel reads per row: a crank's angles (rad), a slider's positions."""
    drv = scene.driver
    return drv.angles if drv.kind == "R" else np.asarray(drv.positions, dtype=float)


def solve_full(plan: Plan, positions: np.ndarray, block: int = ROWS, rows=None) -> Solved:
    """The whole sweep's Solved (every table's arrays), solved block by block into
    arrays over the whole sweep. ``rows``: a stack's (scene, structure) with each
    number over its rows (the plan's hold them per scene), for the Solved."""
    scene, structure = rows or (plan.scene, plan.structure)
    return _solution(plan, scene, structure, positions, solve_arrays(plan, positions, block))


def solve_arrays(plan: Plan, positions: np.ndarray, block: int = ROWS) -> dict:
    """The kernels' arrays over the whole sweep (:meth:`Plan.buffers`, cut to its rows),
    solved block by block."""
    n = positions.size
    x = driver_input(plan.scene)
    buf = plan.buffers(n)
    for lo in range(0, n, block):
        plan.run(x, lo, min(lo + block, n), 0, buf)
    plan.check_swept()
    return _cut(buf, n)


class Unwrapped:
    """A sweep solved in full on the compiled path whose arrays are wrapped in the
    solver's objects (:class:`Kinematics`, the joint reactions) when first read, not
    before (a :class:`~kinetostatics.solver.solved.Deferred`): the driver table reads
    Me/Fe, the undefined-load rows and the dyads' singular rows alone, which it holds
    from the start (measured 2026-11-29, four-bar at 2001 rows: the wrapping 23-45 us of
    a 300-450 us call). The arrays are the kernels', solved once: wrapped later, the
    same numbers."""

    path = "fast"

    def __init__(self, plan: Plan, positions: np.ndarray, buf: dict, dead: tuple):
        drv = plan.scene.driver
        # (Me/Fe copied out, as the Solved's)
        # (the loads let go, None: computed again when asked, as a Solved's)
        self.known = {"scene": plan.scene, "structure": plan.structure, "self_locking": None,
                      "drive": DriverReaction(drv.kind, buf["drv"][0].copy()),
                      "undefined_load": buf["u"], "_loads": None}
        self.positions = positions
        self.plan, self.buf, self.dead = plan, buf, dead
        self.full: dict | None = None
        self.lock = threading.Lock()

    def singular(self) -> np.ndarray:
        """As :attr:`Kinematics.singular`, from each dyad's closeness to a dead centre."""
        flags = [~(d[L.CL2] > SINGULAR_WARN**2) for d in self.buf["d"]]
        return singular_rows(self.positions.size, flags, self.dead)

    def give(self, name: str, have=()) -> dict:
        """The kinematics and joint reactions, wrapped once."""
        with self.lock:
            if self.full is None:
                k = self.known
                sol = _solution(self.plan, k["scene"], k["structure"], self.positions,
                                self.buf, k["drive"])
                kin = sol.kin
                kin.between, kin.ends, kin.unassembled = self.dead
                kin.release()       # as the numpy path's solve: worked out again if asked
                self.full = {"kin": kin, "joint_reactions": sol.joint_reactions}
            return self.full

    def solved(self) -> Solved:
        full, k = self.give("kin"), self.known
        sol = Solved(k["scene"], k["structure"], full["kin"], None, full["joint_reactions"],
                     k["drive"], k["undefined_load"])
        sol.path = "fast"
        return sol

    def __reduce__(self):
        return _as_solved, (self.solved(),)


def _as_solved(solved: Solved) -> Solved:
    return solved


def _cut(buf: dict, n: int) -> dict:
    """The buffers' first ``n`` columns (views: the slab's rows are padded)."""
    return {"m": {k: v[:, :n] for k, v in buf["m"].items()},
            "a": {k: v[:, :n] for k, v in buf["a"].items()},
            "d": [v[:, :n] for v in buf["d"]], "r": [v[:, :n] for v in buf["r"]],
            "drv": buf["drv"][:, :n], "u": buf["u"]}


def solve_lean(plan: Plan, positions: np.ndarray, block: int = ROWS,
               scratch: dict | None = None) -> Kept:
    """A long sweep's :class:`~kinetostatics.solver.blocks.Kept`: Me/Fe and each dyad's
    closeness to a dead centre, the rest of each block in scratch arrays (``scratch``:
    a dict that keeps them for the next sweep of the same scenes' structure: the runs
    of a stack, each fresh array some 3 MB of pages faulted in)."""
    n = positions.size
    x = driver_input(plan.scene)
    width = min(block, n)
    buf = None if scratch is None else scratch.get(width)
    if buf is None:
        buf = plan.buffers(width)
        if scratch is not None:
            scratch[width] = buf
    drive = np.empty(n)
    undefined = np.zeros(n, dtype=bool)
    close = [np.empty(n) for _ in plan.dyads]
    for lo in range(0, n, block):
        hi = min(lo + block, n)
        plan.run(x, lo, hi, lo, buf)
        drive[lo:hi] = buf["drv"][0, :hi - lo]
        undefined[lo:hi] = buf["u"][:hi - lo]
        for c, d in zip(close, buf["d"], strict=True):
            c[lo:hi] = d[L.CL2, :hi - lo]
    plan.check_swept()
    return kept_sweep(plan.structure, plan.scene.driver.kind, drive, undefined, close)


def kept_sweep(structure, kind: str, drive: np.ndarray, undefined: np.ndarray,
               close: list[np.ndarray], measure: bool = False) -> Kept:
    """What a lean sweep keeps (:class:`~kinetostatics.solver.blocks.Kept`): the driver's
    Me/Fe (``kind``: the driver's), the undefined rows, each dyad's closeness to a dead
    centre and its singular rows (closeness within ``SINGULAR_WARN``); with ``measure``
    and two dyads (the six-bars'), their m^2 and its screen too (``Kept.measure2``,
    ``Kept.screened``), with the flags in one compiled pass
    (:func:`~kinetostatics.solver.fast.screen_kernels.flags_and_measure`)."""
    if measure and len(close) == 2:
        flags_and_measure = _screen_kernel()
        n = close[0].size
        singular = [np.empty(n, dtype=bool), np.empty(n, dtype=bool)]
        m2, out = np.empty(n), np.empty(SCAN_FIRST, dtype=np.int64)
        k, below = flags_and_measure(*close, SINGULAR_WARN**2, SCREEN**2, *singular, m2, out)
        # (more intervals than out holds: none told, the screen scans m2 again)
        screened = (out[:k] if k <= out.size else None, bool(below))
        return Kept(structure, DriverReaction(kind, drive), undefined, close, singular, m2,
                    screened)
    # (~(c > SINGULAR_WARN**2) negated in place: one fresh array a dyad, not two)
    singular = [np.logical_not(f, out=f) for f in (c > SINGULAR_WARN**2 for c in close)]
    return Kept(structure, DriverReaction(kind, drive), undefined, close, singular)


@cache
def _screen_kernel():
    """:func:`~kinetostatics.solver.fast.screen_kernels.flags_and_measure`, imported at
    its first use (numba loaded: a lean sweep), then kept: an import statement per call
    cost some 10 us."""
    from .screen_kernels import flags_and_measure
    return flags_and_measure


def _param(scene: Scene, dyad, i: int, known: BodyMotion, m: np.ndarray, d: np.ndarray
           ) -> Param:
    joint, name = dyad.outer[i], dyad.bodies[i]
    b = 10 + 4 * i
    if joint.kind == "R":
        local = scene.bodies[name].local(joint.point_on(name))
        return Param("rot", known, local, d[b], d[b + 1], None, None, None, None)
    return Param("trans", known, c=m[L.C], s=m[L.S], ux=d[b], uy=d[b + 1], bx=d[b + 2],
                 by=d[b + 3])


def _solution(plan: Plan, scene: Scene, structure, positions: np.ndarray, buf: dict,
              drive: DriverReaction | None = None) -> Solved:
    """The Solved of ``scene`` and ``structure`` over the rows of ``buf`` (arrays over
    the whole sweep), every array a view of the kernels' output."""
    n = positions.size
    m = buf["m"]
    drv = scene.driver
    bodies = {GROUND: ground_motion(), drv.body: BodyMotion(drv.angles if drv.kind == "R"
                                                            else None, *m[drv.body])}
    dyads = []
    for i_d, ((g, gs, dyad), d) in enumerate(zip(plan.dyads, buf["d"], strict=True)):
        for b in dyad.bodies:
            bodies[b] = BodyMotion(None, *m[b])
        pr = tuple(_param(scene, dyad, i, bodies[dyad.outer[i].other(dyad.bodies[i])],
                          m[dyad.bodies[i]], d) for i in range(2))
        inner = dyad.inner
        q = (tuple(g[L.Q1X:L.Q1Y + 1, 0]), tuple(g[L.Q2X:L.Q2Y + 1, 0])) if not gs else None
        if inner.kind == "R" and q is None:
            q = tuple(scene.bodies[b].local(inner.point_on(b)) for b in dyad.bodies)
        k = int(g[L.ASSEMBLY, 0]) if not gs else structure.assembly[i_d]
        dyads.append(DyadMotion(
            dyad, pr, k, d[L.XX], d[L.XY], (d[L.C1X], d[L.C1Y]), (d[L.C2X], d[L.C2Y]),
            d[L.DET], n, singular=~(d[L.CL2] > SINGULAR_WARN**2), closeness2=d[L.CL2],
            inner_local=q if inner.kind == "R" else None,
            slider_first=inner.kind == "T" and inner.slider == dyad.bodies[0],
            nx=d[L.NX] if inner.kind == "T" else None,
            ny=d[L.NY] if inner.kind == "T" else None))
    kin = Kinematics(scene, structure, positions, bodies, dyads)
    reactions = _reactions(plan, scene, buf)
    if drive is None:
        # (Me/Fe copied out: a stacked run's scenes keep it, not the slab it lies in)
        drive = DriverReaction(drv.kind, buf["drv"][0].copy())
    sol = Solved(scene, structure, kin, None, reactions, drive, buf["u"])
    sol.path = "fast"
    return sol


def _reactions(plan: Plan, scene: Scene, buf: dict) -> dict:
    """The joint reactions in the numpy path's order (dyads last to first, each its inner
    joint then its outer ones; the driver's joint last)."""
    a = buf["a"]
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


# the block's views and its joint reactions, for the sweep solved again block by block
# (:class:`~kinetostatics.solver.fast.solve.SolvedAgain`, the one-pass tables)
cut_rows, block_reactions = _cut, _reactions
