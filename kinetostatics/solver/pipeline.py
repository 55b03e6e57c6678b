"""The kinetostatic solve: scene -> structure -> kinematics -> loads -> reactions.

Every solve takes one road, a :class:`Sweep`: it knows whether its rows are solved in
blocks (:mod:`~kinetostatics.solver.blocks`: a long sweep, every load elementwise, no
joint friction) or in one pass, and how they are checked: left to the floating-point
trap (:mod:`~kinetostatics.solver.trap`: tame numbers, no friction), then, if the trap
was touched or the trapped pass refused, by looking at the numbers (one refusal naming
the first row that is not finite). A block of rows is solved by :func:`solve_rows`
(loads and reactions from the block's kinematics). The solve gives arrays
(:class:`~kinetostatics.solver.solved.Solved`, or a lean
:class:`~kinetostatics.solver.blocks.LeanSolved`); :func:`kinetostatics.solve` wraps them
in a :class:`~kinetostatics.results.Solution`.
"""

from __future__ import annotations

import math
from functools import cached_property
from typing import Any

import numpy as np

from ..common.lazy import moved_names
from ..model.errors import AssemblyError, WorkbenchError
from ..model.scene import load_scene
from .blocks import Kept, LeanSolved, Unblockable, blockable, blocks_of_sweep, solve_blocks
from .continuity import check_distinct, given_positions
from .deadpoints import dead_points_between_rows, dead_points_of_sweep, measure2
from .fast import path_setting, solve_compiled
from .footprint import check_solve
from .friction import has_friction, solve_with_friction
from .kinematics import solve_kinematics
from .loads import SweepTops, applied_loads, inertia_loads, resultants
from .memo import record_of
from .reactions import solve_reactions
from .solved import Solved
from .structure import Structure, analyse
from .trap import FloatTrap, active, first_trapped, tame, trapped

_sum = np.add.reduce


def solve_arrays(scene: Any, positions: Any = None, *,
                 allow_repeats: bool = False) -> Solved | LeanSolved:
    """The arrays of :func:`kinetostatics.solve`, which takes the same arguments, raises
    the same errors and wraps the arrays in a :class:`~kinetostatics.results.Solution`:
    kinematics, reactions in every joint and the equilibrating moment over the sweep."""
    return Sweep(scene, positions, allow_repeats).solve()


class Sweep:
    """One scene over its driver positions, and how they are solved.

    Parameters
    ----------
    scene : Scene, pathlib.Path, str or dict
        What :func:`~kinetostatics.model.scene.load_scene` reads.
    positions : array_like, optional
        Driver positions (deg or m), in any order; default: the scene's sweep. Each dyad
        keeps the assembly chosen at the scene's own first row.
    allow_repeats : bool
        Solve a sweep that lists a position more than once instead of refusing it.

    Attributes
    ----------
    blocked : bool
        Solved in blocks of rows, and streamed so
        (:func:`~kinetostatics.solver.blocks.blockable`).
    parted : bool
        Solved in blocks of rows (a load measured against the sweep's top as well).
    trusty : bool
        Checked by the floating-point trap first (tame numbers, no joint friction).
    """

    def __init__(self, scene: Any, positions: Any = None, allow_repeats: bool = False,
                 budget: bool = True):
        sc = load_scene(scene)
        if positions is not None:
            positions = given_positions(positions)
        if not allow_repeats:
            own = positions is None
            record = record_of(sc) if own else {}
            # (the scene's own sweep: checked once, or known to increase as it was read)
            if not record.get("distinct") and not (own and sc.driver.increasing):
                q = "angle" if sc.driver.kind == "R" else "length"
                check_distinct(sc.driver.positions if own else positions,
                               sc.units.unit(q), sc.units.file_factor(q))
                record["distinct"] = True
        self.scene = sc
        # the assemblies are chosen at the scene's first row by the solve itself
        self.structure = structure_of(sc)
        self.given = positions
        self.positions = sc.driver.positions if positions is None else positions
        if budget:      # (False: the caller checks its own estimate, e.g. a streamed write)
            check_solve(sc, self.positions.size)    # the peak memory known before it is spent
        self.blocked = blockable(sc, self.positions.size)
        # (a load whose threshold is the sweep's top solved in blocks too, the tops met
        # as they go, SweepTops; not streamed: a table's block alone does not know them)
        self.parted = self.blocked or blockable(sc, self.positions.size, tops=True)

    @cached_property
    def trusty(self) -> bool:
        """Checked by the floating-point trap first: tame numbers, no joint friction (told
        when the numpy path solves: the compiled path does not ask)."""
        return tame(self.scene, self.positions) and not has_friction(self.scene)

    def solve(self) -> Solved | LeanSolved:
        """The solve: trapped first where the numbers are tame, else (or if the trap was
        touched) checked. The compiled path (:mod:`~kinetostatics.solver.fast`) goes
        first when it is wanted for this many rows and covers the scene."""
        # (the numpy path asked for: not the compiled path's look at whether its kernels
        # cover the scene, 25-30 us a call; measured 2026-11-30, slider-crank, 2001 rows)
        sol = None if path_setting() == "numpy" else solve_compiled(
            self.scene, self.structure, self.positions, self.given is not None)
        if sol is not None:
            return sol
        sol = self.trapped() if self.trusty else None
        if sol is None:
            sol = self.checked()
        if isinstance(sol, Solved):
            sol.kin.release()   # what only the solve needed (the same, recomputed if asked)
            if self.assembled is self.structure:
                # each dyad's assembly, chosen at the scene's first row: the next solve
                # of this scene object starts from it (assembled)
                record_of(self.scene)["assembled"] = (self.structure, sol.structure)
        return sol

    @cached_property
    def assembled(self) -> Structure:
        """The structure with each dyad's assembly when an earlier solve of this scene
        object chose them (the same: a function of the scene alone, at its first row),
        else :attr:`structure` (chosen by the solve). Saves a solve of the numpy path
        its choice (measured 2026-11-29, four-bar at 2001 rows: some 40-130 us of
        processor time of a call after a garbage collection)."""
        kept = record_of(self.scene).get("assembled")
        return kept[1] if kept is not None and kept[0] is self.structure else self.structure

    def trapped(self) -> Solved | LeanSolved | None:
        """The solve with the finite checks left to the floating-point trap: its arrays
        when the trap stayed untouched, else None (the caller solves again, checked: the
        same numbers, and its refusals). The dead points between rows are screened
        outside the trap, as the checked solve screens them (their probes may meet
        singular rows on purpose)."""
        sc, structure = self.scene, self.assembled
        trap = FloatTrap()
        try:
            if self.parted:
                with trapped(trap):
                    long = self.in_blocks(trapped_road=True)
                return None if trap.hit else _lean(*long)
            with trapped(trap):
                kin = solve_kinematics(sc, structure, self.given)
            if trap.hit:
                return None
            kin.between, kin.ends, kin.unassembled = dead_points_between_rows(
                kin.scene, kin.structure, kin)
            with trapped(trap):
                sol = _solve_loads(kin.scene, kin.structure, kin)
            return None if trap.hit else sol
        except Exception:       # (refused, or a block layout: the checked solve decides)
            return None

    def checked(self) -> Solved | LeanSolved:
        """The solve with every finite check made by looking at the numbers (a pass per
        kept array): one refusal names the first row that is not finite."""
        long = None
        if self.parted:
            try:
                long = self.in_blocks(trapped_road=False)
            except (Unblockable, WorkbenchError, OverflowError, ZeroDivisionError):
                long = None     # solved in one pass below: its message names every row
        try:
            if long is None:
                kin = solve_kinematics(self.scene, self.assembled, self.given)
                kin.between, kin.ends, kin.unassembled = dead_points_between_rows(
                    kin.scene, kin.structure, kin)
                sol = _solve_loads(kin.scene, kin.structure, kin)
                _check_finite(sol)
            else:
                sol = _lean(*long)
        except (OverflowError, ZeroDivisionError) as exc:
            raise AssemblyError(f"the scene's numbers overflow ({exc}); check its "
                                "dimensions and masses") from None
        return sol

    def lean_in_blocks(self) -> LeanSolved:
        """A blocked sweep (:attr:`blocked`) solved lean in blocks on the checked road, with
        no fallback to one pass (a caller that streams its tables block by block:
        :mod:`kinetostatics.results.streamed`); a refused block is refused here."""
        try:
            return _lean(*self.in_blocks(trapped_road=False))
        except (OverflowError, ZeroDivisionError) as exc:
            raise AssemblyError(f"the scene's numbers overflow ({exc}); check its "
                                "dimensions and masses") from None

    def in_blocks(self, trapped_road: bool) -> tuple:
        """The sweep solved in blocks, lean (:class:`~kinetostatics.solver.blocks.Kept`:
        the driver table's arrays and the dyads' closeness to a dead centre), with the
        function that solves it again in full (the same blocks and assemblies: the same
        numbers), on the same road, when another table asks."""
        pos = self.positions
        tops = None if self.blocked else SweepTops()
        full, st, part = blocks_of_sweep(self.scene, self.structure, pos, tops)
        kept = solve_blocks(pos.size, part, solve_block, full, st, lean=True)
        if tops is not None and not tops.settle():
            # (a row's flag would differ: one pass decides, on either road)
            self.parted = False
            raise Unblockable("tops")
        if tops is not None:
            # (the sweep's tops, settled: whoever solves its blocks again finds them,
            # blocks_of_sweep; the whole sweep's scene, made for these rows or their own)
            full.__dict__["sweep_tops"] = tops
        solved = kept.structure     # (the closure holds this, not the kept arrays)

        def again() -> Solved:
            args = (pos.size, part, solve_block, full, solved)
            return first_trapped(solve_blocks, *args) if trapped_road else solve_blocks(*args)
        return full, kept, again


def structure_of(scene) -> Structure:
    """The scene's decomposition (:func:`~kinetostatics.solver.structure.analyse`, no
    assemblies), worked out once per scene object
    (:func:`~kinetostatics.solver.memo.record_of`): the same object at each solve of the
    scene, so that what is kept for it is found again."""
    record = record_of(scene)
    structure = record.get("structure")
    if structure is None:
        structure = record["structure"] = analyse(scene, assemble=False)
    return structure


def _lean(full, kept: Kept, again) -> LeanSolved:
    """The long sweep's lean arrays, its dead points screened (as on its kinematics)."""
    positions = full.driver.positions
    dead = dead_points_of_sweep(full, kept.structure, positions,
                                measure2(kept.closeness2, positions.size))
    return LeanSolved(full, kept, positions, dead, again)


def solve_block(sc, structure, kin) -> Solved:
    """One block of rows (:func:`~kinetostatics.solver.blocks.solve_blocks`): loads and
    reactions from its kinematics, checked finite."""
    sol = solve_rows(sc, structure, kin)
    if not active():        # (a trapped solve: its trap stands for the check)
        _check_finite(sol)
    kin.release()           # not gathered: the solve alone needed it
    return sol


def solve_rows(sc, structure, kin) -> Solved:
    """The loads and reactions of the rows of ``kin`` (a whole sweep, a block of it or a
    stack of scenes): the place where rows are solved once their motion is known."""
    return _solve_loads(sc, structure, kin)


def _solve_loads(sc, structure, kin) -> Solved:
    friction = has_friction(sc)
    # (the loads for their resultants alone: each cog's arm worked out once for its two
    # loads, applied_loads; with friction they are kept, as the tables read them)
    arms: dict | None = None if friction else {}
    inertia = inertia_loads(sc, kin, arms)
    applied, undefined = applied_loads(sc, kin, arms)
    loads = applied + inertia
    if friction:
        reactions, drive, fl, locking, at_rest = solve_with_friction(sc, kin, loads)
        return Solved(sc, structure, kin, loads + fl, reactions, drive,
                      np.broadcast_to(undefined, (kin.n,)) | at_rest, self_locking=locking)
    acc = resultants(loads, sc.bodies, kin.n)
    # the loads are let go before the reactions are solved (a lower peak of memory: at
    # large sizes fresh pages cost more than the arithmetic); Solution.loads computes them
    # again, with the same numbers, when asked for
    del loads, inertia, applied
    reactions, drive = solve_reactions(kin, acc)
    return Solved(sc, structure, kin, None, reactions, drive, undefined)


def _check_finite(sol: Solved) -> None:
    """Never a silent NaN: every number behind every table is finite, or the scene is
    refused naming the first position where it is not.

    Checked: each body's motion (cos, sin, omega, alpha, origin position, velocity and
    acceleration: every point's x, y, vx, vy, ax, ay and the bodies table follow from
    them), each dyad's transmission measure, every reaction (Fx, Fy, and N, M of a
    prismatic joint) and Me/Fe. Rows flagged ``self_locking`` (joint friction locks the
    mechanism) hold NaN in Me/Fe and the reactions by the contract: they are left out.
    """
    n = sol.positions.size
    free = [getattr(b, f) for b in sol.kin.bodies.values()
            for f in ("cos", "sin", "omega", "alpha", "ox", "oy", "vx", "vy", "ax", "ay")]
    free += [d.closeness2 for d in sol.kin.dyads]
    loads = [sol.Me]
    for r in sol.joint_reactions.values():
        loads += [v for v in (r.fx, r.fy, r.N, r.M) if v is not None]
    locked = sol.self_locking     # rows where friction locks: Me and reactions are NaN
    if locked is not None and locked.any():
        loads = [np.where(locked, 0.0, np.broadcast_to(a, (n,))) for a in loads]
    seen: set[int] = set()
    for a in free + loads:
        # one summing pass per array, each array once (a NaN or an infinity makes the sum
        # non-finite); a sum that overflows with every value finite is looked at value by
        # value
        if isinstance(a, float | int):
            if math.isfinite(a):
                continue
        elif id(a) in seen or math.isfinite(_sum(a, axis=None)):
            seen.add(id(a))
            continue
        bad = np.flatnonzero(~np.isfinite(np.broadcast_to(a, (n,))))
        if bad.size:
            unit = "deg" if sol.scene.driver.kind == "R" else "m"
            raise AssemblyError(
                "the solution overflows (numbers too large or a degenerate geometry) at "
                f"driver position {sol.positions[bad[0]]:g} {unit}; check the scene's "
                "dimensions")


def _trapped(sc, structure, pos: np.ndarray, positions) -> Solved | LeanSolved | None:
    """:meth:`Sweep.trapped` of ``sc`` at ``pos`` (``positions``: as given, or None)."""
    sweep = Sweep.__new__(Sweep)
    sweep.scene, sweep.structure, sweep.given, sweep.positions = sc, structure, positions, pos
    sweep.blocked, sweep.trusty = blockable(sc, pos.size), True
    sweep.parted = sweep.blocked or blockable(sc, pos.size, tops=True)
    return sweep.trapped()


# kinetostatics.solver.pipeline.solve, deprecated: the public solve is
# kinetostatics.solve (the results wrap the arrays); the package root stands above every
# subpackage, so no import runs upward
__getattr__ = moved_names(__name__, {"solve": ("kinetostatics", "solve")})
