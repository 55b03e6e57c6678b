"""A long sweep solved in blocks of rows that stay in the processor's cache.

Every quantity of a solve is elementwise over the rows (positions): row i of every
array depends on row i of the driver's motion only. A long sweep can therefore be
solved a block of rows at a time, giving exactly the numbers of one pass over all the
rows. What it saves is memory traffic: a pass over 2e5 rows makes each of its few
hundred intermediate arrays 1.6 MB, beyond the L2 cache, and each fresh one costs
page faults; a block of ``BLOCK_ROWS`` rows keeps them in cache and reuses the same
memory. Only the arrays a solve keeps are gathered into arrays over the whole sweep
(:class:`Gather`); a solve keeps first only what the driver table and the dead points
need (``lean``: a :class:`LeanSolved`),
and solves the blocks again, gathering every kept array, when another table asks.

What is not elementwise is done once over the whole sweep, as before: the assembly is
chosen at the sweep's first row (in the first block), the dead points between rows are
screened on the gathered motion. A scene whose loads depend on the whole sweep (a
``resist`` or ``when = "resisting"`` load measures its threshold against the sweep's
top speed or power) or that has joint friction is solved in one pass. A block that
the solver refuses sends the sweep back to one pass, so that the message (which rows,
how many) is the one pass's.
"""

from __future__ import annotations

import threading
from dataclasses import replace

import numpy as np

from ..common.lazy import moved_names
from ..model.scene import Scene
from .driver import BodyMotion
from .kinematics import Kinematics, choose_assembly, solve_kinematics, with_positions
from .reactions import DriverReaction
from .solved import Solved

BLOCK_ROWS = 16384   # 128 kB per array (measured best of 4096-65536 on a 2 MB L2 cache)


# glibc gives the top of its heap back to the system once more than its trim threshold
# lies free there, and the next block or run of a stack faults every page in again (about
# 1000 page faults a run of 12 274 rows, its peak 6.7 MB: measured 2026-11-29, 3.6-4.0 ms
# against 1.6 ms a run without them); the threshold follows the largest block it mapped
# and freed (twice its size, for blocks up to 32 MB), so one block of HEAP_BYTES
# allocated and freed untouched (no page faulted) keeps the heap for runs of up to twice
# that
HEAP_BYTES = 16 << 20
_heap: list[int] = []


def keep_heap() -> None:
    """Once per process, raise glibc's heap trim threshold past a run's peak (above); a
    no-op elsewhere and after the first call."""
    if not _heap:
        _heap.append(HEAP_BYTES)
        np.empty(HEAP_BYTES // 8)       # (mapped and freed at once, never touched)


class Unblockable(Exception):
    """The blocks did not give arrays of one layout: solve in one pass instead."""


def blockable(scene: Scene, n: int, tops: bool = False) -> bool:
    """Whether a sweep of ``n`` rows of ``scene`` is solved in blocks: long enough to gain
    (at least two blocks), every load elementwise, no joint friction. ``tops``: a load
    whose threshold is the sweep's top (``resist``, ``when = "resisting"``) counted as
    elementwise too (the solve's blocks measure it as they go,
    :class:`~kinetostatics.solver.loads.SweepTops`; a table streamed block by block
    does not)."""
    if n < 2 * BLOCK_ROWS:
        return False
    from .friction import has_friction
    if has_friction(scene):
        return False
    return tops or all(ld.resist is None and ld.when != "resisting" for ld in scene.loads)


def _per_row(v, n: int) -> bool:
    return type(v) is np.ndarray and v.ndim == 1 and v.shape[0] == n


class Gather:
    """Arrays over the whole sweep, filled block by block from objects of one layout.

    The first block's object sets the layout: each attribute that is an array over its
    rows (or a tuple holding such arrays) gets an array over all ``total`` rows; the
    rest (scalars, names, shared objects) is kept as it is. Two attributes that hold
    one array share one gathered array. A later block of another layout (an attribute
    that is a scalar there and an array here, two arrays where there was one) raises
    :class:`Unblockable`.
    """

    def __init__(self, obj, n: int, arrays: _Arrays, skip: tuple[str, ...] = ()):
        self.obj = obj
        self.cls = type(obj)
        fields = obj.__slots__ if hasattr(obj, "__slots__") else tuple(vars(obj))
        fields = [f for f in fields if f not in skip]
        self.plan = []          # (field, None | tuple of which are per-row, ...)
        self.values = {}
        for f in fields:
            v = getattr(obj, f)
            if _per_row(v, n):
                self.plan.append((f, None))
                self.values[f] = arrays.full(v)
            elif type(v) is tuple and any(_per_row(x, n) for x in v):
                which = tuple(_per_row(x, n) for x in v)
                self.plan.append((f, which))
                self.values[f] = tuple(arrays.full(x) if w else x
                                       for x, w in zip(v, which, strict=True))
            else:
                self.values[f] = v
        planned = {f for f, _ in self.plan}
        self.rest = [f for f in fields if f not in planned]     # kept as they are

    def put(self, obj, rows: slice, n: int, seen: dict) -> None:
        """Copy block ``obj``'s arrays into ``rows`` of the gathered ones (``seen``: the
        block's arrays already copied, by identity, with where they went)."""
        for f, which in self.plan:
            v = getattr(obj, f)
            if which is None:
                _copy(v, self.values[f], rows, n, seen)
                continue
            if type(v) is not tuple or len(v) != len(which):
                raise Unblockable(f)
            for x, w, dest in zip(v, which, self.values[f], strict=True):
                if w:
                    _copy(x, dest, rows, n, seen)
                elif _per_row(x, n) or not _same(x, dest):
                    raise Unblockable(f)
        for f in self.rest:
            if _per_row(getattr(obj, f), n):
                raise Unblockable(f)

    def build(self, **extra):
        """The gathered object (``extra``: attributes given anew)."""
        new = object.__new__(self.cls)
        for f, v in self.values.items():
            object.__setattr__(new, f, extra.pop(f, v))
        for f, v in extra.items():
            object.__setattr__(new, f, v)
        return new


class _Arrays:
    """The gathered arrays, one per array of the first block (by its identity).

    A first look (:meth:`full` before :meth:`allocate`) only notes the arrays; then the
    float ones are given the rows of one slab (one allocation, large enough for the
    kernel's huge pages: the gathered arrays fault in a few hundred pages instead of one
    per 4 kB), the others an array each, and :meth:`full` copies the first block in.
    """

    def __init__(self, total: int):
        self.total = total
        self.first: dict[int, np.ndarray] = {}
        self.dest: dict[int, np.ndarray] | None = None
        self.filled: set[int] = set()

    def full(self, v: np.ndarray) -> np.ndarray:
        if self.dest is None:
            self.first.setdefault(id(v), v)
            return v
        out = self.dest[id(v)]
        if id(v) not in self.filled:
            out[:v.shape[0]] = v
            self.filled.add(id(v))
        return out

    def allocate(self) -> None:
        floats = [k for k, v in self.first.items() if v.dtype == np.float64]
        slab = np.empty((len(floats), self.total))
        self.dest = {k: slab[i] for i, k in enumerate(floats)}
        for k, v in self.first.items():
            if k not in self.dest:
                self.dest[k] = np.empty(self.total, dtype=v.dtype)


def _copy(v, dest: np.ndarray, rows: slice, n: int, seen: dict) -> None:
    if not _per_row(v, n) or v.dtype != dest.dtype:
        raise Unblockable("layout")
    where = seen.get(id(v))
    if where is None:
        # (an array of the first block held twice is one gathered array: in this block
        # too it must be one array, not two that would be written over each other)
        if seen.setdefault(("to", id(dest)), v) is not v:
            raise Unblockable("aliasing")
        seen[id(v)] = dest
        dest[rows] = v
    elif where is not dest:
        raise Unblockable("aliasing")


def _same(a, b) -> bool:
    """Two values that are not per row: the same object or equal scalars."""
    if a is b:
        return True
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return False
    try:
        return bool(a == b)
    except (TypeError, ValueError):
        return False


def solve_blocks(total: int, part, solve_block, scene: Scene | None = None,
                 structure=None, positions: np.ndarray | None = None,
                 block: int | None = None, lean: bool = False) -> Solved | Kept:
    """The solved arrays over ``total`` rows, solved ``block`` rows at a time (``lean``: only
    the driver table's arrays and the dyads' closeness to a dead centre, a
    :class:`Kept`).

    Parameters
    ----------
    total : int
        Rows of the whole sweep.
    part : callable
        ``part(rows, structure) -> (scene, structure)``: the scene and structure of the
        rows ``rows`` (a slice), given the structure the previous block solved with (its
        assemblies chosen; the first block gets ``structure``).
    solve_block : callable
        ``solve_block(scene, structure, kin)``: a block's :class:`Solved` from its kinematics
        (the loads and reactions, checked finite).
    scene, structure
        The whole sweep's scene and structure; ``structure`` None:
        the last block's.
    positions : ndarray, optional
        The whole sweep's driver positions (default: the scene's).

    Raises
    ------
    Unblockable
        The blocks disagree in layout.
    WorkbenchError
        Whatever the solver raises for a block.
    """
    block = block or BLOCK_ROWS
    arrays = _Arrays(total)
    gathers = None
    solved = structure
    for start in range(0, total, block):
        rows = slice(start, min(start + block, total))
        sc, st = part(rows, solved)
        kin = solve_kinematics(sc, st)
        solved = kin.structure              # the first block chose the assembly
        sol = solve_block(sc, solved, kin)
        n = rows.stop - rows.start
        layout, put = (_lean_layout, _lean_put) if lean else (_layout, _put)
        if gathers is None:
            layout(sol, n, arrays)          # a first look: which arrays
            arrays.allocate()
            gathers = layout(sol, n, arrays)
        else:
            put(gathers, sol, rows, n)
    if structure is None or len(structure.assembly) != len(structure.dyads):
        structure = solved
    if lean:
        drive_g, undefined_g, flags_g = gathers
        return Kept(structure, drive_g.build(), undefined_g.values["undefined"],
                     [g.values["closeness2"] for g in flags_g],
                     [g.values["singular"] for g in flags_g])
    bodies_g, dyads_g, reactions_g, drive_g, undefined = gathers
    bodies = {name: g.build(_origin_arm=None, _arms=None) for name, g in bodies_g.items()}
    known = {id(g.obj): name for name, g in bodies_g.items()}
    dyads = []
    for d, (g, params) in enumerate(dyads_g):
        pr = tuple(pg.build(known=bodies[known[id(pg.obj.known)]]) for pg in params)
        dyads.append(g.build(dyad=structure.dyads[d], params=pr, n=total, _tau=None))
    if positions is None:
        positions = scene.driver.positions
    kin = Kinematics(scene, structure, positions, bodies, dyads)
    reactions = {name: g.build() for name, g in reactions_g.items()}
    return Solved(scene, structure, kin, None, reactions, drive_g.build(),
                  undefined.values["undefined"])


def blocks_of_sweep(scene: Scene, structure, positions: np.ndarray, tops=None):
    """The whole sweep's scene, its structure and the ``part`` of :func:`solve_blocks`
    for ``scene`` at ``positions`` (each dyad's assembly chosen at the scene's own
    first row: in the first block when ``positions`` are the scene's); ``tops``: the
    sweep's :class:`~kinetostatics.solver.loads.SweepTops`, which every block's loads
    measure their thresholds by (by default the ones its lean solve settled, kept by
    the whole sweep's scene: a table solved again block by block)."""
    own = positions is scene.driver.positions
    full = scene if own else with_positions(scene, positions)
    if tops is None and own:
        tops = scene.__dict__.get("sweep_tops")
    if len(structure.assembly) != len(structure.dyads) and not own:
        structure = replace(structure, assembly=choose_assembly(scene, structure))

    def part(rows: slice, st):
        sc = with_positions(scene, positions[rows])
        if tops is not None:
            sc.__dict__["tops"] = tops
        return sc, st
    return full, structure, part


class _Undefined:
    """The undefined-load mask of a block as an object (gathered like the others)."""

    __slots__ = ("undefined",)

    def __init__(self, value):
        self.undefined = value


class _Flags:
    """A dyad's closeness to a dead centre and its singular rows, as an object (gathered
    like the others)."""

    __slots__ = ("closeness2", "singular")

    def __init__(self, dm):
        self.closeness2, self.singular = dm.closeness2, dm.singular


class Kept:
    """What a lean solve in blocks keeps of a long sweep: the structure it solved with,
    ``Me``/``Fe`` and the undefined-load rows (the driver table), and each dyad's
    closeness to a dead centre and singular rows (its dead points and flags); maybe their
    m^2 (``measure2``: :func:`~kinetostatics.solver.deadpoints.measure2` of them, made
    with the flags; else None) and its screen (``screened``, as
    :func:`~kinetostatics.solver.deadpoints.dead_points_of_sweep` takes it; else None)."""

    def __init__(self, structure, drive: DriverReaction, undefined, closeness2: list,
                 singular: list, measure2: np.ndarray | None = None,
                 screened: tuple | None = None):
        self.structure, self.drive, self.undefined = structure, drive, undefined
        self.closeness2, self.singular, self.measure2 = closeness2, singular, measure2
        self.screened = screened


class LeanSolved:
    """A long sweep solved in blocks that holds, of the solver's arrays, only what the
    driver table and the dead points need: ``Me``/``Fe``, the undefined-load rows and
    each dyad's closeness to a dead centre and singular rows (at 1e6 rows about 4 arrays
    instead of about 26: 30 MB instead of 200 MB gathered, written and faulted in). Its
    kinematics and joint reactions, which every other table reads, are solved again when
    first asked for (:meth:`give`), in the same blocks with the same assemblies: the same
    numbers, bit for bit (a :class:`~kinetostatics.solver.solved.Deferred`)."""

    def __init__(self, scene: Scene, sweep: Kept, positions: np.ndarray, dead: tuple,
                 again):
        self.known = {"scene": scene, "structure": sweep.structure, "self_locking": None,
                      "drive": sweep.drive, "undefined_load": sweep.undefined}
        self.positions = positions
        self.flags, self.dead, self.again = sweep.singular, dead, again
        self.lock = threading.Lock()
        self.full: dict | None = None

    def singular(self) -> np.ndarray:
        """As :attr:`Kinematics.singular`, from the kept rows of each dyad."""
        return singular_rows(self.positions.size, self.flags, self.dead)

    def give(self, name: str, have=()) -> dict:
        """The kinematics and joint reactions, solved again (once), and from now on the
        full solve's ``Me``/``Fe`` and undefined rows (the same numbers)."""
        with self.lock:
            if self.full is None:
                sol = self.again()
                kin = sol.kin
                kin.between, kin.ends, kin.unassembled = self.dead
                kin.release()
                self.full = {"kin": kin, "joint_reactions": sol.joint_reactions,
                             "drive": sol.drive, "undefined_load": sol.undefined_load}
                self.again = None       # (the solver's closure: no longer needed)
            return self.full

    def solved(self) -> Solved:
        full = self.give("kin")
        sol = Solved(self.known["scene"], self.known["structure"], full["kin"], None,
                     full["joint_reactions"], full["drive"], full["undefined_load"])
        path = self.__dict__.get("path")        # (set by the compiled path)
        if path is not None:
            sol.path = path
        return sol

    def __reduce__(self):
        return _solved, (self.solved(),)


def _solved(solved: Solved) -> Solved:
    return solved


def singular_rows(n: int, flags: list, dead: tuple) -> np.ndarray:
    """:attr:`Kinematics.singular <kinetostatics.solver.kinematics.Kinematics.singular>`
    from each dyad's singular rows (``flags``) and the dead points between and beyond
    the rows (``dead``: between, ends, unassembled), without the kinematics: an array of
    its own each call (a table takes it as its column, no copy)."""
    between, ends, _ = dead
    first = flags[0] if len(flags) == 1 else None
    if type(first) is np.ndarray and first.shape == (n,) and first.dtype == np.bool_:
        out = first.copy()          # (one dyad: its rows as they are, the usual case)
    else:
        out = np.zeros(n, dtype=bool)
        for f in flags:
            out |= f
    if between.size:                # (no dead point between or beyond the rows: usual)
        out[between.ravel()] = True
    if ends.size:
        out[ends] = True
    return out


def _lean_layout(sol: Solved, n: int, arrays: _Arrays) -> tuple:
    return (Gather(sol.drive, n, arrays), Gather(_Undefined(sol.undefined_load), n, arrays),
            [Gather(_Flags(dm), n, arrays) for dm in sol.kin.dyads])


def _lean_put(gathers: tuple, sol: Solved, rows: slice, n: int) -> None:
    drive, undefined, flags = gathers
    if len(flags) != len(sol.kin.dyads):
        raise Unblockable("dyads")
    seen: dict = {}
    drive.put(sol.drive, rows, n, seen)
    undefined.put(_Undefined(sol.undefined_load), rows, n, seen)
    for g, dm in zip(flags, sol.kin.dyads, strict=True):
        g.put(_Flags(dm), rows, n, seen)


def _layout(sol: Solved, n: int, arrays: _Arrays) -> tuple:
    bodies = {name: Gather(m, n, arrays, skip=("_origin_arm", "_arms"))
              for name, m in sol.kin.bodies.items()}
    dyads = [(Gather(dm, n, arrays, skip=("params", "dyad")),
              [Gather(p, n, arrays, skip=("known",)) for p in dm.params])
             for dm in sol.kin.dyads]
    reactions = {name: Gather(r, n, arrays) for name, r in sol.joint_reactions.items()}
    drive = Gather(sol.drive, n, arrays)
    undefined = Gather(_Undefined(sol.undefined_load), n, arrays)
    return bodies, dyads, reactions, drive, undefined


def _put(gathers: tuple, sol: Solved, rows: slice, n: int) -> None:
    bodies, dyads, reactions, drive, undefined = gathers
    seen: dict = {}
    if list(bodies) != list(sol.kin.bodies) or list(reactions) != list(sol.joint_reactions):
        raise Unblockable("bodies")
    for name, g in bodies.items():
        g.put(sol.kin.bodies[name], rows, n, seen)
    for (g, params), dm in zip(dyads, sol.kin.dyads, strict=True):
        g.put(dm, rows, n, seen)
        for pg, p in zip(params, dm.params, strict=True):
            pg.put(p, rows, n, seen)
    for name, g in reactions.items():
        g.put(sol.joint_reactions[name], rows, n, seen)
    drive.put(sol.drive, rows, n, seen)
    undefined.put(_Undefined(sol.undefined_load), rows, n, seen)


__all__ = ["BLOCK_ROWS", "BodyMotion", "DriverReaction", "Gather", "Kept", "LeanSolved",
           "Unblockable", "blockable", "solve_blocks"]

# deprecated names: a lean long sweep is now a Solution wrapping a LeanSolved (the results
# wrap the solver's arrays; the package root stands above every subpackage), and the
# arrays it keeps are a Kept
__getattr__ = moved_names(__name__, {"LeanSolution": ("kinetostatics", "Solution"),
                                     "Sweep": (__name__, "Kept")})
