"""The compiled kernels composed inside one compiled call, over tiles of rows (numba).

One call of :func:`sweep` solves rows ``lo`` to ``hi`` of a scene: per tile of
:data:`TILE` rows, the driver's motion, each dyad's motion in solving order, each body's
load resultants, each dyad's reactions in reverse order and the driver's Me/Fe (the
kernels of :mod:`~kinetostatics.solver.fast.kernels` and
:mod:`~kinetostatics.solver.fast.reaction_kernels`, each with its seed equation). A tile's
arrays stay in the processor's first caches from one kernel to the next, and no kernel
is dispatched from Python (measured 2026-11-28 on the 2-core machine, four-bar at 2e5
rows: the same kernels composed from Python over blocks of 16 384 rows cost 220-300 ns a
row, most of it waiting on memory; over blocks of 64 rows, 640 ns, most of it in the
dispatch of some ten kernels a block).

The structure is a table of numbers (:data:`OPS` columns per dyad: its kind's code and
the indices of its known bodies and of its own two bodies in the stacked motions); the
geometry of each dyad and each body's loads are tuples of arrays. Imported only by
:func:`~kinetostatics.solver.fast.loader.kernels`, after numba's cache folder is settled;
it gives the kernels' other names too.
"""

from __future__ import annotations

import math

from .jitbase import jit
from .kernels import (
    MOTION,
    crank_motion,
    rrr_motion,
    rrt_motion,
    rtr_motion,
    rtt_motion,
    slider_motion,
    trr_motion,
    trt_motion,
    ttr_motion,
)
from .layout import C1X, C1Y, CL2, D_TH, C, S
from .reaction_kernels import (
    REACTIONS,
    body_loads,
    crank_reaction,
    rrr_reactions,
    rrt_reactions,
    rtr_reactions,
    rtt_reactions,
    slider_reaction,
    swept_loads,
    trr_reactions,
    trt_reactions,
    ttr_reactions,
)

TILE = 128      # rows per tile: some 90 arrays of a four-bar's tile in 90 kB
OPS = 5         # a dyad's row of the structure table: kind, k1, k2, b1, b2


@jit
def _motion(kind, stage, lo, hi, off, g, gs, k1, k2, m1, m2, d):
    """The motion kernel of a dyad of kind code ``kind`` (layout.KINDS)."""
    if kind == 7:
        return rrr_motion(stage, lo, hi, off, g, gs, k1, k2, m1, m2, d)
    if kind == 5:
        return rrt_motion(stage, lo, hi, off, g, gs, k1, k2, m1, m2, d)
    if kind == 6:
        return trr_motion(stage, lo, hi, off, g, gs, k1, k2, m1, m2, d)
    if kind == 4:
        return trt_motion(stage, lo, hi, off, g, gs, k1, k2, m1, m2, d)
    if kind == 3:
        return rtr_motion(stage, lo, hi, off, g, gs, k1, k2, m1, m2, d)
    if kind == 1:
        return rtt_motion(stage, lo, hi, off, g, gs, k1, k2, m1, m2, d)
    return ttr_motion(stage, lo, hi, off, g, gs, k1, k2, m1, m2, d)


@jit
def _reactions(kind, lo, hi, off, g, gs, m1, m2, mk1, mk2, d, a1, a2, ak1, ak2, rr):
    """The reactions kernel of a dyad of kind code ``kind``."""
    if kind == 7:
        return rrr_reactions(lo, hi, off, g, gs, m1, m2, mk1, mk2, d, a1, a2, ak1, ak2, rr)
    if kind == 5:
        return rrt_reactions(lo, hi, off, g, gs, m1, m2, mk1, mk2, d, a1, a2, ak1, ak2, rr)
    if kind == 6:
        return trr_reactions(lo, hi, off, g, gs, m1, m2, mk1, mk2, d, a1, a2, ak1, ak2, rr)
    if kind == 4:
        return trt_reactions(lo, hi, off, g, gs, m1, m2, mk1, mk2, d, a1, a2, ak1, ak2, rr)
    if kind == 3:
        return rtr_reactions(lo, hi, off, g, gs, m1, m2, mk1, mk2, d, a1, a2, ak1, ak2, rr)
    if kind == 1:
        return rtt_reactions(lo, hi, off, g, gs, m1, m2, mk1, mk2, d, a1, a2, ak1, ak2, rr)
    return ttr_reactions(lo, hi, off, g, gs, m1, m2, mk1, mk2, d, a1, a2, ak1, ak2, rr)


@jit
def _guide_angle(d, lo, hi, off):
    """RTR: the guide angle's cos and sin (rows C1X, C1Y of the dyad's data), in a pass of
    their own between the two stages."""
    for i in range(lo, hi):
        j = i - off
        th = d[D_TH, j]
        d[C1X, j] = math.cos(th)
        d[C1Y, j] = math.sin(th)


@jit
def _tile(t0, t1, off, x, crank, dg, dgs, w, eps, drv, ops, gd, gds, gl, gls, npoint,
          gsw, gsws, nload, stats, m, a, dd, rr, out, undefined):
    """One tile of rows ``t0`` to ``t1`` (arrays at ``i - off``): the numpy path's order."""
    if crank:
        bad = crank_motion(x, t0, t1, off, dg, dgs, w, eps, m[drv])
    else:
        bad = slider_motion(x, t0, t1, off, dg, dgs, w, eps, m[drv])
    for q in range(ops.shape[0]):
        kind, k1, k2, b1, b2 = ops[q, 0], ops[q, 1], ops[q, 2], ops[q, 3], ops[q, 4]
        if kind == 3:
            _motion(kind, 0, t0, t1, off, gd[q], gds[q], m[k1], m[k2], m[b1], m[b2], dd[q])
            _guide_angle(dd[q], t0, t1, off)
        bad += _motion(kind, 1, t0, t1, off, gd[q], gds[q], m[k1], m[k2], m[b1], m[b2],
                       dd[q])
    for b in range(1, m.shape[0]):
        bad += body_loads(t0, t1, off, gl[b], gls[b], npoint[b], m[b], a[b])
        if nload[b]:
            bad += swept_loads(t0, t1, off, gsw[b], gsws[b], nload[b], m[b], a[b],
                               undefined, stats[b])
    for q in range(ops.shape[0] - 1, -1, -1):
        kind, k1, k2, b1, b2 = ops[q, 0], ops[q, 1], ops[q, 2], ops[q, 3], ops[q, 4]
        bad += _reactions(kind, t0, t1, off, gd[q], gds[q], m[b1], m[b2], m[k1], m[k2],
                          dd[q], a[b1], a[b2], a[k1], a[k2], rr[q])
    if crank:
        bad += crank_reaction(t0, t1, off, dg, dgs, m[drv], a[drv], out)
    else:
        bad += slider_reaction(t0, t1, off, dg, dgs, m[drv], a[drv], out)
    return bad


@jit
def sweep(lo, hi, lean, x, cs, sn, crank, dg, dgs, w, eps, drv, ops, gd, gds, gl, gls,
          npoint, gsw, gsws, nload, stats, m, a, dd, rr, out, undefined, drive, kept_u,
          close):
    """Rows ``lo`` to ``hi``, tile by tile; the count of rows the numpy path must judge.

    ``lean`` false: ``m``, ``a``, ``dd``, ``rr``, ``out`` and ``undefined`` hold every row
    (at ``i``), a crank's cos and sin already in its motion's rows C, S. ``lean`` true:
    they are one tile's scratch (at ``i - t0``), a crank's cos and sin read from ``cs``,
    ``sn`` (at ``i - lo``), and only Me/Fe, the undefined rows and each dyad's closeness
    to a dead centre are kept (``drive``, ``kept_u``, ``close``, at ``i``)."""
    bad = 0
    for t0 in range(lo, hi, TILE):
        t1 = min(t0 + TILE, hi)
        off = t0 if lean else 0
        if lean:
            for i in range(t0, t1):
                undefined[i - off] = False
                if crank:
                    m[drv, C, i - off] = cs[i - lo]
                    m[drv, S, i - off] = sn[i - lo]
        bad += _tile(t0, t1, off, x, crank, dg, dgs, w, eps, drv, ops, gd, gds, gl, gls,
                     npoint, gsw, gsws, nload, stats, m, a, dd, rr, out, undefined)
        if lean:
            for i in range(t0, t1):
                drive[i] = out[0, i - off]
                kept_u[i] = undefined[i - off]
            for q in range(ops.shape[0]):
                for i in range(t0, t1):
                    close[q, i] = dd[q, CL2, i - off]
    return bad


__all__ = ["MOTION", "OPS", "REACTIONS", "TILE", "body_loads", "crank_motion",
           "crank_reaction", "slider_motion", "slider_reaction", "sweep", "swept_loads"]
