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
from dataclasses import fields, replace
from functools import cached_property
from itertools import chain, count
from typing import Any

import numpy as np

from ..model.scene import GROUND, Body, Driver, Scene
from .assembly import hint_points
from .blocks import keep_heap
from .closure import DyadSolver, body_origin, dyad_param
from .driver import driver_motion, ground_motion
from .kinematics import SINGULAR_FAIL
from .memo import Kept, interned
from .probes import probe_dyad
from .structure import Structure
from .trap import tame, tame_values


class Rows(np.ndarray):
    """A mass or an inertia over the rows of a stack. Its truth value is that of every
    row: a stack holds only scenes for which each test the solver makes on them
    (``mass == 0``, ``mass > 0``) comes out alike (:func:`signature`), so such a test,
    against the number 0, is told on the first row (a bool, without a pass over the
    rows). Arithmetic on it gives plain arrays, as the lengths are (an ndarray subclass
    costs time in every operation it enters)."""

    def __bool__(self) -> bool:
        return bool(self.view(np.ndarray).all())

    def __eq__(self, other):
        if _nil(other):
            return bool(self.view(np.ndarray)[0] == 0)
        return np.equal(self, other).view(Rows)

    def __gt__(self, other):
        if _nil(other):
            return bool(self.view(np.ndarray)[0] > 0)
        return np.greater(self, other).view(Rows)

    __hash__ = None

    def __array_wrap__(self, array, context=None, return_scalar=False):
        return array[()] if return_scalar else array.view(np.ndarray)


def _nil(x) -> bool:
    """A Python number equal to 0 (the tests the stack's signature holds alike)."""
    return type(x) in (float, int) and x == 0


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
    return _read(scene)[0]


def _numbers(scene: Scene) -> list:
    """The numbers a stack takes per scene (:class:`Stacker`), in its order: each ground
    point's x and y, each body's mass, inertia, cog and points, each hint, the size."""
    return _read(scene)[1]


def _read(scene: Scene) -> tuple[tuple | None, list]:
    """:func:`signature` and :func:`_numbers` of a scene, read in one pass over its
    parts (a scene just read is touched once: measured 2026-11-29, 1000 new four-bars,
    processor time, best of 9: 11.7-12.4 ms read apart, 10.9-12.5 ms together; most of
    it is the first touch of each new scene's objects, about 50 of them, which neither
    way avoids; a flat signature tuple instead of nested ones was no quicker)."""
    out: list = []
    put, add = out.extend, out.append
    for xy in scene.ground.values():
        put(xy)
    nums: list = []
    alone = False
    bodies = []
    for b in scene.bodies.values():
        m, inertia, cog, pts = b.mass, b.inertia, b.cog, b.points
        add(m)
        add(inertia)
        if cog is not None:
            put(cog)
        for xy in pts.values():
            put(xy)
        alone = alone or b.mass_model is not None
        bodies.append((b.name, tuple(pts), cog is None, m == 0.0, m > 0.0, inertia == 0.0))
    for xy in scene.near.values():
        put(xy)
    add(scene.size)
    joints = []
    for j in scene.joints.values():
        alone = alone or j.friction is not None
        joints.append((j.name, j.kind, j.bodies, j.points))
        nums.append(j.beta)
    if alone:
        return None, out
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
            tuple(loads), tuple(scene.near), struct.pack(f"{len(nums)}d", *nums)), out


# each scene's record (stack_record) while it lives, for the last RECORDS scenes read:
# solve_many over the same scenes again (a study that changes its loads, a benchmark)
# tells their structure and gathers their numbers once
RECORDS = 1 << 16
# the compiled path's cos and sin of a crank's angles, ``turn(angles) -> (cos, sin)``,
# which its kernels read from :meth:`Stacker.sweeps`: put here by that path's loader
# when the kernels load (this module cannot import them)
SWEEP_TURN: list = []
_RECORDS = Kept(RECORDS)
_LABELS: dict[Any, int] = {}        # signature -> a label of its own (an int, quick to hash)


def stack_record(scene: Scene) -> tuple[int | None, bytes, bool, int, tuple | None, list]:
    """What :func:`kinetostatics.solve_many` needs of a scene to stack it, worked out once
    per scene object (kept while it lives; a Scene is frozen): a label of its
    :func:`signature` (scenes of equal signatures get the same label; None for a scene
    solved alone, or without positions), its numbers (:func:`_numbers`) packed as
    float64 bytes, whether its driver positions strictly increase (then none
    repeats: :func:`~kinetostatics.solver.continuity.check_distinct` has nothing to
    refuse), its number of positions, its sweep's key
    (:attr:`~kinetostatics.model.scene_types.Driver.sweep`) and a cell (a list of one
    item, None at first) where :func:`kinetostatics.solve_many` keeps the scene's
    assemblies once chosen (``many.kept_assemblies``: read with its other fields, in the
    same pass over the scenes)."""
    hit = _RECORDS.get(scene)
    if hit is not None:
        return hit
    sig, nums = _read(scene)
    drv = scene.driver
    if not drv.positions.size:
        sig = None
    label = None
    if sig is not None:
        label = _LABELS.get(sig)
        if label is None:
            if len(_LABELS) >= RECORDS:
                _LABELS.clear()     # (a new label for a signature met again: no harm)
            label = _LABELS[sig] = next(_LABEL)
    rec = (label, struct.pack(f"{len(nums)}d", *nums), _increases(drv), drv.positions.size,
           None if drv.sweep is None else interned(_SWEEPS, drv.sweep), [None])
    _RECORDS.put(scene, rec)
    return rec


def stack_records(scenes: list[Scene]) -> list[tuple]:
    """:func:`stack_record` of each scene, the records kept looked up in one loop
    (measured 2026-11-29, 1000 four-bars read before: 0.65 ms a call one call each)."""
    get = _RECORDS.entries.get
    out = []
    for sc in scenes:
        hit = get(id(sc))
        out.append(hit[1] if hit is not None and hit[0]() is sc else stack_record(sc))
    return out


def _increases(driver) -> bool:
    """Whether ``driver``'s positions strictly increase: told once per sweep read from
    start, stop and count (:attr:`~kinetostatics.model.scene.Driver.sweep`: the same
    bits for the same key), else from its positions."""
    key = driver.sweep
    up = _UP.get(key) if key is not None else None
    if up is None:
        p = driver.positions
        up = bool((p[1:] > p[:-1]).all())
        if key is not None:
            if len(_UP) >= 64:
                _UP.clear()
            _UP[key] = up
    return up


_UP: dict[tuple, bool] = {}


_SWEEPS: dict[tuple, tuple] = {}    # (one sweep key object for equal ones: interned)
_LABEL = count(1)       # (a label is never given twice, the table cleared or not)


class Stacker:
    """Builds stacked scenes of a list of scenes of one :func:`signature`.

    Every scene's numbers (:func:`_numbers`, packed by :func:`stack_record`) are read
    into one array in one pass. A run (:meth:`runs`) repeats them over its rows in one
    call. (The probes' rows, :meth:`scene`, are gathered number by number: as one table
    they were no quicker, measured 2026-11-29, the shaper's 5-10 % slower, its probes'
    table of some 50 numbers x 81 000 rows a fresh 32 MB array each round.)"""

    def __init__(self, scenes: list[Scene], numbers: list[bytes] | None = None,
                 one_sweep: bool | None = None):
        """``numbers``: each scene's packed numbers (:func:`stack_record`), when known;
        ``one_sweep``: whether every scene sweeps as the first, when known
        (:meth:`_same_sweep`)."""
        self.scenes = scenes
        self.one_sweep = one_sweep
        s0 = scenes[0]
        self.base = s0
        m = len(scenes)
        if numbers is None:
            numbers = [stack_record(s)[1] for s in scenes]
        # every scene's numbers in one array (a row per scene, a column per number,
        # read from the packed bytes in one pass); a column whose bits all the scenes
        # share is the first scene's number itself, the others arrays over the scenes
        table = np.frombuffer(b"".join(numbers), dtype=np.float64).reshape(m, -1)
        bits = table.view(np.int64)
        varies = (bits != bits[0]).any(axis=0).tolist()
        which = [c for c, v in enumerate(varies) if v]
        # (the numbers that vary, each contiguous: a row of one table, which a run
        # repeats over its rows in one call, runs)
        self._varying = table[:, which].T.copy()
        self._varying.flags.writeable = False     # (handed out as they are: scene(None))
        rows = list(self._varying)
        self._row_of = {id(r): i for i, r in enumerate(rows)}
        rows = iter(rows)
        take = iter([next(rows) if v else x for v, x in zip(varies, _numbers(s0), strict=True)]
                    ).__next__

        def pair():
            return (take(), take())
        self.ground = {p: pair() for p in s0.ground}
        self.bodies = {}
        for name, b in s0.bodies.items():
            mass, inertia = take(), take()
            cog = None if b.cog is None else pair()
            self.bodies[name] = (mass, inertia, cog, {p: pair() for p in b.points})
        self.near = {k: pair() for k in s0.near}
        self.size = take()
        self._gathered: tuple | None = None       # (scene(): the last owner's numbers)
        self._tiles: dict[int, tuple] = {}       # (trig_rows: a shared sweep per count)
        # what the solve of the stack works out once and reads twice (the compiled
        # path's geometry: its fused kernel's and the dead-point screen's bound)
        self.kept: dict[str, tuple] = {}

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
        self._gathered = None
        self._tiles = {}
        self.kept = {}
        self._varying, self._row_of = None, {}
        self.one_sweep = True
        return self

    def tame(self) -> bool:
        """Whether every scene of the stack is :func:`~kinetostatics.solver.trap.tame`
        (the numbers they share are the first scene's; the others told per array; the
        driver positions by the caller, as stacked)."""
        if not tame(self.base):
            return False
        if self._varying is not None:   # (every number that varies: a row of one table)
            table = self._varying
            if isinstance(self.size, np.ndarray):       # (not one of the scene's numbers)
                table = np.delete(table, self._row_of[id(self.size)], axis=0)
            return tame_values([table])     # (in one pass: 15 arrays took 0.09 ms)
        nums: list = [*chain.from_iterable(self.ground.values()),
                      *chain.from_iterable(self.near.values())]
        for m, inertia, cog, pts in self.bodies.values():
            nums += (m, inertia, *(cog or ()), *chain.from_iterable(pts.values()))
        return tame_values([x for x in nums if isinstance(x, np.ndarray)])

    def scene(self, owner: np.ndarray, positions: np.ndarray) -> Scene:
        """The stacked scene: row i is scene ``owner[i]`` (scene i if ``owner`` is None:
        each number as it is) at driver position ``positions[i]``. Each number gathered
        for ``owner`` is kept for the next call with the same ``owner`` object (the
        dead-point probes' rounds: the same rows' scenes at other positions; measured
        2026-11-29, 1000 four-bars: 0.6 ms a call of solve_many in three gathers of some
        25 numbers over 5890 rows), and so is the scene made of them: the next call
        moves its driver alone (:func:`moved`; 0.5 ms of 2.3 in the probes' three
        rounds, each building the scene's bodies and points anew)."""
        if owner is None:           # (row i is scene i: each number as it is)
            return self._build(lambda x: x, positions)
        kept = self._gathered
        if kept is None or kept[0] is not owner:
            kept = self._gathered = (owner, {}, [])
        elif kept[2]:
            return moved(kept[2][0], positions)
        got = kept[1]

        def gather(x: np.ndarray) -> np.ndarray:
            y = got.get(id(x))      # (x: one of this stacker's arrays, alive with it)
            if y is None:
                y = got[id(x)] = x[owner]
            return y
        sc = self._build(gather, positions)
        kept[2].append(sc)
        return sc

    def runs(self, lo: int, hi: int, counts: np.ndarray, positions: np.ndarray) -> Scene:
        """The stacked scene of scenes ``lo`` to ``hi - 1`` one after another, scene
        ``lo + j`` over ``counts[j]`` rows at driver positions ``positions`` (the same
        scene as :meth:`scene` with ``owner = np.repeat(np.arange(lo, hi), counts)``:
        each scene's numbers repeated, a few times quicker than taken row by row)."""
        keep_heap()         # (the runs' arrays reuse the heap's pages, not fresh ones)
        # every number that varies repeated in one call (a row each of one block; 15
        # numbers of 34 four-bars: 29 us against 37 us and 15 calls one by one)
        block = (self._varying[:, lo:hi].repeat(counts, axis=1)
                 if self._varying is not None else None)
        row_of = self._row_of

        def expand(x: np.ndarray) -> np.ndarray:
            i = row_of.get(id(x))       # (x: one of this stacker's rows, alive with it)
            return block[i] if i is not None else x[lo:hi].repeat(counts)
        trig = self.trig_rows(lo, hi, positions) if self.base.driver.kind == "R" else None
        sc = self._build(expand, positions, None if trig is None else trig[0])
        sc.__dict__["segments"] = counts    # each scene's rows (a sweep's maxima per scene)
        if trig is not None:
            sc.__dict__["driver_trig"] = trig
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
        ``positions``, ``counts`` rows each), the compiled path's (:data:`SWEEP_TURN`:
        its kernels read them), and where each scene's rows begin in them: the first
        scene's sweep once, each scene's rows from 0, when every scene sweeps as the
        first, bit for bit (the usual case: no copy per row); else over the run's rows
        (the angles of :meth:`trig_rows`), each scene from its first row in the run. Row
        ``i`` of scene ``e`` (starting at run row ``s``) has cos ``c[i - start[e]]`` with
        ``start[e]`` = ``s`` or 0."""
        p0 = self.base.driver.positions
        if p0.size and positions.size == p0.size * (hi - lo):
            if self._same_sweep(lo, hi) or (positions.view(np.int64).reshape(hi - lo, p0.size)
                                            == p0.view(np.int64)).all():
                return (*self._turned0, np.cumsum(counts) - counts)
        turn = SWEEP_TURN[0]
        return (*turn(self.trig_rows(lo, hi, positions)[0]), np.zeros(hi - lo, dtype=np.int64))

    def _same_sweep(self, lo: int, hi: int) -> bool:
        """Whether scenes ``lo`` to ``hi - 1`` sweep as the first, read from the same
        start, stop and count (:attr:`~kinetostatics.model.scene_types.Driver.sweep`:
        the same bits, told without a pass over their rows)."""
        key = self.base.driver.sweep
        if key is None:
            return False
        if self.one_sweep is None:      # (told for the whole stack once)
            self.one_sweep = all([s.driver.sweep == key for s in self.scenes])
        return self.one_sweep or all([s.driver.sweep == key for s in self.scenes[lo:hi]])

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
            if self._same_sweep(lo, hi) or (positions.view(np.int64).reshape(hi - lo, n)
                                            == p0.view(np.int64)).all():
                return self._tiled(hi - lo)
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

    def _tiled(self, m: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The first scene's angles, cos and sin laid ``m`` times one after another,
        read-only (as :meth:`~kinetostatics.model.scene_types.Driver.trig`'s), made once
        per count for the runs of this stack (most runs hold as many scenes: measured
        2026-11-29, the numpy path's 1000 four-bars x 361 in 30 runs, 3 ms a call tiling
        them run by run)."""
        got = self._tiles.get(m)
        if got is None:
            got = tuple(np.tile(x, m) for x in self._trig0)
            for x in got:
                x.flags.writeable = False
            self._tiles[m] = got
        return got

    @cached_property
    def _turned0(self) -> tuple[np.ndarray, np.ndarray]:
        """The first scene's crank angles' cos and sin, the compiled path's
        (:meth:`sweeps`)."""
        return SWEEP_TURN[0](self.base.driver.angles)

    @cached_property
    def _trig0(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The first scene's crank angles, their cos and sin."""
        th = self.base.driver.angles
        return th, np.cos(th), np.sin(th)

    def _build(self, expand, positions: np.ndarray, angles: np.ndarray | None = None
               ) -> Scene:
        """The stacked scene whose per-scene arrays x become ``expand(x)`` over the rows
        (numbers all the scenes share stay numbers). ``angles``: the crank's angles at
        ``positions``, when known (the run's, :meth:`trig_rows`: the same doubles as its
        Driver makes them).

        The scene, its driver and bodies are the dataclasses' own fields set as their
        constructors set them (``replace`` of the base scene and driver: the same
        objects), without the constructors' calls (measured 2026-11-29, the numpy path's
        1000 four-bars x 361: 30 runs of about 70 us each, mostly constructors)."""
        def at(x):
            return expand(x) if isinstance(x, np.ndarray) else x

        def tested(x):      # a mass or inertia: the solver tests its value (Rows)
            return expand(x).view(Rows) if isinstance(x, np.ndarray) else x

        def pair(p):
            return (at(p[0]), at(p[1]))
        base, made = self.base, object.__new__
        bodies = {}
        for name, (m, inertia, cog, pts) in self.bodies.items():
            b = bodies[name] = made(Body)
            b.__dict__.update(name=name, mass=tested(m), inertia=tested(inertia),
                              cog=None if cog is None else pair(cog),
                              points={p: pair(v) for p, v in pts.items()},
                              mass_model=base.bodies[name].mass_model)
        if angles is None:
            driver = replace(base.driver, positions=positions)
        else:
            driver = made(Driver)
            driver.__dict__.update(self._driver_fields, positions=positions, angles=angles)
        sc = made(Scene)
        sc.__dict__.update(self._scene_fields, ground={p: pair(v) for p, v in self.ground.items()},
                           bodies=bodies, near={k: pair(v) for k, v in self.near.items()},
                           driver=driver, raw={})
        sc.__dict__["size"] = at(self.size)       # the cached property, per row
        return sc

    @cached_property
    def _scene_fields(self) -> dict:
        """The base scene's fields as ``replace`` passes them on (its cached values and
        the solver's records left out)."""
        return {f.name: getattr(self.base, f.name) for f in fields(Scene)}

    @cached_property
    def _driver_fields(self) -> dict:
        """The base driver's fields as ``replace`` passes them on, ``sweep`` as its
        constructor sets it (None: positions replaced)."""
        d = self.base.driver
        return {**{f.name: getattr(d, f.name) for f in fields(Driver) if f.init},
                "sweep": None}


def moved(scene: Scene, positions: np.ndarray) -> Scene:
    """A stacked scene (:meth:`Stacker.scene`) with its driver at other ``positions``:
    the same numbers and size (each row's own)."""
    out = replace(scene, driver=replace(scene.driver, positions=positions))
    out.__dict__["size"] = scene.__dict__["size"]
    return out


def assemblies(stacker: Stacker, structure: Structure, firsts: np.ndarray | None = None
               ) -> tuple[np.ndarray, np.ndarray]:
    """Each scene's assembly k = +-1 per dyad (an array (dyads, scenes)), chosen at its
    first row as :func:`~kinetostatics.solver.kinematics.choose_assembly` does, and which
    scenes it settles: a scene that cannot close at its first row, or whose hints do not
    settle an assembly, is left to be solved (and refused) alone. ``firsts``: each
    scene's first driver position, when known."""
    m = len(stacker.scenes)
    if firsts is None:
        firsts = np.array([s.driver.positions[0] for s in stacker.scenes])
    first = stacker.scene(None, firsts)
    size = np.broadcast_to(np.asarray(first.size, dtype=float), (m,))
    motions = {GROUND: ground_motion(), first.driver.body: driver_motion(first)}
    ok = np.ones(m, dtype=bool)
    ks = np.ones((len(structure.dyads), m), dtype=int)
    with np.errstate(all="ignore"):
        for d, dyad in enumerate(structure.dyads):
            solver = DyadSolver(first, dyad)
            if solver.branches == 2:
                ks[d] = _branch(first, dyad, solver, motions, size, ok)
            # (the closeness alone, as solve_dyad with strict = False measures it: no
            # velocities or accelerations; the next dyad reads these bodies' positions)
            sin2 = probe_dyad(first, dyad, motions, ks[d] if solver.branches == 2 else 1,
                              solver)[0]
            ok &= np.broadcast_to(sin2, (m,)) > SINGULAR_FAIL**2
    return ks, ok


def _branch(first: Scene, dyad, solver: DyadSolver, motions, size, ok) -> np.ndarray:
    """The assembly whose hinted points lie closest, per scene (``ok`` cleared where the
    first row cannot close or no hint settles it)."""
    pr = (dyad_param(first, dyad, 0, motions, speeds=False),
          dyad_param(first, dyad, 1, motions, speeds=False))
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

