"""The kinetostatic solve: scene -> structure -> kinematics -> loads -> reactions."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..model.errors import AssemblyError, WorkbenchError
from ..model.scene import load_scene
from ..results import Solution
from .blocks import LeanSolution, Sweep, Unblockable, blockable, blocks_of_sweep, solve_blocks
from .continuity import check_distinct, given_positions
from .deadpoints import dead_points_between_rows, dead_points_of_sweep, measure2
from .footprint import check_solve
from .friction import has_friction, solve_with_friction
from .kinematics import solve_kinematics
from .loads import applied_loads, inertia_loads, resultants
from .reactions import solve_reactions
from .structure import analyse
from .trap import FloatTrap, active, first_trapped, tame, trapped

_sum = np.add.reduce


def solve(scene: Any, positions: Any = None, *, allow_repeats: bool = False) -> Solution:
    """Kinematics, reactions in every joint and the equilibrating moment over the sweep.

    Parameters
    ----------
    scene : Scene, pathlib.Path, str or dict
        A loaded scene, a path to a ``.toml`` file, TOML text or a dict
        (``scene-format.md`` section 1).
    positions : array_like, optional
        Driver positions (deg or m) at which to solve the same mechanism, in any order
        (each listed once): each dyad keeps the assembly chosen at the scene's own first
        row. Default: the scene's sweep. The tables keep the given order; the summary,
        the continuity of angles and the dead points between rows follow increasing
        driver position.
    allow_repeats : bool
        Solve a sweep that lists a position more than once instead of refusing it (for
        the project's own callers, e.g. a simulation's record that passes a position
        twice, or a reference row prepended to a batch); each repeat is its own row.

    Returns
    -------
    Solution
        Arrays and lazily built tables: ``kinematics``, ``bodies``, ``reactions``,
        ``driver``, ``dyads``, ``sliders``, ``frame``, ``reduced`` and ``summary()``.

    Raises
    ------
    SceneError, StructureError, AssemblyError
        One-line messages for a bad scene (a position listed twice included), a chain
        that is not driver + dyads, a mechanism that cannot be assembled or is exactly
        singular somewhere.

    Examples
    --------
    >>> import kinetostatics as ks
    >>> sol = ks.solve(ks.example("four_bar"))
    >>> round(float(sol.driver["Me"].abs().max()), 1) > 0
    True
    """
    sc = load_scene(scene)
    if positions is not None:
        positions = given_positions(positions)
    if not allow_repeats:
        check_distinct(sc.driver.positions if positions is None else positions,
                       "deg" if sc.driver.kind == "R" else "m")
    # the assemblies are chosen at the scene's first row by the solve itself
    structure = analyse(sc, assemble=False)
    pos = sc.driver.positions if positions is None else positions
    check_solve(sc, pos.size)       # the peak memory known before it is spent
    sol = None
    if tame(sc, pos) and not has_friction(sc):
        sol = _trapped(sc, structure, pos, positions)
    if sol is None:
        sol = _checked(sc, structure, pos, positions)
    sol.release_loads()     # recomputed when asked for: no table needs them (memory)
    if "kin" in sol.__dict__:   # (a lean long sweep: released when solved again)
        sol.kin.release()   # what only the solve needed (the same, recomputed if asked)
    return sol


def _trapped(sc, structure, pos: np.ndarray, positions) -> Solution | None:
    """The solve with the finite checks left to the floating-point trap
    (:mod:`~kinetostatics.solver.trap`): its Solution when the trap stayed untouched,
    else None (the caller solves again, checked: the same numbers, and its refusals).
    The dead points between rows are screened outside the trap, as the checked solve
    screens them (their probes may meet singular rows on purpose)."""
    trap = FloatTrap()
    try:
        if blockable(sc, pos.size):
            with trapped(trap):
                long = _long_sweep(sc, structure, pos, trapped_road=True)
            return None if trap.hit else _lean(*long)
        with trapped(trap):
            kin = solve_kinematics(sc, structure, positions)
        if trap.hit:
            return None
        kin.between, kin.ends, kin.unassembled = dead_points_between_rows(
            kin.scene, kin.structure, kin)
        with trapped(trap):
            sol = _solve_loads(kin.scene, kin.structure, kin)
        return None if trap.hit else sol
    except Exception:       # (refused, or a block layout: the checked solve decides)
        return None


def _checked(sc, structure, pos: np.ndarray, positions) -> Solution:
    """The solve with every finite check made by looking at the numbers (a pass per
    kept array): one refusal names the first row that is not finite."""
    long = None
    if blockable(sc, pos.size):
        try:
            long = _long_sweep(sc, structure, pos, trapped_road=False)
        except (Unblockable, WorkbenchError, OverflowError, ZeroDivisionError):
            long = None     # solved in one pass below: its message names every row
    try:
        if long is None:
            kin = solve_kinematics(sc, structure, positions)
            kin.between, kin.ends, kin.unassembled = dead_points_between_rows(
                kin.scene, kin.structure, kin)
            sol = _solve_loads(kin.scene, kin.structure, kin)
            _check_finite(sol)
        else:
            sol = _lean(*long)
    except (OverflowError, ZeroDivisionError) as exc:
        raise AssemblyError(f"the scene's numbers overflow ({exc}); check its dimensions "
                            "and masses") from None
    return sol


def _long_sweep(sc, structure, pos: np.ndarray, trapped_road: bool) -> tuple:
    """A long sweep solved in blocks, lean (:class:`~kinetostatics.solver.blocks.Sweep`:
    the driver table's arrays and the dyads' closeness to a dead centre), with the
    function that solves it again in full (the same blocks and assemblies: the same
    numbers), on the same road, when another table asks."""
    full, st, part = blocks_of_sweep(sc, structure, pos)
    sweep = solve_blocks(pos.size, part, _solve_block, full, st, lean=True)
    solved = sweep.structure        # (the closure holds this, not the sweep's arrays)

    def again() -> Solution:
        args = (pos.size, part, _solve_block, full, solved)
        return first_trapped(solve_blocks, *args) if trapped_road else solve_blocks(*args)
    return full, sweep, again


def _lean(full, sweep: Sweep, again) -> Solution:
    """The long sweep's Solution, its dead points screened (as on its kinematics)."""
    positions = full.driver.positions
    dead = dead_points_of_sweep(full, sweep.structure, positions,
                                measure2(sweep.closeness2, positions.size))
    return LeanSolution.of(full, sweep, positions, dead, again)


def _solve_block(sc, structure, kin) -> Solution:
    """One block of rows (:func:`~kinetostatics.solver.blocks.solve_blocks`): loads and
    reactions from its kinematics, checked finite."""
    sol = _solve_loads(sc, structure, kin)
    if not active():        # (a trapped solve: its trap stands for the check)
        _check_finite(sol)
    kin.release()           # not gathered: the solve alone needed it
    return sol


def _solve_loads(sc, structure, kin) -> Solution:
    inertia = inertia_loads(sc, kin)
    applied, undefined = applied_loads(sc, kin)
    loads = applied + inertia
    if has_friction(sc):
        reactions, drive, fl, locking, at_rest = solve_with_friction(sc, kin, loads)
        return Solution(sc, structure, kin, loads + fl, reactions, drive,
                        np.broadcast_to(undefined, (kin.n,)) | at_rest, self_locking=locking)
    acc = resultants(loads, sc.bodies, kin.n)
    # the loads are let go before the reactions are solved (a lower peak of memory: at
    # large sizes fresh pages cost more than the arithmetic); Solution.loads computes them
    # again, with the same numbers, when asked for
    del loads, inertia, applied
    reactions, drive = solve_reactions(kin, acc)
    return Solution(sc, structure, kin, None, reactions, drive, undefined)


def _check_finite(sol: Solution) -> None:
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
