"""Many scenes of one structure as one: their rows stacked along the position axis.

Scenes that share a structure (the same bodies, points, joints, driver, loads and
gravity; only the numbers of the points, the ground, the masses and the inertias
differ) are solved as one scene over all their rows: each such number becomes an
array over the rows (a number all the scenes share stays a number). Every elementwise
operation of the solver then does, row by row, exactly what it does for each scene
alone, so the numbers are the same. Used by :func:`kinetostatics.solve_many`.

What the solver decides once per scene is decided here per scene, vectorised: the
assembly of every dyad at the scene's first row (from its ``[near]`` hints, as
:func:`~kinetostatics.solver.kinematics.choose_assembly`). The dead points between rows
are screened for every scene at once by
:func:`~kinetostatics.solver.deadpoints.dead_points_stacked` (each scene's rows a
segment, searched alone along increasing position, the probes of all in one solve).
"""

from __future__ import annotations

import struct
from dataclasses import replace
from functools import cached_property
from itertools import chain
from operator import attrgetter, itemgetter

import numpy as np

from ..model.scene import GROUND, Body, Scene
from .assembly import hint_points
from .closure import DyadSolver, body_origin, dyad_param
from .driver import driver_motion, ground_motion
from .kinematics import SINGULAR_FAIL, solve_dyad
from .structure import Structure
from .trap import tame, tame_values


class Rows(np.ndarray):
    """A mass or an inertia over the rows of a stack. Its truth value is that of every
    row: a stack holds only scenes for which each test the solver makes on them
    (``mass == 0``, ``mass > 0``) comes out alike (:func:`signature`). The lengths are
    plain arrays (an ndarray subclass costs time in every operation it enters)."""

    def __bool__(self) -> bool:
        return bool(self.view(np.ndarray).all())


_mass, _inertia, _cog, _points = (attrgetter(f) for f in ("mass", "inertia", "cog", "points"))
_size = attrgetter("size")


def _col(v: np.ndarray, first):
    """One parameter over the scenes (``v``, as floats): ``first`` (the first scene's
    number itself) when every scene has the same bits, else the array."""
    bits = v.view(np.int64)
    if (bits == bits[0]).all():
        return first
    return v


def _pair(pairs, m: int, first: tuple) -> tuple:
    """A point's (x, y) over the ``m`` scenes, from an iterable of their pairs (as
    :func:`_col`, each coordinate)."""
    xy = np.fromiter(chain.from_iterable(pairs), float, 2 * m).reshape(m, 2)
    return (_col(np.ascontiguousarray(xy[:, 0]), first[0]),
            _col(np.ascontiguousarray(xy[:, 1]), first[1]))


def signature(scene: Scene):
    """What scenes must share to be stacked (structure, joints, driver, loads, gravity,
    hints' names, the tests on the masses), or None for a scene solved alone: joint
    friction (solved per scene by iteration) or a mass model. (A ``resist`` load or one
    acting ``when = "resisting"`` takes its threshold from each scene's own rows: the
    run's ``segments``, :meth:`Stacker.runs`.)

    The numbers the stack takes from its first scene (line angles, forces, resist
    forces, moments, the driver's speed and acceleration, gravity) are compared by their
    bits (packed: a -0.0 is not a 0.0, whose products could differ in sign), in one pass
    per part."""
    nums: list = []
    joints = []
    for j in scene.joints.values():
        if j.friction is not None:
            return None
        joints.append((j.name, j.kind, j.bodies, j.points))
        nums.append(j.beta)
    bodies = []
    for b in scene.bodies.values():
        if b.mass_model is not None:
            return None
        m = b.mass
        bodies.append((b.name, tuple(b.points), b.cog is None, m == 0.0, m > 0.0,
                       b.inertia == 0.0))
    loads = []
    for ld in scene.loads:
        f = ld.force
        loads.append((ld.body, ld.point, f is None, ld.resist is None, ld.when))
        if f is not None:
            nums += (f[0], f[1])
        if ld.resist is not None:
            nums.append(ld.resist)
        nums.append(ld.moment)
    drv = scene.driver
    g = scene.gravity
    nums += (drv.speed, drv.acceleration, g[0], g[1])
    return (drv.body, drv.joint, drv.kind, tuple(bodies), tuple(scene.ground), tuple(joints),
            tuple(loads), tuple(scene.near), struct.pack(f"{len(nums)}d", *nums))


class Stacker:
    """Builds stacked scenes of a list of scenes of one :func:`signature`."""

    def __init__(self, scenes: list[Scene]):
        self.scenes = scenes
        s0 = scenes[0]
        self.base = s0
        m = len(scenes)
        # each parameter read for all the scenes by C-level iteration (map, fromiter):
        # a few times quicker than a list comprehension per coordinate
        grounds = [s.ground for s in scenes]
        self.ground = {p: _pair(map(itemgetter(p), grounds), m, v)
                       for p, v in s0.ground.items()}
        self.bodies = {}
        for name, b in s0.bodies.items():
            bs = list(map(itemgetter(name), [s.bodies for s in scenes]))
            cog = None if b.cog is None else _pair(map(_cog, bs), m, b.cog)
            points = list(map(_points, bs))
            pts = {p: _pair(map(itemgetter(p), points), m, v) for p, v in b.points.items()}
            self.bodies[name] = (_col(np.fromiter(map(_mass, bs), float, m), b.mass),
                                 _col(np.fromiter(map(_inertia, bs), float, m), b.inertia),
                                 cog, pts)
        nears = [s.near for s in scenes]
        self.near = {k: _pair(map(itemgetter(k), nears), m, v) for k, v in s0.near.items()}
        self.size = _col(np.fromiter(map(_size, scenes), float, m), s0.size)

    @classmethod
    def of_columns(cls, base: Scene, m: int, ground: dict, bodies: dict, size) -> Stacker:
        """The stacker of ``m`` variants of ``base`` given by their numbers, without a
        Scene per variant: ``ground`` {point: (x, y)}, ``bodies`` {name: (mass, inertia,
        cog, {point: (x, y)})} and ``size`` (:attr:`Scene.size`) as :meth:`__init__` sets
        them (each number the variants share a number, else an array over them). Every
        variant shares ``base``'s driver, sweep, hints and all else (``scenes`` holds
        ``base`` ``m`` times)."""
        self = cls.__new__(cls)
        self.scenes = [base] * m
        self.base = base
        self.ground = ground
        self.bodies = bodies
        self.near = dict(base.near)
        self.size = size
        return self

    def tame(self) -> bool:
        """Whether every scene of the stack is :func:`~kinetostatics.solver.trap.tame`
        (the numbers they share are the first scene's; the others told per array; the
        driver positions by the caller, as stacked)."""
        if not tame(self.base):
            return False
        nums: list = [*chain.from_iterable(self.ground.values()),
                      *chain.from_iterable(self.near.values())]
        for m, inertia, cog, pts in self.bodies.values():
            nums += (m, inertia, *(cog or ()), *chain.from_iterable(pts.values()))
        return tame_values([x for x in nums if isinstance(x, np.ndarray)])

    def scene(self, owner: np.ndarray, positions: np.ndarray) -> Scene:
        """The stacked scene: row i is scene ``owner[i]`` at driver position
        ``positions[i]``."""
        return self._build(lambda x: x[owner], positions)

    def runs(self, lo: int, hi: int, counts: np.ndarray, positions: np.ndarray) -> Scene:
        """The stacked scene of scenes ``lo`` to ``hi - 1`` one after another, scene
        ``lo + j`` over ``counts[j]`` rows at driver positions ``positions`` (the same
        scene as :meth:`scene` with ``owner = np.repeat(np.arange(lo, hi), counts)``:
        each scene's numbers repeated, a few times quicker than taken row by row)."""
        sc = self._build(lambda x: np.repeat(x[lo:hi], counts), positions)
        sc.__dict__["segments"] = counts    # each scene's rows (a sweep's maxima per scene)
        if sc.driver.kind == "R":
            sc.__dict__["driver_trig"] = self.trig_rows(lo, hi, positions)
        return sc

    def table(self, lo: int, hi: int, counts: np.ndarray, positions: np.ndarray,
              trig: bool = True) -> Scene:
        """The run of :meth:`runs` with each number that differs from scene to scene an
        array over the scenes ``lo`` to ``hi - 1`` (not over their rows): what the
        compiled path's kernels read, a column per scene, with each row's scene
        (:func:`~kinetostatics.solver.fast.stacked.solve_run_stacked`). Its driver and
        its rows are the run's (``trig``: their cos and sin too, ``driver_trig``)."""
        sc = self._build(lambda x: x[lo:hi], positions)
        sc.__dict__["segments"] = counts
        if sc.driver.kind == "R" and trig:
            sc.__dict__["driver_trig"] = self.trig_rows(lo, hi, positions)
        return sc

    def sweeps(self, lo: int, hi: int, counts: np.ndarray, positions: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """A crank's cos and sin for the run of scenes ``lo`` to ``hi - 1`` (at
        ``positions``, ``counts`` rows each), and where each scene's rows begin in them:
        the first scene's sweep once, each scene's rows from 0, when every scene sweeps
        as the first, bit for bit (the usual case: no copy per row); else over the run's
        rows (:meth:`trig_rows`), each scene from its first row in the run. Row ``i`` of
        scene ``e`` (starting at run row ``s``) has cos ``c[i - start[e]]`` with
        ``start[e]`` = ``s`` or 0."""
        p0 = self.base.driver.positions
        if p0.size and positions.size == p0.size * (hi - lo):
            bits = positions.view(np.int64).reshape(hi - lo, p0.size)
            if (bits == p0.view(np.int64)).all():
                return (*self._trig0[1:], np.cumsum(counts) - counts)
        return (*self.trig_rows(lo, hi, positions)[1:], np.zeros(hi - lo, dtype=np.int64))

    def trig_rows(self, lo: int, hi: int, positions: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """A crank's angles, their cos and sin over the run of scenes ``lo`` to
        ``hi - 1`` (at ``positions``), worked out once per distinct sweep (variants of
        one mechanism mostly share theirs: a run whose scenes all sweep as the first
        scene, bit for bit, is told in one comparison) and laid one after another: the
        same numbers, elementwise, as over the run's rows
        (:func:`~kinetostatics.solver.driver.driver_motion`)."""
        p0 = self.base.driver.positions
        n = p0.size
        if n and positions.size == n * (hi - lo):       # each scene at the first's sweep?
            bits = positions.view(np.int64).reshape(hi - lo, n)
            if (bits == p0.view(np.int64)).all():
                return tuple(np.tile(x, hi - lo) for x in self._trig0)
        done: dict[bytes, tuple] = {}
        parts = []
        for sc in self.scenes[lo:hi]:
            pos = sc.driver.positions
            key = pos.tobytes()
            hit = done.get(key)
            if hit is None:
                th = sc.driver.angles
                hit = done[key] = (th, np.cos(th), np.sin(th))
            parts.append(hit)
        return tuple(np.concatenate(x) for x in zip(*parts, strict=True))

    @cached_property
    def _trig0(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The first scene's crank angles, their cos and sin."""
        th = self.base.driver.angles
        return th, np.cos(th), np.sin(th)

    def _build(self, expand, positions: np.ndarray) -> Scene:
        """The stacked scene whose per-scene arrays x become ``expand(x)`` over the rows
        (numbers all the scenes share stay numbers)."""
        def at(x):
            return expand(x) if isinstance(x, np.ndarray) else x

        def tested(x):      # a mass or inertia: the solver tests its value (Rows)
            return expand(x).view(Rows) if isinstance(x, np.ndarray) else x

        def pair(p):
            return (at(p[0]), at(p[1]))
        bodies = {}
        for name, (m, inertia, cog, pts) in self.bodies.items():
            b0 = self.base.bodies[name]
            bodies[name] = Body(name, tested(m), tested(inertia),
                                None if cog is None else pair(cog),
                                {p: pair(v) for p, v in pts.items()}, b0.mass_model)
        sc = replace(self.base, ground={p: pair(v) for p, v in self.ground.items()},
                     bodies=bodies, near={k: pair(v) for k, v in self.near.items()},
                     driver=replace(self.base.driver, positions=positions), raw={})
        sc.__dict__["size"] = at(self.size)       # the cached property, per row
        return sc


def assemblies(stacker: Stacker, structure: Structure) -> tuple[np.ndarray, np.ndarray]:
    """Each scene's assembly k = +-1 per dyad (an array (dyads, scenes)), chosen at its
    first row as :func:`~kinetostatics.solver.kinematics.choose_assembly` does, and which
    scenes it settles: a scene that cannot close at its first row, or whose hints do not
    settle an assembly, is left to be solved (and refused) alone."""
    m = len(stacker.scenes)
    owner = np.arange(m)
    first = stacker.scene(owner, np.array([s.driver.positions[0] for s in stacker.scenes]))
    size = np.broadcast_to(np.asarray(first.size, dtype=float), (m,))
    motions = {GROUND: ground_motion(), first.driver.body: driver_motion(first)}
    ok = np.ones(m, dtype=bool)
    ks = np.ones((len(structure.dyads), m), dtype=int)
    with np.errstate(all="ignore"):
        for d, dyad in enumerate(structure.dyads):
            solver = DyadSolver(first, dyad)
            if solver.branches == 2:
                ks[d] = _branch(first, dyad, solver, motions, size, ok)
            dm = solve_dyad(first, dyad, motions, ks[d] if solver.branches == 2 else 1,
                            strict=False)
            ok &= np.broadcast_to(dm.closeness2, (m,)) > SINGULAR_FAIL**2
    return ks, ok


def _branch(first: Scene, dyad, solver: DyadSolver, motions, size, ok) -> np.ndarray:
    """The assembly whose hinted points lie closest, per scene (``ok`` cleared where the
    first row cannot close or no hint settles it)."""
    pr = (dyad_param(first, dyad, 0, motions), dyad_param(first, dyad, 1, motions))
    cands = {}
    for k in (1, -1):
        cs, ss, gap = solver.positions(pr, k)
        if k == 1 and solver.reach is not None:     # (the pivots' distance: either k)
            ok &= np.broadcast_to(solver.reach / first.size, ok.shape) > SINGULAR_FAIL
        if gap is not None:
            ok &= ~(np.broadcast_to(gap, ok.shape) > 1e-9 * size)
        cands[k] = (cs, [body_origin(pr[i], cs[i], ss[i]) for i in range(2)])

    def where(k, b, loc):
        i = dyad.bodies.index(b)
        (c, s), (ox, oy) = cands[k][0][i], cands[k][1][i]
        return (np.broadcast_to(ox + c * loc[0] - s * loc[1], ok.shape),
                np.broadcast_to(oy + s * loc[0] + c * loc[1], ok.shape))
    hints = hint_points(first, dyad)
    if not hints:
        ok[:] = False
        return np.ones(ok.shape, dtype=int)
    dist = {}
    for k in (1, -1):
        total = 0
        for _, b, loc, t in hints:
            x, y = where(k, b, loc)
            total = total + ((x - t[0]) ** 2 + (y - t[1]) ** 2)
        dist[k] = total
    ok &= np.abs(dist[1] - dist[-1]) > 1e-12 * size ** 2
    return np.where(dist[1] < dist[-1], 1, -1)


def plain(x):
    """A stacked value as the solver gives it for one scene: an array as a plain array."""
    return np.asarray(x) if isinstance(x, np.ndarray) else x

