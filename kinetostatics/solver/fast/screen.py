"""The compiled path's part of the dead-point screen
(:mod:`~kinetostatics.solver.deadpoints`), without numba at import: its kernels
(:mod:`~kinetostatics.solver.fast.screen_kernels`) are imported once the compiled
kernels are loaded in the process."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from functools import partial

import numpy as np

from ...model.scene import GROUND
from ...model.units import DEG
from . import loader
from .choice import path_setting
from .solve import kernel_trig


def compiled_scan() -> Callable | None:
    """:func:`~kinetostatics.solver.fast.screen_kernels.scan_candidates` when the compiled
    kernels are loaded and the numpy path is not asked for, else None (the numpy scan;
    numba is never loaded for it)."""
    if not loader.loaded() or path_setting() == "numpy":
        return None
    from .screen_kernels import scan_candidates
    return scan_candidates


def rrr_probe(stacker, structure, ks: np.ndarray) -> Callable | None:
    """The probe ``at(positions, owner)`` of a stack's dead-point screen
    (:func:`~kinetostatics.solver.deadpoints.dead_points_stacked`) in one compiled pass
    (:func:`~kinetostatics.solver.fast.screen_kernels.probe_rrr`) when the stack is a crank
    and one RRR dyad whose outer pivots are on the ground or the crank and the compiled
    kernels are loaded; else None (numpy's :func:`~kinetostatics.solver.probes.probe_closeness`).
    The same numbers: the crank's cos and sin are numpy's, the rest the probe's
    operations in their order. ``ks``: each scene's assembly (dyads, scenes)."""
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
        at.rounds = partial(_rounds, k=k, geo=geo, on_crank=on_crank)
    return at


def _rounds(lo: np.ndarray, hi: np.ndarray, owner: np.ndarray, t: np.ndarray,
            rounds: int, *, k: np.ndarray, geo: np.ndarray, on_crank: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray]:
    """Every round of the screen's probes of a crank and one RRR dyad in one compiled
    call (:func:`~kinetostatics.solver.fast.screen_kernels.probe_rounds`; ``at.rounds``
    of :func:`rrr_probe`, read by :func:`~kinetostatics.solver.deadpoints._probe`): the
    smallest m^2 inside each interval (``lo``, ``hi``: driver positions, deg) and whether
    some probe could not close, the numbers of the rounds probed one by one (measured
    2026-11-30, 1000 four-bars x 361, their 190 intervals: 0.95 ms a call against 1.50
    round by round, processor time, best of 30 at a load of 11; most of it the 17 670
    probes' cos and sin)."""
    from .screen_kernels import probe_rounds
    n = lo.size
    best, opened = np.empty(n), np.empty(n, dtype=bool)
    scratch = n * (t.size - 2)
    probe_rounds(np.array(lo, dtype=float), np.array(hi, dtype=float),
                 np.asarray(owner, dtype=np.int64), t, DEG, k, geo, on_crank, rounds, best,
                 opened, np.empty(scratch), np.empty(scratch, dtype=bool))
    return best, opened
