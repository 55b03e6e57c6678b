"""The compiled kernels of a body's loads (seed 002 s. 2.1-2.2), row by row: the numpy
path's formulas, as :mod:`~kinetostatics.solver.fast.kernels` computes the motion (the
same conventions: rows ``lo`` to ``hi``, arrays at ``i - off``, geometry at ``i * gs``;
each kernel returns the count of rows the numpy path must judge)."""

from __future__ import annotations

import math

from .jitbase import TILE, body, jit, nonfinite, scratch, tile_in, tile_next, tile_out
from .layout import AL, AX, AY, L_I, L_M0, L_POINT, OM, VX, VY, C, S
from .layout import MOTION as BODY_ROWS


# -- loads (seed 002 s. 2.1-2.2) ----------------------------------------------------------
@jit
def body_loads(lo, hi, off, g, gs, own, npoint, m, acc):
    """A body's load resultants [Fx, Fy, M about its origin]: forces at local points,
    each with the inertia force -m_k a_k of a mass there (the cog's, eq. 2.1, or a
    concentrated mass, eq. 2.8), a couple, and the inertia couple -I_G eps (eq. 2.1).
    In tiles (jitbase.TILE): the motion in, each point load a loop over the tile's rows
    (it vectorises), the resultants out."""
    w = scratch(BODY_ROWS + 3)
    wm, wa = w[:BODY_ROWS], w[BODY_ROWS:]
    wg = scratch(g.shape[0])
    bad, last, t0 = 0, -1, lo       # (last: the scene whose geometry the tile holds)
    while t0 < hi:
        nt, last = tile_next(wg, g, gs, own, t0, hi, last)     # (one scene's rows)
        j0, t0 = t0 - off, t0 + nt
        tile_in(wm[C:AL + 1], m[C:AL + 1], j0, nt)      # (no velocities read)
        tile_in(wm[AX:AY + 1], m[AX:AY + 1], j0, nt)
        bad += tile_loads(wm, wa, wg, npoint, nt)
        tile_out(acc, wa, j0, nt)
    return bad


def tile_loads_for(width: int):
    """``tile_loads(wm, wa, wg, npoint, nt)``: a tile's load resultants ``wa``
    (:func:`body_loads`) from its body's motion ``wm`` and its geometry ``wg`` (the
    tile's scene's in each column), tiles of ``width`` rows; the count of the tile's
    first ``nt`` rows that are not finite."""
    @body
    def tile_loads(wm, wa, wg, npoint, nt):
        wa[:] = 0.0
        for q in range(npoint):
            b = 2 + L_POINT * q
            for t in range(width):
                c, s, al, om = wm[C, t], wm[S, t], wm[AL, t], wm[OM, t]
                w2 = om * om
                lx, ly = wg[b, t], wg[b + 1, t]
                rx, ry = c * lx - s * ly, s * lx + c * ly
                mk = wg[b + 4, t]
                ax = (wm[AX, t] - al * ry) - w2 * rx
                ay = (wm[AY, t] + al * rx) - w2 * ry
                px, py = wg[b + 2, t] - mk * ax, wg[b + 3, t] - mk * ay
                wa[0, t] += px
                wa[1, t] += py
                wa[2, t] += rx * py - ry * px
        bad = 0
        for t in range(width):
            wa[2, t] = wa[2, t] + wg[L_M0, t] - wg[L_I, t] * wm[AL, t]
            f = nonfinite((wa[0, t], wa[1, t], wa[2, t]))
            bad += f if t < nt else 0
        return bad
    return tile_loads


tile_loads = tile_loads_for(TILE)


@jit
def swept_loads(lo, hi, off, g, gs, own, nload, m, acc, undefined, stats):
    """Loads whose rows are told by the whole sweep (the numpy path's
    ``applied_loads``), added to a body's resultants: a ``resist`` force (kind 1) of
    magnitude R against its point's velocity, a force (kind 2) acting ``when =
    "resisting"`` (where its power is negative). A row stands still where the speed (the
    power's magnitude) is at most ``thr`` (1e-9 of the mechanism's own scale): the force
    is zero there and the row is undefined. ``stats[q, e]`` gathers the largest speed and
    the smallest speed of a moving row of scene ``e`` (a stack's: each row's scene
    ``own[i]``; one scene: 0): the caller checks that each sweep's top does not move its
    scene's threshold over a row."""
    bad = 0
    es = 1 if stats.shape[1] > 1 else 0
    for i in range(lo, hi):
        j = i - off
        bad += swept_row(j, own[i * gs], own[i * es], j, g, nload, m, acc, undefined, stats)
    return bad


@body
def swept_row(j, r, e, u, g, nload, m, acc, undefined, stats):
    """:func:`swept_loads` at row ``j`` of ``m`` and ``acc`` (geometry column ``r``, the
    row of scene ``e`` of ``stats``, its flag ``undefined[u]``); 1 if not finite."""
    c, s = m[C, j], m[S, j]
    om = m[OM, j]
    for q in range(nload):
        rx, ry, fx, fy, x, still = swept_force(g, 7 * q, r, c, s, om, m[VX, j], m[VY, j])
        stats[q, e, 0], stats[q, e, 1] = swept_stats(stats[q, e, 0], stats[q, e, 1], x, still)
        if still:
            undefined[u] = True
        acc[0, j] += fx
        acc[1, j] += fy
        acc[2, j] += rx * fy - ry * fx
    return nonfinite((acc[0, j], acc[1, j], acc[2, j]))


@body
def swept_force(g, b, r, c, s, om, vx0, vy0):
    """A swept load's ``(rx, ry, fx, fy, x, still)`` at a row (its geometry from row
    ``b`` of column ``r`` of ``g``; the body's cos and sin ``c``, ``s``, its angular
    velocity ``om`` and its origin's velocity ``vx0``, ``vy0``): the arm of its point,
    the force, the speed (the power's magnitude) ``x`` and whether the row stands still
    (:func:`swept_loads`)."""
    lx, ly = g[b, r], g[b + 1, r]
    rx, ry = c * lx - s * ly, s * lx + c * ly
    vx, vy = vx0 - om * ry, vy0 + om * rx
    thr = g[b + 6, r]
    if g[b + 2, r] == 1.0:
        x = math.hypot(vx, vy)
        still = x <= thr
        fx = 0.0 if still else -g[b + 3, r] * vx / x
        fy = 0.0 if still else -g[b + 3, r] * vy / x
    else:
        fx, fy = g[b + 4, r], g[b + 5, r]
        power = fx * vx + fy * vy
        x = abs(power)
        still = x <= thr
        if still or not power < 0.0:
            fx = fy = 0.0
    return rx, ry, fx, fy, x, still


@body
def swept_stats(top, least, x, still):
    """A swept load's statistics ``(top, least)`` after a row of speed ``x``: the largest
    speed (a NaN kept) and the smallest of a moving row (:func:`swept_loads`)."""
    if x > top or not x == x:
        top = x
    if not still and x < least:
        least = x
    return top, least
