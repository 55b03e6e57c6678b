"""The ``reactions`` and ``kinematics`` tables of a long sweep solved lean, each built in
one pass: the sweep solved again block by block and each block's rows written straight
into the table's columns.

A long sweep is solved lean (:class:`~kinetostatics.solver.blocks.LeanSolved`: of the
solver's arrays only what the driver table and the dead points need). Its kinematics
and joint reactions are otherwise solved again in full when first read, gathered into
about 26 arrays over the sweep (200 MB at 1e6 positions, written and faulted in), and the
tables are then computed from those. Here the table is computed from each block of rows
while that block's arrays are fresh in the caches, and written into its columns (one
:class:`~kinetostatics.results.longtable.FloatBlock`): the table's bytes are written once
and nothing else over the sweep is held. The ``kinematics`` table solves only the
kinematics of each block; ``reactions`` the loads and reactions too.

Every row is computed by the same operations as from the full re-solve, on the solver's
own blocks with the sweep's assemblies (:func:`~kinetostatics.solver.blocks.blocks_of_sweep`,
as :mod:`kinetostatics.results.streamed` does): the same numbers, bit for bit. The one
column that depends on the whole sweep, ``offset`` = M / N of a prismatic joint (left
empty where ``|N|`` is at most 1e-12 of its largest over the sweep), is worked out once
its ``N`` and ``M`` columns are whole. The pass runs under the floating-point trap
(:mod:`kinetostatics.solver.trap`) and, if the trap is touched, again with every check,
as the re-solve does.

What it costs is measured by ``python -m kinetostatics bench --tables`` (the solve and
these tables against the solve and the write floor of their bytes; README, "Speed").
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..solver.blocks import BLOCK_ROWS, LeanSolved, blocks_of_sweep
from ..solver.kinematics import solve_kinematics
from ..solver.pipeline import solve_block
from ..solver.solved import Solved
from ..solver.trap import first_trapped
from .longtable import FloatBlock, LongTable, offsets

if TYPE_CHECKING:
    import pandas as pd

    from .solution import Solution

PASSED = ("reactions", "kinematics")    # the tables built in one pass
LOADS = {"reactions": True, "kinematics": False}    # whether the pass solves the loads


def lean_frame(sol: Solution, name: str) -> pd.DataFrame | None:
    """Table ``name`` of ``sol`` built in one pass (module docstring), or None where the
    solution's arrays are whole (or solved on the compiled path, whose re-solve is its
    own): the caller builds it from them."""
    d = sol.__dict__
    lean = d.get("_deferred")
    if (name not in PASSED or type(lean) is not LeanSolved or "kin" in d
            or sol.path != "numpy" or lean.full is not None):
        return None
    state: dict = {}
    first_trapped(_fill, sol, lean, name, state)
    table, fill = state["table"], state["fill"]
    if name == "reactions":
        _offsets(fill, state["prismatic"], table.n)
    return table.frame_of(fill)


def _fill(sol: Solution, lean: LeanSolved, name: str, state: dict) -> None:
    """Solve the sweep again block by block and write each block's rows of every block of
    the table into one :class:`FloatBlock`; into ``state``: the whole table's definition
    (its block names from the first block of rows: the whole solution's would solve it
    again), the ``fill`` and the table's blocks whose ``N`` is an array (the prismatic
    joints of ``reactions``)."""
    scene, structure = lean.known["scene"], lean.known["structure"]
    positions = lean.positions
    n = positions.size
    _, structure, part = blocks_of_sweep(scene, structure, positions)
    # each joint's largest |N| taken as infinite: the offset is left for _offsets
    largest = dict.fromkeys(range(len(scene.joints)), np.inf)
    prismatic: list[int] = []
    for start in range(0, n, BLOCK_ROWS):
        rows = slice(start, min(start + BLOCK_ROWS, n))
        sc, st = part(rows, structure)
        kin = solve_kinematics(sc, st)
        st = kin.structure
        solved = (solve_block(sc, st, kin) if LOADS[name]
                  else Solved(sc, st, kin, None, {}, None, None))
        block = type(sol).block_of(solved, {}, largest).long_table(name)
        if "fill" not in state:
            table = state["table"] = LongTable(positions, block.labels, block.floats,
                                               block.chunk, sol._tiled)
            state["fill"] = FloatBlock(table)
        fill = state["fill"]
        here = slice(0, rows.stop - rows.start)
        for i in range(block.blocks):
            values = block.chunk(i, here)
            if start == 0 and name == "reactions" and np.ndim(values["N"]):
                prismatic.append(i)
            fill.put(i, slice(i * n + rows.start, i * n + rows.stop), values)
    state["prismatic"] = prismatic


def _offsets(fill: FloatBlock, prismatic: list[int], n: int) -> None:
    """The ``offset`` of each prismatic joint's rows, from its whole ``N`` and ``M``."""
    for i in prismatic:
        rows = slice(i * n, (i + 1) * n)
        nn, mm = fill.rows["N"][rows], fill.rows["M"][rows]
        fill.rows["offset"][rows] = offsets(nn, mm, np.abs(nn).max() if n else 0.0)
