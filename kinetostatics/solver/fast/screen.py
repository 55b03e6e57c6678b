"""The compiled path's part of the dead-point screen
(:mod:`~kinetostatics.solver.deadpoints`), without numba at import: its kernels
(:mod:`~kinetostatics.solver.fast.screen_kernels`,
:mod:`~kinetostatics.solver.fast.probe_kernels`) are imported once the compiled
kernels are loaded in the process. The scan of the rows, and the probes between rows
of a sweep (:func:`sweep_probe`) and of a stack (:func:`stack_probe`), each in one
compiled call."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from functools import partial

import numpy as np

from ...model.scene import GROUND, Scene
from ...model.units import DEG
from ..deadpoints import SWEEP_PROBES
from ..memo import record_of
from . import loader
from .choice import path_setting
from .geometry import driver_geometry, dyad_geometry
from .layout import DYAD_GEOMETRY, KINDS
from .screen_bound import CLEAR, known_bodies, lipschitz
from .screen_bound import cleared as bound_cleared
from .solve import kernel_trig


def compiled_scan() -> Callable | None:
    """:func:`~kinetostatics.solver.fast.screen_kernels.scan_candidates` when the compiled
    kernels are loaded and the numpy path is not asked for, else None (the numpy scan;
    numba is never loaded for it)."""
    if not loader.loaded() or path_setting() == "numpy":
        return None
    from .screen_kernels import scan_candidates
    return scan_candidates


def stack_probe(stacker, structure, ks: np.ndarray) -> Callable | None:
    """The probe ``at(positions, owner)`` of a stack's dead-point screen
    (:func:`~kinetostatics.solver.deadpoints.dead_points_stacked`) in one compiled call
    when the compiled kernels are loaded (and the numpy path is not asked for): a crank
    and one RRR dyad by :func:`crank_rrr_probe`, any other driver and chain of dyads by
    :func:`chain_probe` (each scene's geometry a column of the kernels' tables,
    :meth:`~kinetostatics.solver.stack.Stacker.table`); else None (numpy's
    :func:`~kinetostatics.solver.probes.probe_closeness`). ``ks``: each scene's assembly
    (dyads, scenes)."""
    if compiled_scan() is None:
        return None
    at = crank_rrr_probe(stacker, structure, ks)
    if at is not None:
        return at
    driver, dyads = stack_tables(stacker, structure, ks)
    return chain_probe(stacker.base.driver, driver, dyads, structure.dyads)


def stack_tables(stacker, structure, ks: np.ndarray) -> tuple:
    """A stack's driver's and dyads' geometry tables (a column per scene where its
    numbers differ, :meth:`~kinetostatics.solver.stack.Stacker.table`), each with its
    stride."""
    kept = stacker.kept.get("geometry")
    if kept is not None and kept[0] is structure and kept[1] is ks:
        # (the fused kernel's, stacked.solve_group_kept: made of the same table)
        return kept[2].driver, [g[:2] for g in kept[2].dyads]
    m = len(stacker.scenes)
    table = stacker.table(0, m, np.ones(m, dtype=np.int64), stacker.base.driver.positions,
                          trig=False)
    return driver_geometry(table), [dyad_geometry(table, d, k)
                                     for d, k in zip(structure.dyads, ks, strict=True)]


def stack_bound(stacker, structure, ks: np.ndarray) -> np.ndarray | None:
    """Each scene's L of a stack (:func:`~kinetostatics.solver.fast.screen_bound.lipschitz`
    over :func:`stack_tables`: numpy, no numba; one value where the scenes share it), or
    None where no bound is known (a sliding driver, a dyad on a body whose turning is not
    bounded)."""
    drv = stacker.base.driver
    known = known_bodies(drv, structure.dyads) if drv.kind == "R" else None
    if known is None:
        return None
    (gd, _), dyads = stack_tables(stacker, structure, ks)
    return lipschitz(True, np.asarray(gd, dtype=float), np.array(known), dyad_stack(dyads),
                     tuple(d.kind for d in structure.dyads))


def stack_clear(stacker, structure, ks: np.ndarray) -> Callable | None:
    """``clear(lo, hi, owner, m_lo, m_hi)`` of a stack's dead-point screen on the numpy
    path (:func:`~kinetostatics.solver.fast.screen_bound.cleared` with
    :func:`stack_bound`), or None where no bound is known. The compiled probes attach
    theirs themselves (:func:`chain_probe`, :func:`crank_rrr_probe`)."""
    bound = stack_bound(stacker, structure, ks)
    return None if bound is None else partial(bound_cleared, bound, int(bound.size > 1))


def dyad_stack(dyads: list) -> np.ndarray:
    """The dyads' geometry tables (each ``(table, stride)``) in one array (dyads,
    ``DYAD_GEOMETRY``, columns): the widest table's columns, a one-column table
    broadcast over them."""
    cols = max(g.shape[1] for g, _ in dyads)
    gy = np.empty((len(dyads), DYAD_GEOMETRY, cols))
    for i, (g, _) in enumerate(dyads):
        gy[i] = g
    return gy


def sweep_probe(scene: Scene, structure) -> Callable | None:
    """The probe ``at(positions, owner)`` of a sweep's dead-point screen
    (:func:`~kinetostatics.solver.deadpoints.dead_points_of_sweep`, one of its
    ``SWEEP_PROBES``) in one compiled call (:func:`chain_probe`) when ``scene`` was solved on
    the compiled path with ``structure`` (the kernels' geometry kept for it,
    ``solve._assembled``: the same tables, kept only once the compiled kernels were
    loaded); else None (numpy's probe: the numpy path, or a scene at positions given
    apart, whose record holds none). Made once per kept geometry and kept beside it in
    the scene's record (measured 2026-11-30, the shaper at 2001 rows: making it took
    about 75 of a solve's 900 us under cProfile)."""
    record = record_of(scene)
    kept = record.get("fast")
    if kept is None or kept[1] is not structure:
        return None
    made = record.get("probe")
    if made is not None and made[0] is kept:
        return made[1]
    geometry = kept[2]
    at = chain_probe(scene.driver, geometry.driver, [g[:2] for g in geometry.dyads],
                     structure.dyads)
    record["probe"] = (kept, at)
    return at


# (deadpoints cannot import the compiled path's package, which imports it: the sweep's
# compiled probe is told to it here, read whenever the kernels are loaded)
SWEEP_PROBES.append(sweep_probe)


def chain_probe(drv, driver: tuple, dyads: list, chain) -> Callable | None:
    """The probe ``at(positions, owner)`` of a driver ``drv`` and the dyads ``chain`` (each
    dyad's outer joints on the ground, the driver or an earlier dyad's bodies; else
    None) in one compiled call
    (:func:`~kinetostatics.solver.fast.probe_kernels.probe_chain`; ``driver``: the
    driver's geometry table and stride, ``dyads``: each dyad's, in the kernels' layout, a
    column per scene of a stack or one), with ``at.rounds`` (every round in one call,
    the chain's kernel of :func:`~kinetostatics.solver.fast.probe_kernels.rounds_of`;
    measured 2026-11-30, the shaper at 2001 rows: its screen about 900 -> 86 us, 1000
    shapers' probes 49 -> 23 ms, processor time at a load of 6) unless a crank's
    cos and sin in a compiled loop are not numpy's here. A crank's cos and sin are
    numpy's, the dyads closed by the compiled path's closures: m^2 the numpy probe's
    (:func:`~kinetostatics.solver.probes.probe_closeness`) but for the RTR guide's angle,
    the compiled path's (a few ulps apart)."""
    known = known_bodies(drv, chain)
    if known is None:
        return None
    gy = dyad_stack(dyads)
    gd, gds = driver
    crank = drv.kind == "R"
    kinds = tuple(d.kind for d in chain)
    args = (crank, np.ascontiguousarray(gd, dtype=float), gds, np.array(known, dtype=np.int64),
            gy, int(gy.shape[2] > 1))
    from .probe_kernels import probe_chain, rounds_of
    codes = np.array([KINDS[k] for k in kinds], dtype=np.int64)

    def at(positions: np.ndarray, owner: np.ndarray) -> tuple[list, np.ndarray]:
        x = np.ascontiguousarray(positions, dtype=float)
        c = s = x
        if crank:   # (the crank's angles as the probe's Driver makes them, numpy's cos, sin)
            angles = replace(drv, positions=x).angles
            c, s = np.cos(angles), np.sin(angles)
        m2, gone = np.empty(x.size), np.empty(x.size, dtype=bool)
        probe_chain(c, s, x, np.asarray(owner, dtype=np.int64), codes, *args, m2, gone)
        return [m2], gone
    if not crank or kernel_trig():      # (the C library's cos and sin: numpy's here)
        at.rounds = partial(_rounds, kernel=rounds_of(kinds), args=args)
    bound = lipschitz(crank, gd, args[3], gy, kinds)
    # the intervals the rows prove clear (screen_bound): not probed (measured 2026-11-30,
    # 1000 shapers x 361: all 2626 cleared, solve_many 69.5-80.6 -> 44.8-50.5 ms best;
    # 1000 slotted levers: all 2342, 41-44 -> 31-33 ms; processor time at a load of 10-12)
    if bound is not None:
        at.clear = partial(cleared, bound, int(bound.size > 1))
    return at


def cleared(bound: np.ndarray, stride: int, lo: np.ndarray, hi: np.ndarray,
             owner: np.ndarray, m_lo: np.ndarray, m_hi: np.ndarray) -> np.ndarray:
    """:func:`~kinetostatics.solver.fast.screen_bound.cleared` in one compiled call
    (:func:`~kinetostatics.solver.fast.probe_kernels.clear_rows`: the same verdicts)."""
    from .probe_kernels import clear_rows
    out = np.empty(lo.size, dtype=bool)
    clear_rows(bound, stride, np.asarray(lo, dtype=float), np.asarray(hi, dtype=float),
               np.asarray(owner, dtype=np.int64), np.asarray(m_lo, dtype=float),
               np.asarray(m_hi, dtype=float), DEG, CLEAR, out)
    return out


def crank_rrr_probe(stacker, structure, ks: np.ndarray) -> Callable | None:
    """The probe ``at(positions, owner)`` of a stack's dead-point screen
    (:func:`~kinetostatics.solver.deadpoints.dead_points_stacked`) in one compiled pass
    (:func:`~kinetostatics.solver.fast.screen_kernels.probe_rrr`) when the stack is a crank
    and one RRR dyad whose outer pivots are on the ground or the crank and the compiled
    kernels are loaded; else None (:func:`stack_probe` tells the other structures).
    The same numbers as numpy's :func:`~kinetostatics.solver.probes.probe_closeness`:
    the crank's cos and sin are numpy's, the rest the probe's operations in their
    order. ``ks``: each scene's assembly (dyads, scenes)."""
    scene = stacker.base
    drv = scene.driver
    if compiled_scan() is None or drv.kind != "R" or len(structure.dyads) != 1:
        return None
    dyad = structure.dyads[0]
    if dyad.inner.kind != "R" or any(j.kind != "R" for j in dyad.outer):
        return None
    knowns = [j.other(b) for j, b in zip(dyad.outer, dyad.bodies, strict=True)]
    driving = scene.joints[drv.joint]
    if any(k not in (GROUND, drv.body) for k in knowns) or GROUND not in driving.bodies:
        return None
    from .screen_kernels import COLUMNS, probe_rrr, rrr_gaps
    m = len(stacker.scenes)
    columns = [*stacker.ground[driving.point_on(GROUND)],
               *stacker.bodies[drv.body][3][driving.point_on(drv.body)]]
    for j, b in zip(dyad.outer, dyad.bodies, strict=True):
        k = j.other(b)
        columns += (stacker.ground[j.point_on(GROUND)] if k == GROUND
                    else stacker.bodies[k][3][j.point_on(k)])
        columns += stacker.bodies[b][3][j.point_on(b)]
    for b in dyad.bodies:
        columns += stacker.bodies[b][3][dyad.inner.point_on(b)]
    columns.append(stacker.size)
    geo = np.empty((m, COLUMNS))
    for i, x in enumerate(columns):
        geo[:, i] = x
    on_crank = np.array([k != GROUND for k in knowns])
    k = ks[0].astype(float)

    def at(positions: np.ndarray, owner: np.ndarray) -> tuple[list, np.ndarray]:
        # (the crank's angles as the probe's Driver makes them, then numpy's cos, sin)
        angles = replace(drv, positions=positions).angles
        c, s = np.cos(angles), np.sin(angles)
        m2, opened = np.empty(angles.size), np.zeros(angles.size, dtype=bool)
        if probe_rrr(c, s, owner, k, geo, on_crank, m2):
            rrr_gaps(c, s, owner, geo, on_crank, opened)    # (else none: numpy's probe)
        return [m2], opened
    if kernel_trig():       # (the C library's cos and sin are numpy's here)
        from .screen_kernels import probe_rounds
        at.rounds = partial(_rounds, kernel=probe_rounds, args=(k, geo, on_crank))
    # the intervals the rows prove clear (screen_bound, the RRR dyad's L): not probed
    bound = stack_bound(stacker, structure, ks)
    at.clear = partial(cleared, bound, int(bound.size > 1))
    return at


def _rounds(lo: np.ndarray, hi: np.ndarray, owner: np.ndarray, t: np.ndarray,
            rounds: int, *, kernel: Callable, args: tuple) -> tuple[np.ndarray, np.ndarray]:
    """Every round of the screen's probes in one compiled call (``at.rounds`` of
    :func:`crank_rrr_probe` and :func:`chain_probe`, read by
    :func:`~kinetostatics.solver.deadpoints._probe`; ``kernel``:
    :func:`~kinetostatics.solver.fast.screen_kernels.probe_rounds` or
    a chain's of :func:`~kinetostatics.solver.fast.probe_kernels.rounds_of`, ``args`` its tables):
    the smallest m^2 inside each interval (``lo``, ``hi``: driver positions, deg for a
    crank) and whether some probe could not close, the numbers of the rounds probed one
    by one (measured 2026-11-30, 1000 four-bars x 361, their 190 intervals: 0.95 ms a
    call against 1.50 round by round, processor time, best of 30 at a load of 11; most
    of it the 17 670 probes' cos and sin)."""
    n = lo.size
    best, opened = np.empty(n), np.empty(n, dtype=bool)
    scratch = n * (t.size - 2)
    kernel(np.array(lo, dtype=float), np.array(hi, dtype=float),
           np.asarray(owner, dtype=np.int64), t, DEG, *args, rounds, best, opened,
           np.empty(scratch), np.empty(scratch, dtype=bool))
    return best, opened
