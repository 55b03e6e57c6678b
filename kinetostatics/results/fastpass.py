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
  prismatic joint copied, its ``offset`` worked out once its columns are whole.

No array over the whole sweep is made but the table's own, and no temporary per column:
measured 2026-11-29 (four-bar, 1e6 positions) against the full re-solve's some 26 arrays
(200 MB) and the tables computed from them chunk by chunk (docs/solve-paths.md, "Tables
at scale"). The numbers are those of the full re-solve's tables, bit for bit (the same
kernels row by row; the same operations on each row). Where a kernel refuses a block
(never expected: the sweep was solved by the same kernels) the caller builds the table
from the full re-solve.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .longtable import (
    KINEMATICS_FLOATS,
    REACTIONS_FLOATS,
    FloatBlock,
    LongTable,
    fill_offsets,
)

if TYPE_CHECKING:
    import pandas as pd

    from ..solver.blocks import LeanSolved
    from .solution import Solution


def compiled_frame(sol: Solution, lean: LeanSolved, name: str) -> pd.DataFrame | None:
    """Table ``name`` (``reactions`` or ``kinematics``) of ``sol``, a sweep solved lean on
    the compiled path (``lean``), built in one pass (module docstring); None where a
    kernel refused a block."""
    from ..solver.fast.compose import Refused
    from ..solver.fast.solve import SolvedAgain
    again = SolvedAgain(lean.known["scene"], lean.known["structure"])
    write = _kinematics if name == "kinematics" else _reactions
    try:
        table, fill = write(sol, again, lean.positions)
    except Refused:
        return None
    return table.frame_of(fill)


def _unused(i: int, part: slice) -> dict:
    raise NotImplementedError("a table built in one pass has its columns already")


def _kinematics(sol: Solution, again, positions: np.ndarray) -> tuple[LongTable, FloatBlock]:
    """The ``kinematics`` table's definition and its float columns, written block by
    block (:func:`~kinetostatics.solver.fast.table_kernels.point_rows`)."""
    points = list(sol._points())
    table = LongTable(positions, {"body": [b for b, _, _ in points],
                                  "point": [p for _, p, _ in points]},
                      KINEMATICS_FLOATS, _unused, sol._tiled)
    fill = FloatBlock(table)
    for c in fill.names:
        fill.array(c)
    out = fill.reserve()
    n = table.n
    local = [(float(lx), float(ly)) for _, _, (lx, ly) in points]
    point_rows = again.kernels.point_rows
    for lo, hi, motions, _ in again.blocks():
        for i, ((b, _, _), (lx, ly)) in enumerate(zip(points, local, strict=True)):
            point_rows(motions[b], hi - lo, lx, ly, out, i * n + lo)
    return table, fill


def _reactions(sol: Solution, again, positions: np.ndarray) -> tuple[LongTable, FloatBlock]:
    """The ``reactions`` table's definition and its float columns, written block by
    block (``F``: numpy's ``hypot`` of the columns just written, in place)."""
    joints = list(sol.scene.joints)
    n = positions.size
    table = fill = None
    prismatic: list[int] = []
    for lo, hi, _, reactions in again.blocks():
        if table is None:
            table = LongTable(positions, {"joint": joints,
                                          "on": [reactions[j].on for j in joints],
                                          "by": [reactions[j].by for j in joints]},
                              REACTIONS_FLOATS, _unused, sol._tiled)
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
