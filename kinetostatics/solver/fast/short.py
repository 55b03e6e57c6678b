"""A short sweep of one scene, a crank and one dyad, in ``solve_many``'s fused kernel:
what the driver table and the dead points read (no numba here: the kernels come in the
plan, loaded).

A single call's costs are mostly fixed ones at a few thousand rows (measured
2026-11-29, the four-bar at 2001 rows, processor time, each call after a garbage
collection as the bench times it: the composed kernels and their slab 420-450 us of
a 820 us call, Python and dispatch mostly; the fused kernel 130 us): one kernel writes
Me/Fe, the undefined rows and the closeness to a dead centre, the same numbers as the
composed kernels, bit for bit (:mod:`~kinetostatics.solver.fast.fused_kernels`). Its
arguments but the rows' are worked out once per scene object
(:func:`~kinetostatics.solver.memo.record_of`); the rest of the solve, which the other
tables read, is solved when one asks for it
(:class:`~kinetostatics.solver.blocks.LeanSolved`).
"""

from __future__ import annotations

import numpy as np

from ...model.scene import GROUND, Scene
from ..blocks import BLOCK_ROWS, Kept
from ..deadpoints import SCREEN
from ..memo import record_of
from ..reactions import DriverReaction
from .compose import Plan, Refused, turn
from .geometry import NO_SWEPT_LOADS

START = np.zeros(1, dtype=np.int64)     # where the one scene's rows begin in its cos, sin
NO_ANGLES = np.zeros(0)     # (the fused kernel reads the rows' cos and sin: none worked out)
NO_ANGLES.flags.writeable = False       # (read-only as a driver's angles: one signature)
OWNERS = np.zeros(2 * BLOCK_ROWS, dtype=np.int64)  # each row's scene: 0 (a short sweep)
NO_TRIG = np.zeros(0)     # (the guide's kernels given the angles: no cos, sin; writable,
#  as a stack's: one signature)
NO_STATS = np.zeros((1, 1, 2))          # (a body without swept loads: never written)
NO_ROWS = np.zeros(0, dtype=np.int64)   # (the rows below the screen: counted, not written;
#  writable, as a stack's: one signature)


def fused_sweep(kernels, scene: Scene, full: Scene, structure, geometry,
                positions: np.ndarray) -> Kept | None:
    """The :class:`~kinetostatics.solver.blocks.Kept` of ``full`` (``scene`` at
    ``positions``: itself for its own sweep) of fewer than ``2 * BLOCK_ROWS`` rows: Me,
    the undefined rows, the dyad's closeness to a dead centre and its singular flags
    from the fused kernel, with whether some row is below the dead-point screen
    (``Kept.screened``: no pass over the rows to tell it);
    or None: not a crank and one dyad the fused kernels cover, or a ``resist`` load
    (solved by the composed kernels). Raises
    :class:`~kinetostatics.solver.fast.compose.Refused` as they do."""
    record = record_of(scene)
    kept = record.get("fused")
    if kept is None or kept[0] is not structure or kept[1] is not kernels:
        kept = record["fused"] = (structure, kernels,
                                  fused_call(kernels, scene, structure, geometry))
    call = kept[2]
    if call is None:
        return None
    kernel, fixed = call
    cs, sn = scene_trig(kernels, record, scene) if full is scene else _trig(kernels, full)
    n = positions.size
    drive, close, undefined = np.empty(n), np.empty(n), np.zeros(n, dtype=bool)
    singular = np.empty(n, dtype=bool)
    bad, below = kernel(0, n, OWNERS, cs, sn, START, NO_ANGLES, *fixed, drive, close, singular,
                        undefined, SCREEN**2, NO_ROWS)
    if bad:
        raise Refused(bad)
    return Kept(structure, DriverReaction("R", drive), undefined, [close], [singular],
                screened=(None, below > 0))


def fused_call(kernels, scene: Scene, structure, geometry) -> tuple | None:
    """The fused kernel of ``scene`` (:func:`fused_kernel`) and its arguments after the
    rows' cos, sin and where they begin, before its outputs (as
    :func:`~kinetostatics.solver.fast.stacked.fused_kept` gives them for a run), or None
    for another structure or ``resist`` loads (their statistics are written per solve)."""
    plan = Plan(kernels, scene, structure, structure.assembly, geometry=geometry)
    found = None if plan.swept else fused_kernel(plan)
    if found is None:
        return None
    kernel, order, known = found
    return kernel, fused_arguments(plan, order, known)


def fused_arguments(plan: Plan, order: tuple, known: list) -> tuple:
    """The fused kernel's arguments after the rows' cos, sin and where they begin, before
    its outputs: the driver's and the dyad's geometry, whether each outer joint's known
    body is the driver, and each body's loads, swept loads and their statistics (bodies
    in ``order``: the driver, the dyad's first, its second)."""
    gy, gys, _ = plan.dyads[0]
    dname = order[0]
    loads = [plan.loads[b] for b in order]
    swept = [plan.swept.get(b, NO_SWEPT_LOADS) for b in order]
    return (*plan.driver, plan.speed, plan.accel, gy, gys, known[0] == dname,
            known[1] == dname, tuple(g for g, _, _ in loads), tuple(gs for _, gs, _ in loads),
            tuple(p for _, _, p in loads), tuple(sw[0] for sw in swept),
            tuple(sw[1] for sw in swept), tuple(len(sw[2]) for sw in swept),
            tuple(plan.stats.get(b, NO_STATS) for b in order))


def fused_kernel(plan: Plan) -> tuple | None:
    """The fused kernel of a plan's crank and one dyad
    (:data:`~kinetostatics.solver.fast.fused_kernels.KEPT`: every kind but RTR), the
    bodies in its order (the driver, the dyad's first, its second) and each outer
    joint's known body; or None: another structure (more bodies, an outer joint on a body
    other than the ground or the driver)."""
    if not plan.crank or len(plan.dyads) != 1:
        return None
    from .fused_kernels import KEPT  # (plan.k given: numba loaded, its cache settled)
    dyad = plan.dyads[0][2]
    kernel = KEPT.get(dyad.kind)
    dname = plan.scene.driver.body
    order = (dname, *dyad.bodies)
    known = [j.other(b) for j, b in zip(dyad.outer, dyad.bodies, strict=True)]
    if (kernel is None or len(plan.bodies) != 3 or set(plan.bodies) != set(order)
            or not set(known) <= {GROUND, dname}):
        return None
    return kernel, order, known


def scene_trig(kernels, record: dict, scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """The cos and sin of the scene's own sweep (the compiled path's: :func:`_trig`), kept
    in its record."""
    trig = record.get("trig")
    if trig is None:
        trig = record["trig"] = _trig(kernels, scene)
    return trig


def _trig(kernels, scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """The compiled path's cos and sin of the scene's crank angles
    (:func:`~kinetostatics.solver.fast.compose.turn`), writable: the arrays ``solve_many``
    hands the kernel (one compiled signature)."""
    angles = scene.driver.angles
    cs, sn = np.empty(angles.size), np.empty(angles.size)
    turn(kernels, angles, cs, sn)
    return cs, sn
