"""A scene solved on the compiled path, or None for the numpy path (no numba here)."""

from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace

import numpy as np

from ...model.scene import GROUND, Scene
from ..blocks import BLOCK_ROWS, Kept, LeanSolved
from ..deadpoints import SCREEN, dead_points_of_sweep, measure2
from ..kinematics import choose_assembly, with_positions
from ..memo import record_of
from ..reactions import DriverReaction
from ..solved import Solved
from .choice import wanted
from .compose import (
    ROWS,
    Geometry,
    Plan,
    Refused,
    Unwrapped,
    block_reactions,
    check_stats,
    cut_rows,
    driver_input,
    fresh_stats,
    kept_sweep,
    solve_arrays,
    solve_full,
    solve_lean,
)
from .geometry import NO_SWEPT_LOADS, not_covered
from .layout import CL2, I_SFIRST
from .loader import kernels as loaded_kernels
from .short import (
    NO_ROWS,
    NO_STATS,
    NO_TRIG,
    OWNERS,
    START,
    fused_arguments,
    fused_call,
    fused_kernel,
    fused_sweep,
)


def solve_compiled(scene: Scene, structure, positions: np.ndarray, given: bool
                   ) -> Solved | None:
    """``scene`` at ``positions`` (``given``: not the scene's own) on the compiled path,
    or None: the path is off or not wanted for this many rows
    (:func:`~kinetostatics.solver.fast.choice.wanted`), the scene is not covered
    (:func:`~kinetostatics.solver.fast.geometry.not_covered`), or a kernel met a row the
    numpy path must judge (it refuses it with its message, or solves it)."""
    n = positions.size
    kept = record_of(scene).get("fast")     # (kept for a scene the kernels cover)
    if (kept is None or kept[0] is not structure) and not_covered(scene) is not None:
        return None
    kernels = wanted(n)
    if kernels is None:
        return None
    structure, geometry = _assembled(scene, structure)
    full = with_positions(scene, positions) if given else scene
    try:
        if n >= 2 * BLOCK_ROWS:
            sweep = fused_blocks(kernels, scene, full, structure, geometry, positions)
            if sweep is None:
                sweep = guided_blocks(kernels, full, structure, geometry, positions)
            if sweep is None:
                sweep = solve_lean(Plan(kernels, full, structure, structure.assembly,
                                        geometry=geometry), positions)
        else:
            sweep = fused_sweep(kernels, scene, full, structure, geometry, positions)
            if sweep is None:       # (an RTR dyad first: per block of rows, as a long one)
                sweep = guided_blocks(kernels, full, structure, geometry, positions)
        if sweep is not None:
            def again() -> Solved:
                return solve_full(Plan(kernels, full, structure, structure.assembly,
                                       geometry=geometry), positions)
            m2 = sweep.measure2
            dead = dead_points_of_sweep(full, structure, positions,
                                        measure2(sweep.closeness2, n) if m2 is None else m2,
                                        sweep.screened)
            sol = LeanSolved(full, sweep, positions, dead, again)
        else:
            plan = Plan(kernels, full, structure, structure.assembly, geometry=geometry)
            buf = solve_arrays(plan, positions)
            # (dead_points_between_rows of the kinematics the arrays make: their
            # closeness to a dead centre, d[CL2], is each dyad's closeness2)
            dead = dead_points_of_sweep(full, structure, positions,
                                        measure2([d[CL2] for d in buf["d"]], n))
            sol = Unwrapped(plan, positions, buf, dead)
    except Refused:
        return None
    sol.path = "fast"       # (a LeanSolved's: its full solve's is set by _solution)
    return sol


def fused_blocks(kernels, scene: Scene, full: Scene, structure, geometry,
                 positions: np.ndarray) -> Kept | None:
    """The :class:`~kinetostatics.solver.blocks.Kept` of a long sweep of a crank and one
    dyad (``full``: ``scene`` at ``positions``) from ``solve_many``'s fused kernel
    (:func:`~kinetostatics.solver.fast.short.fused_call`): Me, the undefined rows and
    the dyad's closeness to a dead centre, the numbers of the composed kernels bit for
    bit (the same row helpers in the same order). The crank's cos and sin are worked out
    in the kernel, tile by tile, the compiled path's
    (:func:`~kinetostatics.solver.fast.trig_kernels.sincos_rows`; called per ``OWNERS``
    rows: measured 2026-11-29, the slider-crank at 1e6 rows, 31 calls instead of 245 of
    the kernel per block of 4096 rows and 490 of numpy's cos and sin). None for another
    structure or ``resist`` loads
    (:func:`~kinetostatics.solver.fast.compose.solve_lean` solves those). Raises
    :class:`~kinetostatics.solver.fast.compose.Refused` as the composed kernels do."""
    found = _fused(kernels, scene, structure, geometry)
    if found is None:
        return None
    kernel, fixed, plan = found
    n = positions.size
    # (the crank's cos and sin worked out per tile into the kernel's scratch, not kept:
    # the tables' pass works them out again, the same doubles, if a table asks)
    drive, close, undefined = np.empty(n), np.empty(n), np.zeros(n, dtype=bool)
    singular = np.empty(n, dtype=bool)
    bad, below = by_tiles(kernel, full.driver, OWNERS.size, fixed,
                          (drive, close, singular, undefined), (SCREEN**2, NO_ROWS))
    if bad:
        raise Refused(bad)
    if plan is not None:
        plan.check_swept()
    # (the singular flags and whether some row is below the dead-point screen told by the
    # kernel: no pass over the rows for them)
    return Kept(structure, DriverReaction("R", drive), undefined, [close], [singular],
                screened=(None, below > 0))


def by_tiles(kernel, driver, w: int, fixed: tuple, outs: tuple, tail: tuple
             ) -> tuple[int, int]:
    """``kernel`` (a one-scene kernel of the crank's angles, ``fused_call``'s) over the
    driver's rows, ``w`` rows a call, each call given its
    rows' slices of ``outs`` and then ``tail``; returns the count of rows refused and the
    count of rows below the dead-point screen. Each tile's angles
    read-only, as the driver makes them and NO_ANGLES (one compiled signature): the
    driver's own once made, else worked out per tile into one scratch array
    (:meth:`~kinetostatics.model.scene.Driver.angles_into`, the same doubles), no array
    of all the rows' radians made."""
    n = driver.positions.size
    scratch = np.empty(min(w, n))
    bad = below = 0
    for lo in range(0, n, w):
        at = slice(lo, min(lo + w, n))
        b, k = kernel(0, at.stop - lo, OWNERS, NO_TRIG, NO_TRIG, START,
                      driver.angles_into(at, scratch), *fixed, *(o[at] for o in outs), *tail)
        bad += b
        below += k
    return bad, below


_TRIG: dict[str, bool] = {}


def kernel_trig() -> bool:
    """Whether the C library's cos and sin of an angle in a compiled loop
    (:func:`~kinetostatics.solver.fast.trig_kernels.libm_rows`, fused by LLVM into one
    ``sincos``) are numpy's bit for bit here: checked once a process on the angles of
    :func:`trig_probes`. The dead-point screen's probes take numpy's cos and sin, and
    in one compiled call the C library's where they are numpy's
    (:func:`~kinetostatics.solver.fast.screen.stack_probe`); the sweeps' kernels take the
    compiled path's own (:mod:`~kinetostatics.solver.fast.trig_kernels`)."""
    if "same" not in _TRIG:
        from .trig_kernels import libm_rows  # (numba loaded: kernels given)
        x = trig_probes()
        cs, sn = np.empty_like(x), np.empty_like(x)
        libm_rows(x, cs, sn)
        with np.errstate(invalid="ignore"):     # (infinities among the probes)
            want = np.cos(x).tobytes(), np.sin(x).tobytes()
        _TRIG["same"] = (cs.tobytes(), sn.tobytes()) == want
    return _TRIG["same"]


def trig_probes(n: int = 20_000) -> np.ndarray:
    """Angles (rad) whose cos and sin :func:`kernel_trig` checks: a turn (``n + 1``
    rows), ``n`` each within +-8, +-1e3 and +-1e9, multiples of
    pi / 4, and zeros, subnormals, the largest doubles, infinities and NaN. Read-only,
    as a driver's angles."""
    rng = np.random.default_rng(31)
    special = np.array([0.0, -0.0, 5e-324, 2.2e-308, 1e-8, 1.7976931348623157e308,
                        -1.7976931348623157e308, np.inf, -np.inf, np.nan])
    x = np.concatenate([np.linspace(0.0, 2.0 * np.pi, n + 1),
                        *(rng.uniform(-r, r, n) for r in (8.0, 1e3, 1e9)),
                        np.pi / 4 * np.arange(-64, 65), special])
    x.flags.writeable = False
    return x


def _fused(kernels, scene: Scene, structure, geometry) -> tuple | None:
    """The fused kernel of ``scene``, its arguments (but the rows' cos, sin and where
    they begin, and its outputs) and the plan whose ``resist`` (``when = "resisting"``)
    statistics they hold (None without such loads: the arguments are then kept per scene
    object, as a short sweep's); or None for another structure. A scene with such loads
    gets a plan per solve: the statistics are each sweep's own, checked after the sweep
    (:meth:`~kinetostatics.solver.fast.compose.Plan.check_swept`)."""
    record = record_of(scene)
    kept = record.get("fused")
    if kept is None or kept[0] is not structure or kept[1] is not kernels:
        kept = record["fused"] = (structure, kernels,
                                  fused_call(kernels, scene, structure, geometry))
    if kept[2] is not None:
        return (*kept[2], None)
    if not geometry.swept:
        return None         # (another structure)
    plan = Plan(kernels, scene, structure, structure.assembly, geometry=geometry)
    found = fused_kernel(plan)
    if found is None:
        return None
    kernel, order, known = found
    return kernel, fused_arguments(plan, order, known), plan


def guided_blocks(kernels, full: Scene, structure, geometry, positions: np.ndarray
                  ) -> Kept | None:
    """The :class:`~kinetostatics.solver.blocks.Kept` of a long sweep of a crank and one
    RTR dyad (the slotted lever's structure), or of a crank, one RTR dyad and a second
    dyad of another kind (the shaper's), from the kernels of
    :mod:`~kinetostatics.solver.fast.guide_kernels`, the numbers of the composed kernels
    bit for bit; or None for another structure. One kernel call over the sweep works
    out, tile by tile, the crank's cos and sin (the compiled path's,
    :func:`~kinetostatics.solver.fast.trig_kernels.sincos_rows`), the guide's angle's
    cos and sin, then the rest. Raises
    :class:`~kinetostatics.solver.fast.compose.Refused` as the composed kernels do."""
    found = _guided(kernels, full, structure, geometry)
    if found is None:
        return None
    kernel, rest, order = found
    stats = fresh_stats(geometry.swept, 1)
    n = positions.size
    drive, undefined = np.empty(n), np.zeros(n, dtype=bool)
    close = [np.empty(n) for _ in geometry.dyads]
    # (one call, no scratch rows: measured 2026-11-30, guided_blocks alone, ns a row,
    # processor time, best of 7, three alternating pairs of processes at a load of 6-7:
    # shaper 144-155 at 2e5 rows, 151-158 at 1e6 against 160-191 and 171-183 in two
    # kernels per block, numpy's cos and sin between them; slotted lever 93-96, 99-107
    # against 107-114, 109-120)
    # (the driver's angles, all the rows': measured 2026-11-30, the shaper at 1e6 rows,
    # processor time, 16 alternating pairs, calls of 2**16 or 2**18 rows given each
    # tile's radians, by_tiles, cost 6 % more than the one call)
    bad = kernel(0, n, OWNERS, NO_TRIG, NO_TRIG, START, full.driver.angles, *rest,
                 stats_in(stats, order), drive, *close, undefined)
    if bad:
        raise Refused(bad)
    check_stats(geometry.swept, stats)
    return kept_sweep(structure, "R", drive, undefined, close, measure=True)


def _guided(kernels, full: Scene, structure, geometry) -> tuple | None:
    """:func:`guided_call`'s kernel, its arguments and the bodies in its order (the swept
    loads' statistics, each sweep's own, :func:`~kinetostatics.solver.fast.compose.fresh_stats`,
    given per call: :func:`stats_in`); or None for another structure: worked out
    once per scene object, structure and geometry (:func:`~kinetostatics.solver.memo.record_of`;
    the same arguments, each a function of these alone)."""
    record = record_of(full)
    kept = record.get("guided")
    if kept is None or kept[0] is not structure or kept[1] is not kernels or (
            kept[2] is not geometry):
        plan = Plan(kernels, full, structure, structure.assembly, geometry=geometry)
        kept = record["guided"] = (structure, kernels, geometry, guided_call(plan))
    return kept[3]


def stats_in(stats: dict, order: tuple) -> tuple:
    """The swept loads' statistics (:func:`~kinetostatics.solver.fast.compose.fresh_stats`)
    of the bodies in the guide kernel's ``order`` (:func:`guided_call`'s), the guide
    kernel's last argument before its outputs."""
    return tuple(stats.get(b, NO_STATS) for b in order)


def guided_call(plan: Plan) -> tuple | None:
    """The guide's kernel (:func:`~kinetostatics.solver.fast.guide_kernels.rtr_kept`, or
    for a second dyad one of ``AFTER_RTR``), its arguments (but the rows' cos and sin,
    where each scene's begin, the crank's angles, the swept loads' statistics,
    :func:`stats_in`, and the outputs) and the bodies in its order, for a crank and one RTR
    dyad whose outer joints are on the ground or the crank, and maybe a second dyad (not
    RTR) whose outer joints are on the ground, the crank or the RTR dyad's bodies; else
    None. One scene's plan, or a stack's (each table with its ``gs``: 1, a column per
    scene; the kernels refill a tile's geometry where its scene changes)."""
    if not plan.crank or len(plan.dyads) not in (1, 2) or plan.dyads[0][2].kind != "RTR":
        return None
    from .guide_kernels import AFTER_RTR, rtr_kept  # (numba loaded: plan.k given)
    gy, gys, dyad = plan.dyads[0]
    dname = plan.scene.driver.body
    order = (dname, *dyad.bodies)
    known = [j.other(b) for j, b in zip(dyad.outer, dyad.bodies, strict=True)]
    gd, gds = plan.driver
    if not set(known) <= {GROUND, dname} or (gy[I_SFIRST] != 0.0).any():
        return None         # (the kernels pin the guide first: guide_kernels._pin)
    first = (gd, gds, plan.speed, plan.accel, gy, gys, known[0] == dname, known[1] == dname)
    kernel, second = rtr_kept, ()
    if len(plan.dyads) == 2:
        gz, gzs, dyad = plan.dyads[1]
        kernel = AFTER_RTR.get(dyad.kind)
        which = (GROUND, *order)        # (the kernel's codes: 0 the ground, 1 the crank...)
        known = [j.other(b) for j, b in zip(dyad.outer, dyad.bodies, strict=True)]
        if kernel is None or not set(known) <= set(which):
            return None
        second = (gz, gzs, which.index(known[0]), which.index(known[1]))
        order = (*order, *dyad.bodies)
    if len(plan.bodies) != len(order) or set(plan.bodies) != set(order):
        return None
    loads = [plan.loads[b] for b in order]
    swept = [plan.swept.get(b, NO_SWEPT_LOADS) for b in order]
    return kernel, (*first, *second, tuple(g for g, _, _ in loads),
                    tuple(gs for _, gs, _ in loads), tuple(p for _, _, p in loads),
                    tuple(sw[0] for sw in swept), tuple(sw[1] for sw in swept),
                    tuple(len(sw[2]) for sw in swept)), order


class SolvedAgain:
    """A sweep solved lean on the compiled path, solved again a block of rows at a time
    into one scratch buffer (the tables built in one pass,
    :mod:`kinetostatics.results.fastpass`): per block, each body's motion and each
    joint's reaction over the block's rows, the numbers of the full re-solve bit for bit
    (the same kernels, row by row, with the sweep's assemblies).

    ``scene``: the sweep's scene (its own positions), ``structure`` with the assemblies
    it was solved with."""

    def __init__(self, scene: Scene, structure):
        self.kernels = loaded_kernels()
        self.plan = Plan(self.kernels, scene, structure, structure.assembly)

    def blocks(self, block: int = ROWS):
        """``(lo, hi, motions, reactions)`` per block of rows ``lo`` to ``hi``: body ->
        its motion, a ``(10, hi - lo)`` array (:mod:`~kinetostatics.solver.fast.layout`),
        and joint -> :class:`~kinetostatics.solver.reactions.JointReaction`, views of
        the scratch buffer (the next block writes over them). Raises
        :class:`~kinetostatics.solver.fast.compose.Refused` where a kernel refuses a row
        (never expected: the sweep was solved by the same kernels)."""
        plan = self.plan
        x = driver_input(plan.scene)
        n = x.size
        buf = plan.buffers(min(block, n))
        for lo in range(0, n, block):
            hi = min(lo + block, n)
            plan.run(x, lo, hi, lo, buf)
            rows = cut_rows(buf, hi - lo)
            yield lo, hi, rows["m"], block_reactions(plan, plan.scene, rows)
        plan.check_swept()


def _assembled(scene: Scene, structure) -> tuple:
    """``structure`` with each dyad's assembly (chosen at the scene's first row) and the
    kernels' :class:`~kinetostatics.solver.fast.compose.Geometry`, worked out once per
    scene object (:func:`~kinetostatics.solver.memo.record_of`; the same numbers: each is
    a function of the frozen scene alone, its positions aside) for the structure
    :func:`~kinetostatics.solver.structure.analyse` gives it."""
    record = record_of(scene)
    kept = record.get("fast")
    if kept is not None and kept[0] is structure:
        return kept[1], kept[2]
    given = structure
    if len(structure.assembly) != len(structure.dyads):
        structure = replace(structure, assembly=choose_assembly(scene, structure))
    geometry = Geometry(scene, structure, structure.assembly)
    record["fast"] = (given, structure, geometry)
    return structure, geometry


def solve_run_compiled(scene: Scene, structure, kept: bool = False
                       ) -> Solved | KeptRun | None:
    """A run of stacked scenes (:meth:`~kinetostatics.solver.stack.Stacker.runs`, each
    dyad's assembly an array over the rows) on the compiled path, or None (as
    :func:`solve_compiled`; the caller asks :func:`~kinetostatics.solver.fast.choice.wanted`
    once for the whole group first). Every row is the row its scene gives alone on the
    compiled path, bit for bit: the same kernels, each number the scene's own. ``kept``:
    only what the scenes' cut Solutions keep of their run (a :class:`KeptRun`): no
    Solved and no arrays wrapped in motions and reactions (measured 2026-11-28, 1000
    four-bars x 361 in runs of 12 288 rows: some 20 ms of the compiled solve_many's
    150)."""
    if not_covered(scene) is not None:
        return None
    positions = scene.driver.positions
    kernels = wanted(positions.size)
    if kernels is None:
        return None
    try:
        plan = Plan(kernels, scene, structure, structure.assembly)
        if kept:
            return KeptRun(solve_lean(plan, positions), positions)
        return solve_full(plan, positions)
    except Refused:
        return None


class KeptRun:
    """What a stacked solve (:func:`~kinetostatics.solver.many.solve_all`) reads of a run
    solved lean on the compiled path, under a Solved's names: ``positions``, ``drive``,
    ``undefined_load`` and ``kin.dyads`` (each dyad's ``closeness2`` and ``singular``)."""

    path = "fast"

    def __init__(self, sweep, positions: np.ndarray):
        self.positions, self.drive, self.undefined_load = (positions, sweep.drive,
                                                           sweep.undefined)
        self.kin = SimpleNamespace(n=positions.size, dyads=[
            SimpleNamespace(closeness2=c, singular=f)
            for c, f in zip(sweep.closeness2, sweep.singular, strict=True)])

