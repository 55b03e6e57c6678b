"""What a fused kernel does with a tile once its bodies' motions are worked out, shared
by the kernels of :mod:`~kinetostatics.solver.fast.guide_kernels` (tiles of
:data:`~kinetostatics.solver.fast.jitbase.TILE` rows; ``tile_swept`` by
:mod:`~kinetostatics.solver.fast.fused_kernels` too): the swept loads of a body over the
tile's rows, a dyad's reactions and what its outer joints load its known bodies with,
the crank's Me (seed 002 eqs 2.47-2.48) and the write-out of what a long sweep keeps.
Each helper does the composed kernels' operations in their order
(:mod:`~kinetostatics.solver.fast.reaction_kernels`): the same numbers, bit for bit.
Inlined by LLVM (``body``); the kernels module's rules hold here.
"""

from __future__ import annotations

import numpy as np

from .jitbase import TILE, body, nonfinite
from .layout import CL2, OM, P_GROUND, PARAM, VX, VY, C, S
from .load_kernels import swept_force, swept_stats
from .reaction_kernels import crank_moment, reaction_row, swept_row


@body
def tile_swept(lo, t0, nt, own, gs, es, gw, nw, wm, wa, undefined, st):
    """A body's swept loads (``resist``, ``when = "resisting"``: :func:`swept_row`)
    over the ``nt`` rows of the tile that starts at row ``t0`` of rows from ``lo``
    (``own``: each row's scene, its geometry at ``own[i * gs]``, its statistics at
    ``own[i * es]``), added to the tile's resultants ``wa``; the count of rows that are
    not finite."""
    if gs == 0 and es == 0:
        return _tile_swept_one(lo, t0, nt, gw, nw, wm, wa, undefined, st)
    bad = 0
    for t in range(nt):
        i = t0 + t
        # (one scene's: column 0, a constant once inlined with gs = es = 0)
        r = own[i * gs] if gs != 0 else 0
        e = own[i * es] if es != 0 else 0
        bad += swept_row(t, r, e, i - lo, gw, nw, wm, wa, undefined, st)
    return bad


@body
def _tile_swept_one(lo, t0, nt, gw, nw, wm, wa, undefined, st):
    """:func:`tile_swept` of one scene (its geometry in column 0, its statistics in row
    0): per load, its forces over the tile's rows in a loop of their own (it vectorises
    but for ``resist``'s hypot), then its statistics and undefined rows, row after row
    (:func:`swept_row`'s operations per row, in its order: the same numbers; measured
    2026-11-30, the shaper's ram, a million rows in tiles of 64: 4.8 ns a row against
    7.6 row by row)."""
    xs = np.empty(wm.shape[1])
    for q in range(nw):
        for t in range(nt):
            rx, ry, fx, fy, xs[t], _ = swept_force(gw, 7 * q, 0, wm[C, t], wm[S, t], wm[OM, t],
                                                   wm[VX, t], wm[VY, t])
            wa[0, t] += fx
            wa[1, t] += fy
            wa[2, t] += rx * fy - ry * fx
        top, least, thr = st[q, 0, 0], st[q, 0, 1], gw[7 * q + 6, 0]
        for t in range(nt):
            still = xs[t] <= thr
            top, least = swept_stats(top, least, xs[t], still)
            if still:
                undefined[t0 + t - lo] = True
        st[q, 0, 0], st[q, 0, 1] = top, least
    bad = 0
    for t in range(nt):
        bad += nonfinite((wa[0, t], wa[1, t], wa[2, t]))
    return bad


@body
def tile_reactions(rot1, rot2, inner_r, nt, wg, wm1, wm2, wk1, wk2, wd, wa1, wa2, wak1, wak2,
                   wr):
    """A dyad's reactions over a tile (:func:`reaction_row`, seed 002 s. 2.3) into
    ``wr``, its bodies' resultants ``wa1``, ``wa2`` and what its outer joints load the
    known bodies with (``wak1``, ``wak2``, zeroed first); the count of the tile's first
    ``nt`` rows that are not finite."""
    wak1[:] = 0.0
    wak2[:] = 0.0
    bad = 0
    for t in range(TILE):
        f = reaction_row(rot1, rot2, inner_r, t, t, wg, wm1, wm2, wk1, wk2, wd, wa1, wa2,
                         wak1, wak2, wr)
        bad += f if t < nt else 0
    return bad


@body
def add_rows(wa, wak):
    """A tile's three resultant rows ``wak`` added to ``wa`` (every column, in order)."""
    for f in range(3):
        src, dst = wak[f], wa[f]        # (rows as 1-d views, as ``tile_add``)
        for t in range(TILE):
            dst[t] += src[t]


@body
def copy_rows(wk, wm):
    """A tile's motion ``wm`` copied into ``wk`` (every row and column, in order). Loops,
    not numba's slice assignment: that one compiles a message naming both shapes for a
    mismatch that cannot happen here (measured 2026-11-29, a cold cache: the shaper's
    kernel 40 s of processor time with three such copies, 8.7 s of it theirs)."""
    for f in range(wm.shape[0]):
        src, dst = wm[f], wk[f]
        for t in range(TILE):
            dst[t] = src[t]


@body
def known_loads(wg, wa1, wa2, wak1, wak2):
    """What a dyad's outer joints load their known bodies with (``wak1``, ``wak2``, a
    tile's) added to those bodies' resultants ``wa1``, ``wa2`` in order, unless the
    known body is the ground (as the composed reactions add them, ``tile_add``)."""
    if wg[P_GROUND, 0] == 0.0:
        add_rows(wa1, wak1)
    if wg[PARAM + P_GROUND, 0] == 0.0:
        add_rows(wa2, wak2)


@body
def tile_moment(wgd, wdrv, wad, wr, nt):
    """The crank's Me over a tile (:func:`crank_moment`) into row 0 of ``wr``; the count
    of the tile's first ``nt`` rows where Me or the crank's resultant force is not
    finite."""
    bad = 0
    for t in range(TILE):
        me = crank_moment(t, t, wgd, wdrv, wad)
        wr[0, t] = me
        f = nonfinite((me, wad[0, t], wad[1, t]))
        bad += f if t < nt else 0
    return bad


def tile_kept_for(width: int):
    """``tile_kept(j0, nt, whole, wr, wd, drive, close)``: what a sweep keeps of a tile
    of ``width`` rows, at ``j0`` on: Me (row 0 of ``wr``) and the dyad's closeness to a
    dead centre (``wd``'s); the whole tile where ``whole`` (the arrays reach past it: a
    loop of a constant count, vectorised), else ``nt`` rows. (Measured 2026-11-29, 1000
    four-bars x 361 in solve_many's fused kernel: the nt-row loop 0.35 ms of 11.7 a
    call.)"""
    @body
    def tile_kept(j0, nt, whole, wr, wd, drive, close):
        if whole:
            for t in range(width):
                drive[j0 + t] = wr[0, t]
                close[j0 + t] = wd[CL2, t]
        else:
            for t in range(nt):
                drive[j0 + t] = wr[0, t]
                close[j0 + t] = wd[CL2, t]
    return tile_kept


tile_kept = tile_kept_for(TILE)         # (tiles of TILE rows: the RTR guide's kernels)

__all__ = ["add_rows", "copy_rows", "known_loads", "tile_kept", "tile_kept_for", "tile_moment",
           "tile_reactions", "tile_swept"]
