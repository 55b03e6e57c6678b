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
  prismatic joint copied, its ``offset`` worked out once its columns are whole. The pass
  also keeps the bodies' motion (ten rows a body) in rows of the ``kinematics`` table's
  own array, not written yet (:class:`KeptMotion`): that table, asked for later, is
  written over them a chunk at a time, without solving again (as the numpy path's
  :mod:`~kinetostatics.results.onepass` does).

No array over the whole sweep is made but the tables' own, and no temporary per column
(the full re-solve gathered some 26 arrays, 200 MB at 1e6 positions, and the tables were
computed from them chunk by chunk: docs/solve-paths.md, "Tables at scale"). The numbers
are those of the full re-solve's tables, bit for bit (the same kernels row by row; the
same operations on each row). Where a kernel refuses a block (never expected: the sweep
was solved by the same kernels) the caller builds the table from the full re-solve.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..solver.fast.layout import MOTION as MOTION_ROWS
from .longtable import (
    KINEMATICS_FLOATS,
    REACTIONS_FLOATS,
    FloatBlock,
    LongTable,
    fill_offsets,
    point_labels,
    reaction_labels,
)

KEPT = "_onepass"       # the Solution's entry holding what a pass kept (as onepass's)
# Rows of kept motion copied out at a time (a body's ten rows, about 1 MB for three bodies
# at 4096: the copy stays in the cache while the points are written). Measured
# 2026-11-29, four-bar at 1e6, kinematics from the kept motion, five rounds each,
# alternated: 4096 rows 0.081 / 0.097 s best / median, 2048 0.091 / 0.116, 8192 0.088 /
# 0.129, 32 768 (longtable.CHUNK) 0.100 / 0.121
KEPT_CHUNK = 4096

if TYPE_CHECKING:
    import pandas as pd

    from ..solver.blocks import LeanSolved
    from .solution import Solution


def compiled_frame(sol: Solution, lean: LeanSolved, name: str) -> pd.DataFrame | None:
    """Table ``name`` (``reactions`` or ``kinematics``) of ``sol``, a sweep solved lean on
    the compiled path (``lean``), built in one pass (module docstring); None where a
    kernel refused a block. The ``reactions`` pass keeps the bodies' motion for the
    ``kinematics`` table, if that is not made yet (:class:`KeptMotion`)."""
    from ..solver.fast.compose import Refused
    from ..solver.fast.solve import SolvedAgain
    d = sol.__dict__
    kept = d.pop(KEPT, None)            # (taken: no two threads make a table of one pass)
    if name == "kinematics" and type(kept) is KeptMotion:
        return kept.frame()
    again = SolvedAgain(lean.known["scene"], lean.known["structure"])
    try:
        if name == "kinematics":
            table, fill = _kinematics(sol, again, lean.positions)
        else:
            keep = None if "kinematics" in d else KeptMotion(sol, again.kernels,
                                                              lean.positions)
            table, fill = _reactions(sol, again, lean.positions, keep)
            if keep is not None and keep.whole:
                d[KEPT] = keep
    except Refused:
        return None
    return table.frame_of(fill)


def _no_chunks(i: int, part: slice) -> dict:
    """The ``chunk`` of a table built here: none is ever asked for (the table is made
    whole by :meth:`~kinetostatics.results.longtable.LongTable.frame_of`; the CSV writer
    reads the Solution's own tables)."""
    raise RuntimeError("a table built in one pass gives no chunks: its columns are whole")


def _kinematics_table(sol: Solution, positions: np.ndarray
                      ) -> tuple[LongTable, FloatBlock, list]:
    """The ``kinematics`` table's definition, its float columns (one array, every column
    a row of it) and its points (body, point, local point)."""
    points = list(sol._points())
    table = LongTable(positions, point_labels(points), KINEMATICS_FLOATS, _no_chunks,
                      sol._tiled)
    fill = FloatBlock(table)
    for c in fill.names:
        fill.array(c)
    return table, fill, points


def _kinematics(sol: Solution, again, positions: np.ndarray) -> tuple[LongTable, FloatBlock]:
    """The ``kinematics`` table's definition and its float columns, written block by
    block (:func:`~kinetostatics.solver.fast.table_kernels.point_rows`)."""
    table, fill, points = _kinematics_table(sol, positions)
    out = fill.reserve()
    n = table.n
    local = [(float(lx), float(ly)) for _, _, (lx, ly) in points]
    point_rows = again.kernels.point_rows
    for lo, hi, motions, _ in again.blocks():
        for i, ((b, _, _), (lx, ly)) in enumerate(zip(points, local, strict=True)):
            point_rows(motions[b], hi - lo, lx, ly, out, i * n + lo)
    return table, fill


class KeptMotion:
    """The bodies' motion over the sweep, kept by the ``reactions`` pass for the
    ``kinematics`` table: each body's ten motion rows
    (:mod:`~kinetostatics.solver.fast.layout`) in rows of that table's own array, which
    are not written yet (:attr:`whole` False where they do not fit: nothing kept). The
    table is then written over them a chunk of rows at a time, each chunk's motion
    copied out first (no re-solve, no page beyond the table's own)."""

    def __init__(self, sol: Solution, kernels, positions: np.ndarray):
        self.table, self.fill, self.points = _kinematics_table(sol, positions)
        self.kernels = kernels
        self.bodies = list(dict.fromkeys(b for b, _, _ in self.points))
        n = positions.size
        room = self.fill.reserve().reshape(-1, n) if n else None
        rows = MOTION_ROWS * len(self.bodies)
        self.whole = room is not None and room.shape[0] >= rows
        self.slab = room[:rows] if self.whole else None

    def put(self, motions: dict, lo: int, hi: int) -> None:
        """The bodies' motion over rows ``lo`` to ``hi`` (body -> its motion array)."""
        for k, b in enumerate(self.bodies):
            self.slab[MOTION_ROWS * k:MOTION_ROWS * (k + 1), lo:hi] = motions[b]

    def frame(self) -> pd.DataFrame:
        """The ``kinematics`` table, its columns written over the kept motion."""
        table, fill, slab = self.table, self.fill, self.slab
        n = table.n
        out = fill.reserve()
        local = [(float(lx), float(ly)) for _, _, (lx, ly) in self.points]
        where = {b: k for k, b in enumerate(self.bodies)}
        point_rows = self.kernels.point_rows
        # (a row longer than the chunk: the kernel sees the layout of the solve's buffer,
        # one compiled signature for both roads)
        scratch = np.empty((slab.shape[0], KEPT_CHUNK + 8))
        for lo in range(0, n, KEPT_CHUNK):
            hi = min(lo + KEPT_CHUNK, n)
            motion = scratch[:, :hi - lo]
            motion[...] = slab[:, lo:hi]            # (before the chunk's rows are written)
            for i, ((b, _, _), (lx, ly)) in enumerate(zip(self.points, local, strict=True)):
                k = where[b]
                point_rows(motion[MOTION_ROWS * k:MOTION_ROWS * (k + 1)], hi - lo, lx, ly,
                           out, i * n + lo)
        self.slab = None
        return table.frame_of(fill)


def _reactions(sol: Solution, again, positions: np.ndarray, keep: KeptMotion | None
               ) -> tuple[LongTable, FloatBlock]:
    """The ``reactions`` table's definition and its float columns, written block by
    block (``F``: numpy's ``hypot`` of the columns just written, in place); ``keep``:
    where the bodies' motion is kept, block by block, if it fits."""
    joints = list(sol.scene.joints)
    n = positions.size
    table = fill = None
    prismatic: list[int] = []
    keep = keep if keep is not None and keep.whole else None
    for lo, hi, motions, reactions in again.blocks():
        if keep is not None:
            keep.put(motions, lo, hi)
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
