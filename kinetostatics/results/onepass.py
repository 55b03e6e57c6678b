"""The ``reactions`` and ``kinematics`` tables of a long sweep solved lean, each built in
one pass that solves the sweep again block by block and writes each block's rows straight
into the table's columns; the ``reactions`` pass keeps what the ``kinematics`` table is
made of, so that the two cost one re-solve.

A long sweep is solved lean (:class:`~kinetostatics.solver.blocks.LeanSolved`: of the
solver's arrays only what the driver table and the dead points need). Its kinematics
and joint reactions are otherwise solved again in full when first read, gathered into
about 26 arrays over the sweep (200 MB at 1e6 positions, written and faulted in), and the
tables are then computed from those. Here the sweep is solved again block by block
(for ``kinematics`` the kinematics alone) and, while each block's arrays are fresh in the
caches, the table's rows are computed and written into its columns (one
:class:`~kinetostatics.results.longtable.FloatBlock`). The ``reactions`` pass also keeps
the bodies' motion arrays (at 1e6 positions 16 for the four-bar, 128 MB) in the rows of
the ``kinematics`` table's own array, which is not written yet; that table, if it is
asked for later, is computed from them a chunk of rows at a time, each chunk's motion
copied out before its rows are written over, without solving again and with no page
beyond the table's own. (The ``kinematics`` pass keeps nothing for ``reactions``: the
loads and reactions of a block cost what its kinematics cost, which a user of the
``kinematics`` table alone would pay for nothing.)

Every row is computed by the same operations as from the full re-solve, on the solver's
own blocks with the sweep's assemblies (:func:`~kinetostatics.solver.blocks.blocks_of_sweep`,
as :mod:`kinetostatics.results.streamed` does): the same numbers, bit for bit (a kept
motion array holds the block's values; a value that is one number in every block stays
that number, so the arithmetic that skips exact zeros takes the same road). The one
column that depends on the whole sweep, ``offset`` = M / N of a prismatic joint (left
empty where ``|N|`` is at most 1e-12 of its largest over the sweep), is worked out once
its ``N`` and ``M`` columns are whole (:func:`fill_offsets`). The pass runs under the
floating-point trap (:mod:`kinetostatics.solver.trap`) and, if the trap is touched, again
with every check, as the re-solve does. A sweep solved lean on the compiled path is
passed by :mod:`kinetostatics.results.fastpass` (its kernels, table by table).

What it costs is measured by ``python -m kinetostatics bench --tables`` (the solve and
these tables against the solve and the write floor of their bytes; README, "Speed").
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..solver.blocks import BLOCK_ROWS, LeanSolved, blocks_of_sweep
from ..solver.driver import BodyMotion
from ..solver.kinematics import solve_kinematics
from ..solver.pipeline import solve_block
from ..solver.solved import Solved
from ..solver.trap import first_trapped
from .longtable import CHUNK, FloatBlock, LongTable, fill_offsets, table_block

if TYPE_CHECKING:
    import pandas as pd

    from .solution import Solution

PASSED = ("reactions", "kinematics")    # the tables built in one pass
KEPT = "_onepass"       # the Solution's entry holding a pass (for the table not built yet)


def lean_frame(sol: Solution, name: str) -> pd.DataFrame | None:
    """Table ``name`` of ``sol`` built in one pass (module docstring), or None where the
    solution's arrays are whole (or solved on the compiled path, whose re-solve is its
    own): the caller builds it from them."""
    d = sol.__dict__
    lean = d.get("_deferred")
    if (type(lean) is not LeanSolved or "kin" in d or sol.path not in ("numpy", "fast")
            or lean.full is not None):
        d.pop(KEPT, None)               # (the arrays are whole: what a pass kept is moot)
        return None
    if name == "bodies":                # (a pass of its own, on the compiled path)
        from .fastpass import bodies_frame
        return bodies_frame(sol, lean) if sol.path == "fast" else None
    if name not in PASSED:
        return None
    if sol.path == "fast":              # solved again by the kernels, table by table
        from .fastpass import compiled_frame
        return compiled_frame(sol, lean, name)
    other = "reactions" if name == "kinematics" else "kinematics"
    passed = d.pop(KEPT, None)          # (taken: no two threads make a table of one pass)
    if passed is None or not passed.has(name):
        passed = OnePass(sol, lean)
        first_trapped(passed.run, name, other not in d)
    frame = passed.frame(name)
    if other not in d and passed.has(other):
        d[KEPT] = passed                # what the other table is made from
    return frame


class OnePass:
    """One pass over a lean sweep (module docstring): the ``reactions`` table's columns,
    and the ``kinematics`` table's columns or the bodies' motion it is computed from."""

    def __init__(self, sol: Solution, lean: LeanSolved):
        self.sol, self.lean = sol, lean
        self.tables: dict[str, LongTable] = {}      # each table's definition
        self.fills: dict[str, FloatBlock] = {}      # ... and its float columns
        self.prismatic: list[int] = []              # reactions' blocks with N an array
        self.motion: KeptMotion | None = None       # the bodies' motion, kept
        self.built: set[str] = set()                # tables whose columns are written
        self.taken: set[str] = set()                # tables whose frame was made

    def has(self, name: str) -> bool:
        """Whether table ``name`` can be made from this pass without solving again."""
        if name in self.taken:
            return False
        return name in self.built or (name == "kinematics" and self.motion is not None)

    def run(self, name: str, other: bool = True) -> None:
        """Solve the sweep again block by block (for ``kinematics`` the kinematics alone)
        and write each block's rows into the columns of table ``name``; for
        ``reactions``, with ``other`` (the ``kinematics`` table not made yet), keep the
        bodies' motion too (each table's definition from the first block of rows: the
        whole solution's would solve it again)."""
        scene, structure = self.lean.known["scene"], self.lean.known["structure"]
        positions = self.lean.positions
        n = positions.size
        _, structure, part = blocks_of_sweep(scene, structure, positions)
        # each joint's largest |N| taken as infinite: the offset is left for fill_offsets
        largest = dict.fromkeys(range(len(scene.joints)), np.inf)
        bodies = list(dict.fromkeys(b for b, _, _ in self.sol._points()))
        keep = KeptMotion(bodies, n) if name == "reactions" and other else None
        self.prismatic, self.motion = [], None
        for start in range(0, n, BLOCK_ROWS):
            rows = slice(start, min(start + BLOCK_ROWS, n))
            sc, st = part(rows, structure)
            kin = solve_kinematics(sc, st)
            st = kin.structure
            solved = (solve_block(sc, st, kin) if name == "reactions"
                      else Solved(sc, st, kin, None, {}, None, None))
            block = type(self.sol).block_of(solved, {}, largest)
            self._put(name, block.long_table(name), rows, n)
            if keep is not None:
                if start == 0:      # the motion is kept in the kinematics table's room
                    room = self._table("kinematics", block.long_table("kinematics"))
                    keep.room = room.reserve().reshape(-1, n)
                keep.put(kin.bodies, rows)
        self.built.add(name)
        if keep is not None and keep.whole:
            self.motion = keep
        elif keep is not None:
            self.tables.pop("kinematics", None)
            self.fills.pop("kinematics", None)

    def _table(self, name: str, block: LongTable) -> FloatBlock:
        """The columns of table ``name`` (``block``: its definition over a block of rows),
        made at the first block."""
        if name not in self.fills:
            self.tables[name] = LongTable(self.lean.positions, block.labels, block.floats,
                                          block.chunk, self.sol._tiled)
            self.fills[name] = FloatBlock(self.tables[name])
        return self.fills[name]

    def _put(self, name: str, block: LongTable, rows: slice, n: int) -> None:
        """Block of rows ``rows`` of table ``name`` (``block``: its definition over
        those rows) into the table's columns."""
        fill = self._table(name, block)
        here = slice(0, rows.stop - rows.start)
        for i in range(block.blocks):
            values = block.chunk(i, here)
            if rows.start == 0 and name == "reactions" and np.ndim(values["N"]):
                self.prismatic.append(i)
            fill.put(i, slice(i * n + rows.start, i * n + rows.stop), values)

    def frame(self, name: str) -> pd.DataFrame:
        """Table ``name`` as a DataFrame (made once: its columns are the table's)."""
        self.taken.add(name)
        table, fill = self.tables.pop(name), self.fills.pop(name)
        if name == "kinematics" and name not in self.built:
            motion, self.motion = self.motion, None
            self._kinematics_of(motion, table, fill)
        if name == "reactions":
            fill_offsets(fill, self.prismatic, table.n)
        return table.frame_of(fill)

    def _kinematics_of(self, motion: KeptMotion, table: LongTable, fill: FloatBlock) -> None:
        """The ``kinematics`` columns from the kept motion, a chunk of rows at a time: the
        motion's rows of the chunk are copied out first, then the chunk's rows of every
        point are written (over the motion's rows of that chunk, where it was kept in the
        table's room, and nowhere else: rows of a later chunk stay as they were)."""
        n = table.n
        for start in range(0, n, CHUNK):
            rows = slice(start, min(start + CHUNK, n))
            block = self.sol._kinematics_long(motion.bodies(rows))
            here = slice(0, rows.stop - rows.start)
            for i in range(block.blocks):
                fill.put(i, slice(i * n + rows.start, i * n + rows.stop), block.chunk(i, here))


class KeptMotion:
    """Bodies' motion over the sweep, kept block by block: each field that is an array
    over a block's rows becomes a row of one array over the sweep (one allocation);
    a field that is one number stays that number. A block whose layout differs from
    the first one's (an array where there was a number, another number, two fields
    that are one array in the first block and two in this one) leaves nothing kept
    (:attr:`whole` False): the table is then made by solving again."""

    def __init__(self, bodies: list[str], n: int, room: np.ndarray | None = None):
        self.names, self.n = bodies, n
        self.layout: dict[tuple[str, str], object] = {}    # (body, field) -> row or number
        self.slab: np.ndarray | None = None
        self.room = room        # rows of n values to keep the arrays in, if there are enough
        self.whole = True

    def put(self, motions: dict[str, BodyMotion], rows: slice) -> None:
        """The motions of the block of rows ``rows`` (``motions``: body -> motion)."""
        if not self.whole:
            return
        size = rows.stop - rows.start
        if self.slab is None:
            self._lay_out(motions, size)
        written: dict[int, int] = {}            # the block's arrays by identity -> row
        source: dict[int, int] = {}             # ... and each row's array
        for (b, f), where in self.layout.items():
            v = getattr(motions[b], f)
            per_row = type(v) is np.ndarray and v.ndim == 1 and v.shape[0] == size
            if type(where) is int and per_row:
                if written.setdefault(id(v), where) != where \
                        or source.setdefault(where, id(v)) != id(v):
                    self.whole = False          # the arrays are not laid out as at first
                    return
                self.slab[where, rows] = v
            elif type(where) is int or per_row or type(v) is not type(where) \
                    or np.float64(v).tobytes() != np.float64(where).tobytes():
                self.whole = False
                return

    def _lay_out(self, motions: dict[str, BodyMotion], size: int) -> None:
        """The first block's layout: a row of the slab per distinct array."""
        rows: dict[int, int] = {}
        for b in self.names:
            for f in BodyMotion.FIELDS:
                v = getattr(motions[b], f)
                if type(v) is np.ndarray and v.ndim == 1 and v.shape[0] == size \
                        and v.dtype == np.float64:
                    self.layout[b, f] = rows.setdefault(id(v), len(rows))
                elif type(v) is float or type(v) is np.float64:
                    self.layout[b, f] = v
                else:
                    self.whole = False
                    return
        room = self.room
        fits = room is not None and room.shape[0] >= len(rows)
        self.slab = room[:len(rows)] if fits else table_block((len(rows), self.n))

    def bodies(self, rows: slice | None = None) -> dict[str, BodyMotion]:
        """Each body's motion over the whole sweep (``rows``: over those rows, copied
        out of where they are kept)."""
        copies = {}
        for v in self.layout.values():
            if type(v) is int and v not in copies:
                copies[v] = self.slab[v] if rows is None else self.slab[v, rows].copy()
        out = {}
        for b in self.names:
            values = [self.layout[b, f] for f in BodyMotion.FIELDS]
            out[b] = BodyMotion(None, *(copies[v] if type(v) is int else v for v in values))
        return out
