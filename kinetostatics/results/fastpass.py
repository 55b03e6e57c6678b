"""The ``reactions`` and ``kinematics`` tables of a long sweep solved lean on the compiled
path, each built in one pass: the sweep is solved again by the kernels a block of rows
at a time into one scratch buffer
(:class:`~kinetostatics.solver.fast.solve.SolvedAgain`), and each block's rows are
written straight into the table's columns, allocated once
(:class:`~kinetostatics.results.longtable.FloatBlock`), while the block is in the caches:

* ``kinematics``: every point's six columns by one compiled kernel per point and block
  (:func:`~kinetostatics.solver.fast.table_kernels.point_rows`), with the numpy path's
  operations in its order;
* ``reactions``: ``Fx``, ``Fy`` copied (or negated) into their columns, ``F =
  hypot(Fx, Fy)`` written in place (numpy's ``hypot``, ``out=``), ``N`` and ``M`` of a
  prismatic joint copied, its ``offset`` worked out once its columns are whole. If the
  ``kinematics`` table is not made yet, the pass writes its columns too, from each
  block's motion (:class:`PointRows`): that table, asked for later, is then ready
  without solving again, each byte of either table written once. (Keeping the bodies'
  motion for it instead, in the table's own rows, wrote 30 of its 54 rows twice for the
  four-bar and read them back: measured 2026-11-29 at 1e6 positions, both tables
  0.14-0.15 s of user time against 0.16-0.18 s, processes alternated; the ``reactions``
  table alone now costs the kinematics' writes too, 0.21 against 0.17 s, and holds
  their 432 MB, a peak of 807 against 627 MB.)

A crank and one dyad (not RTR, no ``resist`` loads) takes the fused table kernels instead
(:class:`~kinetostatics.solver.fast.table_pass.FusedTables`): the block solved tile by
tile in one kernel and each tile's rows of both tables written there by non-temporal
stores, ``F`` by numpy's ``hypot`` bit for bit at a fifteenth of its cost, the crank's
cos and sin those the lean solve kept (docs/solve-paths.md, "The fused table kernels").

The ``bodies`` table, over increasing driver positions, is a composed pass of its own
(:func:`bodies_frame`): each body's ``omega`` and ``alpha`` written, its continuous angle
carried from block to block (:class:`~kinetostatics.results.sweepangles.SweepAngles`).

No array over the whole sweep is made but the tables' own, and no temporary per column
(the full re-solve gathered some 26 arrays, 200 MB at 1e6 positions, and the tables were
computed from them chunk by chunk: docs/solve-paths.md, "Tables at scale"). The numbers
are those of the full re-solve's tables, bit for bit (the same kernels row by row; the
same operations on each row). Where a kernel refuses a block (never expected: the sweep
was solved by the same kernels) the caller builds the table from the full re-solve.
"""

from __future__ import annotations

from types import SimpleNamespace
from typing import TYPE_CHECKING

import numpy as np

from ..solver.driver import BodyMotion
from ..solver.fast.layout import AL, OM
from .longtable import (
    KINEMATICS_FLOATS,
    REACTIONS_FLOATS,
    FloatBlock,
    LongTable,
    fill_offsets,
    point_labels,
    reaction_labels,
)
from .sweepangles import SweepAngles, laid_out

KEPT = "_onepass"       # the Solution's entry holding what a pass wrote ahead (as onepass's)

if TYPE_CHECKING:
    import pandas as pd

    from ..solver.blocks import LeanSolved
    from .solution import Solution


def compiled_frame(sol: Solution, lean: LeanSolved, name: str) -> pd.DataFrame | None:
    """Table ``name`` (``reactions`` or ``kinematics``) of ``sol``, a sweep solved lean on
    the compiled path (``lean``), built in one pass (module docstring); None where a
    kernel refused a block. The ``reactions`` pass writes the ``kinematics`` table's
    columns too, if that table is not made yet (:class:`PointRows`)."""
    from ..solver.fast.compose import Refused
    from ..solver.fast.loader import kernels
    from ..solver.fast.solve import SolvedAgain
    from ..solver.fast.table_pass import FusedTables
    d = sol.__dict__
    kept = d.pop(KEPT, None)            # (taken: no two threads make a table of one pass)
    if name == "kinematics" and type(kept) is PointRows:
        return kept.frame()
    scene, structure = lean.known["scene"], lean.known["structure"]
    fused = FusedTables(kernels(), scene, structure)
    try:
        if fused.kernel is not None:
            return _fused_frame(sol, fused, lean, name)
        again = SolvedAgain(scene, structure)
        rows = again.kernels.point_rows
        if name == "kinematics":
            points = PointRows(sol, lean.positions, rows)
            for lo, hi, motions, _ in again.blocks():
                points.put(motions, lo, hi)
            return points.frame()
        points = None if "kinematics" in d else PointRows(sol, lean.positions, rows)
        table, fill = _reactions(sol, again, lean.positions, points)
    except Refused:
        return None
    if points is not None:
        d[KEPT] = points
    return table.frame_of(fill)


def bodies_frame(sol: Solution, lean: LeanSolved) -> pd.DataFrame | None:
    """The ``bodies`` table of ``sol``, a sweep solved lean on the compiled path over
    strictly increasing driver positions, in one pass: the sweep solved again a block
    of rows at a time (:class:`~kinetostatics.solver.fast.solve.SolvedAgain`), each
    body's ``omega`` and ``alpha`` written into the table's columns and its angle
    carried on by :class:`~kinetostatics.results.sweepangles.SweepAngles` (the
    operations of :func:`~kinetostatics.results.sweepangles.degree_angles` block by
    block: the same angles, bit for bit), laid out as :attr:`Solution.angles` holds them
    (the table's ``angle`` column). None where a kernel refused a block or the
    positions do not increase: the caller solves the sweep again in full. (Measured
    2026-11-30, the four-bar at 1e6 rows: 1.97 s from the full re-solve, its 26 arrays
    over the sweep and ``body_angles`` over them.)"""
    from ..solver.fast.compose import Refused
    from ..solver.fast.solve import SolvedAgain
    positions = lean.positions
    n = positions.size
    if n < 2 or not bool(np.all(positions[1:] > positions[:-1])):
        return None
    scene, structure = lean.known["scene"], lean.known["structure"]
    names = list(sol.scene.bodies)
    table = sol.long_table("bodies")        # (its angle column: sol.angles, set here)
    fill = FloatBlock(table)
    omega, alpha = fill.array("omega"), fill.array("alpha")
    angles = SweepAngles(scene, structure, positions)
    try:
        for lo, hi, motions, _ in SolvedAgain(scene, structure).blocks():
            if any(b not in motions for b in names):
                return None
            for i, b in enumerate(names):
                omega[i * n + lo:i * n + hi] = motions[b][OM]
                alpha[i * n + lo:i * n + hi] = motions[b][AL]
            bodies = {b: BodyMotion(None, *m) for b, m in motions.items()}
            angles.add(slice(lo, hi), SimpleNamespace(scene=scene, structure=structure,
                                                      n=hi - lo, bodies=bodies))
    except Refused:
        return None
    d = sol.__dict__
    d["angles"], d["_angle_whole"] = laid_out(angles.angles(), sol.scene, n)
    return table.frame_of(fill)


def _fused_frame(sol: Solution, fused, lean: LeanSolved, name: str) -> pd.DataFrame:
    """Table ``name`` written by the fused table kernel
    (:class:`~kinetostatics.solver.fast.table_pass.FusedTables`): the ``kinematics``
    table alone, or the ``reactions`` table and, if it is not made yet, the
    ``kinematics`` table's columns in the same pass (kept for it, :class:`PointRows`)."""
    d, positions = sol.__dict__, lean.positions
    points = None
    if name == "kinematics" or "kinematics" not in d:
        points = PointRows(sol, positions)
    located = [] if points is None else list(zip(points.bodies, points.local, strict=True))
    kout = np.empty((6, 0)) if points is None else points.out
    if name == "kinematics":
        fused.write(located, kout)
        return points.frame()
    joints = list(sol.scene.joints)
    table = LongTable(positions, reaction_labels(joints, fused.reactions), REACTIONS_FLOATS,
                      _no_chunks, sol._tiled)
    fill, prismatic = _reaction_columns(table, joints, fused.reactions)
    fused.write(located, kout, joints, fill.reserve())
    fill_offsets(fill, prismatic, table.n)
    if points is not None:
        d[KEPT] = points
    return table.frame_of(fill)


def _reaction_columns(table: LongTable, joints: list[str], reactions: dict
                      ) -> tuple[FloatBlock, list[int]]:
    """The ``reactions`` table's float columns, ``Fx, Fy, F`` arrays to be written in
    place (and ``N, M, offset`` where a joint is prismatic), a pin's ``N, M, offset``
    its constants; and the prismatic joints' blocks."""
    n = table.n
    fill = FloatBlock(table)
    for c in ("Fx", "Fy", "F"):
        fill.array(c)
    prismatic = [i for i, j in enumerate(joints) if reactions[j].N is not None]
    for c in ("N", "M", "offset") if prismatic else ():
        fill.array(c)
    for i in set(range(len(joints))) - set(prismatic):     # a pin: no N, M, offset
        fill.put(i, slice(i * n, (i + 1) * n), {"N": 0.0, "M": 0.0, "offset": np.nan},
                 ("N", "M", "offset"))
    return fill, prismatic


def _no_chunks(i: int, part: slice) -> dict:
    """The ``chunk`` of a table built here: none is ever asked for (the table is made
    whole by :meth:`~kinetostatics.results.longtable.LongTable.frame_of`; the CSV writer
    reads the Solution's own tables)."""
    raise RuntimeError("a table built in one pass gives no chunks: its columns are whole")


class PointRows:
    """The ``kinematics`` table written block by block, as the kernels solve the sweep
    again: every point's six columns by one compiled kernel per point and block
    (:func:`~kinetostatics.solver.fast.table_kernels.point_rows`) straight into the
    table's own array (its rows the columns, :class:`FloatBlock`), from the block's
    motion while it is in the caches; each byte of the table written once."""

    def __init__(self, sol: Solution, positions: np.ndarray, point_rows=None):
        points = list(sol._points())
        self.table = LongTable(positions, point_labels(points), KINEMATICS_FLOATS,
                               _no_chunks, sol._tiled)
        self.fill = FloatBlock(self.table)
        for c in self.fill.names:
            self.fill.array(c)
        self.out = self.fill.reserve()
        self.bodies = [b for b, _, _ in points]
        self.local = [(float(lx), float(ly)) for _, _, (lx, ly) in points]
        self.point_rows = point_rows    # (None: written by a fused table kernel)

    def put(self, motions: dict, lo: int, hi: int) -> None:
        """Rows ``lo`` to ``hi`` of every point (``motions``: body -> its motion over
        them, :mod:`~kinetostatics.solver.fast.layout`)."""
        n, out, point_rows = self.table.n, self.out, self.point_rows
        for i, (b, (lx, ly)) in enumerate(zip(self.bodies, self.local, strict=True)):
            # (one layout, C, whatever the block: a stack's block is a strided view of its
            # motion, and point_rows was compiled again for it, 'A', after a stacked solve)
            m = motions[b] if motions[b].flags.c_contiguous else np.ascontiguousarray(motions[b])
            point_rows(m, hi - lo, lx, ly, out, i * n + lo)

    def frame(self) -> pd.DataFrame:
        """The ``kinematics`` table (every row written)."""
        return self.table.frame_of(self.fill)


def _reactions(sol: Solution, again, positions: np.ndarray, points: PointRows | None
               ) -> tuple[LongTable, FloatBlock]:
    """The ``reactions`` table's definition and its float columns, written block by
    block (``F``: numpy's ``hypot`` of the columns just written, in place); ``points``:
    the ``kinematics`` table, written block by block too (None: not asked)."""
    joints = list(sol.scene.joints)
    n = positions.size
    table = fill = None
    prismatic: list[int] = []
    for lo, hi, motions, reactions in again.blocks():
        if points is not None:
            points.put(motions, lo, hi)
        if table is None:
            table = LongTable(positions, reaction_labels(joints, reactions),
                              REACTIONS_FLOATS, _no_chunks, sol._tiled)
            fill = FloatBlock(table)
            fx_all, fy_all, f_all = (fill.array(c) for c in ("Fx", "Fy", "F"))
            prismatic = [i for i, j in enumerate(joints) if reactions[j].N is not None]
            if prismatic:
                fill.array("offset")
            for i in set(range(len(joints))) - set(prismatic):   # a pin: no N, M, offset
                fill.put(i, slice(i * n, (i + 1) * n), {"N": 0.0, "M": 0.0, "offset": np.nan},
                         ("N", "M", "offset"))
        w = hi - lo
        for i, j in enumerate(joints):
            r = reactions[j]
            rows = slice(i * n + lo, i * n + hi)
            fx, fy = fx_all[rows], fy_all[rows]
            for value, out in ((r.fx, fx), (r.fy, fy)):
                if r.sign > 0:
                    np.copyto(out, value)
                else:
                    np.negative(value, out=out)
            np.hypot(fx, fy, out=f_all[rows])
            if r.N is not None:
                fill.put(i, rows, {c: np.broadcast_to(np.asarray(v, dtype=float), (w,))
                                   for c, v in (("N", r.N), ("M", r.M))}, ("N", "M"))
    fill_offsets(fill, prismatic, n)
    return table, fill
