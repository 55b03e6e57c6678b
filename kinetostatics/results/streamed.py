"""``solve --out`` of a sweep too long to hold: its tables streamed block by block.

A one-shot solve holds every array over the sweep while its tables are written (at
1e7 positions about 6 GB). A streamed solve holds over the sweep only what is not
elementwise: ``Me``/``Fe`` and the flags of the driver table, each dyad's closeness to a
dead centre (the dead points between rows), and each turning body's continuous angle
(it depends on the rows before). Everything else is solved a block of rows at a time,
on the solver's own blocks (:func:`~kinetostatics.solver.blocks.blocks_of_sweep`, the
same assemblies), written, and let go:

1. the lean solve (:meth:`Sweep.lean_in_blocks
   <kinetostatics.solver.pipeline.Sweep.lean_in_blocks>`): ``Me``/``Fe``, the flags;
2. one pass over the blocks for what every row of a table may depend on: the bodies'
   angles (:class:`~kinetostatics.results.sweepangles.SweepAngles`), each prismatic
   joint's largest ``|N|`` (the ``offset`` column) and the summary's extremes
   (:class:`~kinetostatics.results.summary.Extremes`);
3. one pass per block of a long table (joint, point, body, dyad): each table's file
   gets that block's rows, block of rows after block of rows, so that every file holds
   its rows in the one-shot's order.

Every row of every table is computed by the same operations as in a one-shot solve, so
the files and ``summary.json`` are the one-shot's, bit for bit (tested at sizes where
both run). The passes cost a solve each (about 0.1 s per 1e6 positions), small beside
the writing. The files go into the staging folder of
:func:`~kinetostatics.model.outputs.staged_folder`: whole or not at all.

Streamed: a sweep that the solver solves in blocks (no joint friction, no load whose
threshold depends on the whole sweep) over strictly increasing driver positions.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from ..model.memory import FLOAT, budget, check_memory
from ..solver.blocks import blocks_of_sweep
from ..solver.footprint import BASE, check_solve, solve_bytes
from ..solver.kinematics import solve_kinematics
from ..solver.pipeline import Sweep, solve_block
from ..solver.solved import Solved
from .longtable import columns_frame
from .output import CsvStream, ParquetStream, Repeats, write_parquet
from .solution import Solution
from .summary import Extremes, left_out, solution_summary
from .sweepangles import SweepAngles

STREAM_BLOCK = 131_072      # rows solved and written at a time
# bytes per row held over the sweep (the positions twice, Me, the order and the summary's
# passes over them) and per row and column of a block being solved and written; measured
# with /usr/bin/time -v at 1e7 positions (docs/limits.md), a little above
SWEEP_ROW = 64 * FLOAT
SWEEP_COLUMN = 3 * FLOAT    # per dyad and turning body
BLOCK_ROW_FACTOR = 3.0      # a block's solve and its tables: 3 x a one-shot solve's row


def streamable(sweep: Sweep) -> bool:
    """Whether ``sweep`` can be streamed: solved in blocks, positions strictly increasing."""
    pos = sweep.positions
    return sweep.blocked and pos.size > 1 and bool(np.all(pos[1:] > pos[:-1]))


def stream_bytes(scene, rows: int, block: int = STREAM_BLOCK) -> float:
    """Estimated peak bytes of a streamed solve and write of ``rows`` positions."""
    columns = len(scene.bodies) + 2     # turning bodies and dyads, at most
    return (BASE + rows * (SWEEP_ROW + SWEEP_COLUMN * columns)
            + BLOCK_ROW_FACTOR * (solve_bytes(scene, min(rows, block)) - BASE))


def open_solve(scene: Any, stream: bool | None = None) -> Solution | StreamedSolve:
    """A solve whose tables are to be written (``solve --out``): a :class:`Solution` when
    the one-shot solve fits the memory budget, else a :class:`StreamedSolve` when the
    sweep can be streamed; refused in one line when neither fits.

    ``stream``: True or False forces the road (True still needs a streamable sweep)."""
    sweep = Sweep(scene, budget=False)
    n = sweep.positions.size
    if stream is None:
        stream = n >= 100_000 and solve_bytes(sweep.scene, n) > budget()[0]
    if stream and streamable(sweep):
        return StreamedSolve(sweep)
    check_solve(sweep.scene, n)
    return Solution.of(sweep.solve())


class StreamedSolve:
    """A long sweep solved for its tables block by block (module docstring).

    Parameters
    ----------
    sweep : Sweep
        A streamable sweep (:func:`streamable`).
    block : int
        Rows solved and written at a time.
    """

    def __init__(self, sweep: Sweep, block: int = STREAM_BLOCK):
        n = sweep.positions.size
        check_memory(stream_bytes(sweep.scene, n, block),
                     f"the streamed solve of {sweep.scene.title!r} at {n:,} positions",
                     "use fewer positions (driver.count)")
        lean = sweep.lean_in_blocks()
        self.block = block
        self.lean = lean
        self.whole = Solution.of(lean)      # Me/Fe and the flags over the sweep
        self.scene = self.whole.scene
        self.positions = lean.positions
        self.singular = lean.singular()
        out = left_out(self.singular, None)
        self.keep = ~out if out.any() and not out.all() else np.ones(n, dtype=bool)
        self.angles: dict[str, np.ndarray] | None = None
        self.largest_n: dict[int, float] = {}
        self.extremes: Extremes | None = None

    def blocks(self, loads: bool = True) -> Iterator[tuple[slice, Solution]]:
        """(rows, the Solution of those rows) over the sweep, solved again block by block
        with the sweep's assemblies (``loads`` False: the kinematics alone)."""
        structure = self.whole.structure
        _, structure, part = blocks_of_sweep(self.scene, structure, self.positions)
        n = self.positions.size
        for start in range(0, n, self.block):
            rows = slice(start, min(start + self.block, n))
            sc, st = part(rows, structure)
            kin = solve_kinematics(sc, st)
            solved = solve_block(sc, st, kin) if loads else Solved(
                sc, st, kin, None, {}, None, None)
            angles = {} if self.angles is None else {b: a[rows]
                                                     for b, a in self.angles.items()}
            yield rows, Solution.block_of(solved, angles, self.largest_n)

    def _gather(self) -> None:
        """The pass for what rows depend on: angles, largest |N|, the summary's extremes."""
        if self.angles is not None:
            return
        angles = SweepAngles(self.scene, self.whole.structure, self.positions)
        prismatic = [i for i, j in enumerate(self.scene.joints.values()) if j.kind == "T"]
        largest: dict[int, float] = {}
        joints = list(self.scene.joints)
        for rows, sol in self.blocks():
            if self.extremes is None:
                self.extremes = Extremes(self.scene, sol.kin.dyads,
                                         (self.lean.dead[0], self.lean.dead[2]))
            angles.add(rows, sol.kin)
            keep = self.keep[rows]
            self.extremes.add(sol, keep, self.positions[rows][keep])
            for i in prismatic:
                r = sol.joint_reactions[joints[i]]
                top = np.abs(np.broadcast_to(np.asarray(r.N, dtype=float), rows.stop
                                             - rows.start)).max()
                largest[i] = top if i not in largest else np.maximum(largest[i], top)
        self.largest_n.update(largest)
        self.angles = angles.angles()

    def summary(self) -> dict:
        """The contract's ``summary.json`` content: :meth:`Solution.summary` of the
        one-shot solve, bit for bit."""
        self._gather()
        return solution_summary(self.whole, self.extremes)

    def write(self, directory: str | Path, fmt: str = "csv",
              announce: Callable[[str], None] | None = None,
              summary: dict | None = None) -> list[Path]:
        """Every table and ``summary.json`` into ``directory``, whole or not at all (as
        :meth:`Solution.write`, which takes the same arguments)."""
        from ..model.outputs import staged_folder
        from .output import parquet_available
        if fmt not in ("csv", "parquet"):
            from ..model.errors import WorkbenchError
            raise WorkbenchError(f"format {fmt!r}: use csv or parquet")
        if fmt == "parquet":
            parquet_available()
        text = json.dumps(self.summary() if summary is None else summary, indent=2) + "\n"
        with staged_folder(directory, Solution.OUTPUT_KIND) as stage:
            _Tables(self, stage.path, fmt, announce).write()
            stage.file("summary.json").write_text(text)
        return [Path(directory) / f for f in (*(f"{n}.{fmt}" for n in Solution.FILES),
                                              "summary.json")]


class _Tables:
    """The seven tables of a streamed solve, written pass after pass into a folder."""

    def __init__(self, streamed: StreamedSolve, folder: Path, fmt: str, announce):
        self.s, self.folder, self.fmt, self.announce = streamed, folder, fmt, announce
        self.sinks: dict[str, CsvStream | ParquetStream] = {}

    def write(self) -> None:
        s = self.s
        s._gather()
        counts: dict[str, int] = {}
        k, passes = 0, 1
        try:
            while k < passes:       # pass k: block k of every table that has one
                for rows, sol in s.blocks(loads=k == 0 or k < len(s.scene.joints)):
                    if not counts:
                        counts = self._open(sol)
                        passes = max(counts.values())
                    reps = Repeats()    # the position column, formatted once per block
                    for name, blocks in counts.items():
                        if k < blocks:
                            self._put(name, k, rows, sol, reps)
                k += 1
        finally:
            for sink in self.sinks.values():
                sink.close()
        for name, blocks in counts.items():
            if blocks == 0 and self.fmt == "parquet":      # no rows: the one-shot's file
                write_parquet(columns_frame(self._empty(name)),
                              self.folder / f"{name}.parquet")

    def _empty(self, name: str) -> dict:
        from .longtable import concat_blocks
        return concat_blocks([], self.names[name])

    def _open(self, sol: Solution) -> dict[str, int]:
        """Open every table's file; the number of blocks of rows of each table."""
        n = self.s.positions.size
        scene = self.s.scene
        counts = {}
        self.names = {}
        for name in Solution.FILES:
            if name in Solution.LONG_TABLES:
                table = sol.long_table(name)
                names, blocks = table.columns, table.blocks
            elif name == "driver":
                names, blocks = self.s.whole._driver_names(), 1
            elif name == "frame":
                names, blocks = list(sol.columns(name)), 1
            else:
                names = list(sol.columns(name))
                blocks = len(sol.kin.dyads) if name == "dyads" else sum(
                    1 for j in scene.joints.values() if j.kind == "T")
            counts[name] = blocks
            self.names[name] = names
            path = self.folder / f"{name}.{self.fmt}"
            if self.fmt == "csv":
                self.sinks[name] = CsvStream(path, names, n * blocks, self.announce)
            elif blocks:
                self.sinks[name] = ParquetStream(path)
        return counts

    def _put(self, name: str, k: int, rows: slice, sol: Solution, reps: Repeats) -> None:
        """Block ``k`` of table ``name`` at the rows ``rows``."""
        sink = self.sinks[name]
        if name in Solution.LONG_TABLES:
            table = sol.long_table(name)
            if self.fmt == "csv":
                sink.block(table, k, reps)
            else:
                sink.frame(table.block_frame(k))
            return
        if name == "driver":
            w = self.s.whole
            cols = {"position": self.s.positions[rows],
                    w.driver_quantity: np.asarray(w.Me)[rows],
                    "singular": self.s.singular[rows],
                    "undefined_load": np.broadcast_to(w.undefined_load,
                                                      self.s.positions.shape)[rows]}
        else:
            cols = sol.columns(name)
            m = rows.stop - rows.start
            cols = {c: v[k * m:(k + 1) * m] for c, v in cols.items()}
        if self.fmt == "csv":
            sink.columns(cols, reps)
        else:
            sink.frame(columns_frame(cols))
