"""A run of stacked scenes solved on the compiled path (no numba here): each number that
differs from scene to scene handed to the kernels per scene, with each row's scene."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..blocks import Kept
from ..deadpoints import MANY_BELOW, SCREEN
from ..reactions import DriverReaction
from ..solved import Solved
from .choice import wanted
from .compose import Geometry, Plan, Refused, kept_sweep, solve_full, solve_lean
from .geometry import not_covered
from .short import NO_ANGLES, fused_arguments, fused_kernel
from .solve import KeptRun, guided_call, stats_in


def solve_run_stacked(stacker, structure, ks: np.ndarray, lo: int, hi: int,
                      counts: np.ndarray, positions: np.ndarray, kept: bool = False,
                      scratch: dict | None = None) -> Solved | KeptRun | None:
    """Scenes ``lo`` to ``hi - 1`` of ``stacker``
    (:class:`~kinetostatics.solver.stack.Stacker`) one after another, ``counts`` rows
    each at ``positions``, each dyad in its scene's assembly (``ks``: dyads x scenes),
    on the compiled path; or None (the path is off, or the run is not covered). Every row
    is the row its scene gives alone on this path, bit for bit: the same kernels, each
    number the scene's own (a ``resist`` or ``when = "resisting"`` load's threshold too:
    each scene's from its own sweep). A kernel that meets a row the numpy path must
    judge, or a sweep's top that moves its threshold, raises
    :class:`~kinetostatics.solver.fast.compose.Refused`: the run's scenes are then
    solved one by one, each as :func:`~kinetostatics.solve` solves it (not the run on
    the numpy path: its other scenes would differ from their solves in the last bits).

    The kernels read the geometry per scene
    (:meth:`~kinetostatics.solver.stack.Stacker.table`, a column per scene, gathered per
    tile), not per row (measured 2026-11-29: a stack's geometry per row, some 100
    numbers a row copied from arrays over the run, cost the RRR motion 107-226 ns a row
    against 23 with one scene's). ``kept``: only what the scenes' cut Solutions keep of
    their run (:class:`~kinetostatics.solver.fast.solve.KeptRun`: Me/Fe, the flags, the
    closeness to a dead centre), solved in the buffers of ``scratch`` (kept there for
    the group's next run); else the whole Solved, its scene and structure with each
    number over the rows (:meth:`~kinetostatics.solver.stack.Stacker.runs`)."""
    kernels = wanted(positions.size)
    if kernels is None:
        return None
    crank = stacker.base.driver.kind == "R"
    table = stacker.table(lo, hi, counts, positions, trig=False)
    if not_covered(table) is not None:
        return None
    owner = np.repeat(np.arange(hi - lo, dtype=np.int64), counts)
    plan = Plan(kernels, table, structure, ks[:, lo:hi], owner)
    if kept and crank:
        sweep = fused_kept(plan, positions.size, stacker.sweeps(lo, hi, counts, positions))
        if sweep is not None:
            return KeptRun(sweep, positions)
    if crank:       # (the composed kernels: the run's cos and sin over its rows)
        table.__dict__["driver_trig"] = stacker.trig_rows(lo, hi, positions)
    if kept:
        return KeptRun(solve_lean(plan, positions, scratch=scratch), positions)
    rows = (stacker.runs(lo, hi, counts, positions),
            replace(structure, assembly=tuple(np.repeat(k[lo:hi], counts) for k in ks)))
    return solve_full(plan, positions, rows=rows)


def solve_group_kept(stacker, structure, ks: np.ndarray, counts: np.ndarray,
                     positions: np.ndarray) -> tuple[Kept, np.ndarray | None] | None:
    """What the cut Solutions of every scene of ``stacker`` keep (``counts`` rows each at
    ``positions``, each dyad in its scene's assembly ``ks``), in one fused kernel call
    over all their rows, and the rows below the dead-point screen if the kernel told them
    (:func:`fused_screened`), or None: not a crank and one dyad the fused kernels cover
    (solved run by run, :func:`solve_run_stacked`). Each row is the one a
    run of its scenes gives (each row with its scene's geometry; every number the scene's
    own): the geometry and the plan are worked out once, not per run (measured
    2026-11-29, 1000 four-bars x 361 in 8 runs: 1.2 ms of plans and 1.7 ms of tables a
    call). Raises :class:`~kinetostatics.solver.fast.compose.Refused` as the run's kernel
    does (the caller then solves run by run)."""
    kernels = wanted(positions.size)
    if kernels is None or stacker.base.driver.kind != "R":
        return None
    m = counts.size
    # (the table's driver at the first scene's sweep: the kernel takes the rows' cos and
    # sin from sweeps(), and a driver over every row would work out their angles, a
    # fresh array of 8 bytes a row, for nothing)
    table = stacker.table(0, m, counts, stacker.base.driver.positions, trig=False)
    if not_covered(table) is not None:
        return None
    geometry = Geometry(table, structure, ks)
    # (kept for the dead-point screen's bound, screen.stack_tables: the same tables, one
    # table and geometry fewer; measured 2026-12-01, 1000 four-bars x 361, stack_bound
    # 0.43 -> 0.24 ms a call, best of 21 at a load of 7-8)
    stacker.kept["geometry"] = (structure, ks, geometry)
    plan = Plan(kernels, table, structure, ks, owners(counts), geometry)
    return fused_screened(plan, positions.size, stacker.sweeps(0, m, counts, positions),
                          _scratch(positions.size))


def owners(counts: np.ndarray) -> np.ndarray:
    """Each row's scene (counted from 0) of a stack of scenes of ``counts`` rows each,
    the last one kept: the same stack solved again (a design's generations, a study's
    loads) reuses it rather than fault in 8 fresh bytes a row (measured 2026-11-29, 1000
    four-bars x 361: 706 page faults a call). Writable, as every other caller's owners
    (``short.OWNERS``, a run's): a read-only array is another type to numba, and each
    fused kernel was compiled twice (measured 2026-11-30, an empty cache: 6-10 s of
    processor time each; the compiled tests 285 s of CPU against 244 s); the kernels
    only read it."""
    key = counts.tobytes()
    own = _OWNERS.get(key)
    if own is None:
        own = np.repeat(np.arange(counts.size, dtype=np.int64), counts)
        _OWNERS.clear()
        _OWNERS[key] = own
    return own


_OWNERS: dict[bytes, np.ndarray] = {}


def _scratch(n: int) -> np.ndarray:
    """An array of ``n`` doubles for a group's closeness to a dead centre, which no
    Solution keeps (its singular flags are made of it, its dead points screened from it):
    one given back by :func:`release` if it is long enough, else a new one (measured
    2026-11-29, 1000 four-bars x 361: 708 page faults a call, about 0.9 ms, faulting in
    a fresh one)."""
    try:
        buf = SCRATCH.pop()
    except IndexError:          # (none free: first call, or another thread has it)
        buf = None
    return buf[:n] if buf is not None and buf.size >= n else np.empty(n)


def release(kept: Kept) -> None:
    """Give back the closeness arrays of :func:`solve_group_kept`'s ``kept`` once its dead
    points are screened (nothing reads them after)."""
    for buf in kept.closeness2:
        buf = buf if buf.base is None else buf.base
        if len(SCRATCH) < SCRATCH_KEPT:
            SCRATCH.append(buf)


SCRATCH: list[np.ndarray] = []      # (list.pop and append: each thread its own array)
# the closeness arrays kept for the next group: a six-bar's two and a spare
SCRATCH_KEPT = 3


def fused_kept(plan: Plan, n: int, trig: tuple, close: np.ndarray | None = None
               ) -> Kept | None:
    """The :class:`~kinetostatics.solver.blocks.Kept` of :func:`fused_screened`."""
    got = fused_screened(plan, n, trig, close)
    return None if got is None else got[0]


def fused_screened(plan: Plan, n: int, trig: tuple, close: np.ndarray | None = None
                   ) -> tuple[Kept, np.ndarray | None] | None:
    """What a run's scenes keep (Me, the undefined rows, the closeness to a dead
    centre and the singular flags) of a crank and one dyad (not RTR; a crank and an RTR
    dyad first, :func:`guided_kept`), in one fused kernel over the run's ``n``
    rows (``trig``: the crank's cos and sin and where each scene's rows begin in them,
    :meth:`~kinetostatics.solver.stack.Stacker.sweeps`;
    :data:`~kinetostatics.solver.fast.fused_kernels.KEPT`: every kernel of a block in turn on
    each tile of 16 rows, ``jitbase.FUSED_TILE``, its values in one scratch array; the
    numbers of the kernels composed over blocks, bit for bit), with the rows whose
    closeness is below the dead-point screen (``deadpoints.SCREEN``), told by the kernel
    (numpy's ``flatnonzero(m2 < SCREEN**2)``, the same rows; None where more than one
    in ``MANY_BELOW`` are: ``deadpoints._candidates`` then scans the rows compiled, and
    for an RTR dyad); or None for another structure (solved
    by :func:`~kinetostatics.solver.fast.compose.solve_lean`). ``close``: the array the
    closeness is written to (a new one if None). Raises
    :class:`~kinetostatics.solver.fast.compose.Refused` as the composed kernels do."""
    fused = fused_kernel(plan)
    if fused is None:
        kept = guided_kept(plan, n, trig, close)
        return None if kept is None else (kept, None)
    kernel, order, known = fused
    drive, undefined = np.empty(n), np.zeros(n, dtype=bool)
    singular = np.empty(n, dtype=bool)
    close = np.empty(n) if close is None else close
    below = np.empty(n // MANY_BELOW + 1, dtype=np.int64)
    bad, k = kernel(0, n, plan.own, *trig, NO_ANGLES, *fused_arguments(plan, order, known),
                    drive, close, singular, undefined, SCREEN**2, below)
    if bad:
        raise Refused(bad)
    plan.check_swept()
    return (Kept(plan.structure, DriverReaction("R", drive), undefined, [close], [singular]),
            below[:k] if k <= below.size else None)


def guided_kept(plan: Plan, n: int, trig: tuple, close: np.ndarray | None = None
                ) -> Kept | None:
    """:func:`fused_kept` of a crank and one RTR dyad, maybe a second dyad (the slotted
    lever's and the shaper's structures) in the guide's kernel
    (:func:`~kinetostatics.solver.fast.solve.guided_call`: each tile one scene's rows,
    its geometry refilled where its scene changes; each row the numbers of its scene's
    own solve, bit for bit), or None for another structure. ``close``: the first dyad's
    closeness (a new array if None, and so the second's; else the second's one of
    :func:`_scratch` too, given back by :func:`release`: measured 2026-11-30, 1000
    shapers x 361, 706 page faults, about 2 ms a call, faulting in a fresh one)."""
    found = guided_call(plan)
    if found is None:
        return None
    kernel, rest, order = found
    drive, undefined = np.empty(n), np.zeros(n, dtype=bool)
    fresh = close is None
    closes = [np.empty(n) if fresh else close,
              *(np.empty(n) if fresh else _scratch(n) for _ in plan.dyads[1:])]
    bad = kernel(0, n, plan.own, *trig, NO_ANGLES, *rest, stats_in(plan.stats, order), drive,
                 *closes, undefined)
    if bad:
        raise Refused(bad)
    plan.check_swept()
    return kept_sweep(plan.structure, "R", drive, undefined, closes)
